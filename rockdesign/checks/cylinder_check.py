"""``check`` for a cylinder (thesis Ch. 5): the statistical verdict over a suite of record pairs, and
whether a planar analysis would have sufficed.

For every record pair of the suite (default ``p695-farfield-pairs``, scaled to the resultant PGA of
``[excitation]``, Table 5.4's scaling):

* the 3D model of the project (undamped or damped) gives θ_max/α, quasi-impacts and overturning
  (θ reaching θ_ot = overturn_tilt·α);
* the planar Housner model of the same cylinder (a rocking block of equal inertia,
  λ = (3 + cos²α)/12, c_r of Eq 5.41) runs along each component alone — the planar analysis an engineer
  would make; it overturns when θ_max ≥ α (the static capacity of the non-spinning cylinder);
* Polyakov's rule 2 per component, SD_max/2B, is reported as information only.

Verdict (as the planar check): the one-sided 95 % upper bound of the 3D P(overturn) (Clopper–Pearson)
must not exceed ``[analysis] overturn_probability_limit``.  The comparison reports P(overturn) and
θ_max of the planar model (worse of the two components) against the 3D model.
"""
from __future__ import annotations

import dataclasses
import math
import statistics as pystats

import numpy as np

from ..errors import ProjectError
from ..kernel_cache import sources_digest
from ..units import QuantityParseError, parse_quantity
from .statistics import overturning_probability

EXCITATION_KEYS = ("design_pga", "suites", "scale", "records_dir")
SCALE_METHODS = ("resultant_pga", "factor")
DEFAULT_SUITE = "p695-farfield-pairs"


def cylinder_excitation(project) -> tuple[list[str], str, float]:
    """(suites of pairs, scaling method, target [m/s²] or factor) from ``[excitation]`` of a cylinder project.

    ``scale = { method = "resultant_pga", target = "0.3 g" }`` or ``{ method = "factor", value = 1.2 }``;
    ``design_pga`` alone means resultant-PGA scaling to it.  Default: resultant PGA 1.5 g tan α (the thesis's
    Table 5.4 level relative to uplift)."""
    from ..motions.pairs import PAIR_SUITES
    raw = project.excitation_raw or {}
    file, g = project.path, project.system.g
    for key in raw:
        if key not in EXCITATION_KEYS:
            raise ProjectError("unknown key for a cylinder", file=file, key=f"excitation.{key}",
                               expected="one of " + ", ".join(EXCITATION_KEYS), found=f"'{key}'")
    suites = raw.get("suites", [DEFAULT_SUITE])
    if not isinstance(suites, list) or not all(isinstance(s, str) for s in suites) or not suites:
        raise ProjectError("wrong type", file=file, key="excitation.suites", expected="a list of suite names",
                           found=repr(suites))
    for s in suites:
        if s not in PAIR_SUITES:
            raise ProjectError("a cylinder needs suites of record pairs", file=file, key="excitation.suites",
                               expected="one of " + ", ".join(PAIR_SUITES), found=repr(s))

    def accel(value, key):
        try:
            v = parse_quantity(value, "acceleration", gravity=g)
        except QuantityParseError as exc:
            raise ProjectError(f"expects {exc}", file=file, key=key) from None
        if not v > 0:
            raise ProjectError("must be positive", file=file, key=key, expected="an acceleration > 0", found=repr(value))
        return v

    if "scale" in raw:
        rule = raw["scale"]
        if not isinstance(rule, dict) or rule.get("method") not in SCALE_METHODS:
            raise ProjectError("invalid scaling for a cylinder", file=file, key="excitation.scale",
                               expected='{ method = "resultant_pga", target = "0.3 g" } or { method = "factor", '
                                        'value = 1.2 }', found=repr(rule))
        if rule["method"] == "resultant_pga":
            if set(rule) != {"method", "target"}:
                raise ProjectError("resultant_pga scaling takes a target", file=file, key="excitation.scale",
                                   expected='{ method = "resultant_pga", target = "0.3 g" }', found=repr(rule))
            return suites, "resultant_pga", accel(rule["target"], "excitation.scale.target")
        value = rule.get("value")
        if set(rule) != {"method", "value"} or isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not value > 0:
            raise ProjectError("factor scaling takes a positive value", file=file, key="excitation.scale",
                               expected='{ method = "factor", value = 1.2 }', found=repr(rule))
        return suites, "factor", float(value)
    if "design_pga" in raw:
        return suites, "resultant_pga", accel(raw["design_pga"], "excitation.design_pga")
    return suites, "resultant_pga", 1.5 * g * project.system.tan_alpha


def planar_block(cyl):
    """The planar Housner model of the cylinder: a block with λ = I1*/R² = (3 + cos²α)/12 (Eq 5.20) and
    c_r of Eq 5.41."""
    from ..cylinder.quantities import restitution_root
    from ..systems import Column, RockingSystem
    lam = (3.0 + math.cos(cyl.alpha) ** 2) / 12.0
    system = RockingSystem(f"{cyl.name} (planar)", "column", Column(cyl.half_height, cyl.base_radius, cyl.mass, lam),
                           g=cyl.g)
    return system.with_restitution(restitution_root(cyl.alpha) ** 2)


def _planar_component(block, samples, dt, a):
    from ..dynamics.simulate import simulate
    from ..motions.motion import record_motion
    motion = record_motion("component", samples, dt)
    r = simulate(block, motion, model="exact", rtol=a.rtol, atol=a.atol, t_end=motion.duration + a.free_vibration,
                 overturn="static", rest_velocity=a.rest_velocity)
    return {"theta_max_over_alpha": r.theta_max_over_alpha, "overturned": bool(r.overturned), "impacts": r.impacts}


def run_cylinder_check(project, progress=None) -> dict:
    """The cylinder check: results as a JSON-ready dict (records, summary, checks, verdict)."""
    from ..cylinder.quantities import quantities_json
    from ..cylinder.engine import simulate_cylinder
    from ..motions.pairs import suite_pairs
    from ..motions.spectra import sd_max_of_samples
    cyl, a = project.system, project.analysis
    suites, method, target = cylinder_excitation(project)
    pairs = [(s, p) for s in suites for p in suite_pairs(s, gravity=cyl.g)]
    block = planar_block(cyl)
    records = []
    for i, (suite, pair) in enumerate(pairs):
        factor = target / pair.resultant_pga if method == "resultant_pga" else target
        scaled = pair.scaled(factor)
        r = simulate_cylinder(cyl, scaled, free_vibration=a.free_vibration, rtol=a.rtol, atol=a.atol,
                              rest_velocity=a.rest_velocity)
        row = {"id": pair.meta.get("id", pair.name), "suite": suite, "event": pair.meta.get("event"),
               "station": pair.meta.get("station"), "scale": factor, "resultant_pga": scaled.resultant_pga,
               "theta_max_over_alpha": r.theta_max / cyl.alpha, "overturned": r.overturned,
               "overturn_mode": r.overturn_mode, "quasi_impacts": r.quasi_impacts, "uplift_time": r.uplift_time,
               "status": r.status}
        if cyl.damped:
            row["min_contact_force_over_weight"] = r.min_contact_force_over_weight
        for comp, samples in (("x", pair.x), ("y", pair.y)):
            accel = factor * samples
            sd, _ = sd_max_of_samples(accel, pair.dt, a.sdmax_damping, a.sdmax_band)
            row[f"polyakov_ratio_{comp}"] = sd / (2.0 * cyl.base_radius)
            planar = _planar_component(block, accel, pair.dt, a)
            row[f"planar_{comp}"] = planar
        row["planar_theta_max_over_alpha"] = max(row["planar_x"]["theta_max_over_alpha"],
                                                 row["planar_y"]["theta_max_over_alpha"])
        row["planar_overturned"] = row["planar_x"]["overturned"] or row["planar_y"]["overturned"]
        records.append(row)
        if progress is not None:
            progress("cylinder and planar analyses", i + 1, len(pairs))
    n = len(records)
    k3 = sum(r["overturned"] for r in records)
    kp = sum(r["planar_overturned"] for r in records)
    p3, lo3, hi3 = overturning_probability(k3, n, 0.90)
    pp, lop, hip = overturning_probability(kp, n, 0.90)
    unconservative = [r["id"] for r in records if r["overturned"] and not r["planar_overturned"]]
    survived = [r for r in records if not r["overturned"] and not r["planar_overturned"]]
    summary = {
        "n_records": n, "n_overturned": k3, "p_overturn": p3, "p_overturn_ci90": [lo3, hi3],
        "median_theta_max_over_alpha": pystats.median(r["theta_max_over_alpha"] for r in records),
        "total_quasi_impacts": sum(r["quasi_impacts"] for r in records),
        "planar": {"n_overturned": kp, "p_overturn": pp, "p_overturn_ci90": [lop, hip],
                   "median_theta_max_over_alpha": pystats.median(r["planar_theta_max_over_alpha"] for r in records),
                   "criterion": "θ_max ≥ α along either component (Housner block of equal inertia, c_r Eq 5.41)"},
        "difference_p_overturn": p3 - pp,
        "n_planar_unconservative": len(unconservative), "planar_unconservative_records": unconservative,
        "median_theta_ratio_3d_over_planar": pystats.median(
            r["theta_max_over_alpha"] / r["planar_theta_max_over_alpha"] for r in survived
            if r["planar_theta_max_over_alpha"] > 0) if survived else None,
        "max_polyakov_ratio": max(max(r["polyakov_ratio_x"], r["polyakov_ratio_y"]) for r in records),
        "scaling": {"method": method, "target" if method == "resultant_pga" else "value": target},
    }
    limit = a.overturn_probability_limit
    planar_ok = len(unconservative) == 0 and kp >= k3
    checks = [
        {"name": f"RHA (3D): P(overturn) ≤ {100 * limit:g} % at 95 % confidence (θ reaching θ_ot = "
                 f"{cyl.overturn_tilt:g}α counts as overturning)",
         "utilisation": hi3 / limit if limit > 0 else math.inf, "passed": hi3 <= limit, "governs_verdict": True,
         "detail": f"{k3} of {n} record pairs overturn; P = {p3:.3g}, 90 % interval [{lo3:.3g}, {hi3:.3g}]"},
        {"name": "Does a planar analysis suffice? (Housner along each component)",
         "utilisation": (k3 / kp) if kp else (math.inf if k3 else 0.0), "passed": planar_ok, "governs_verdict": False,
         "detail": f"planar: {kp} of {n} overturn (P = {pp:.3g}); 3D − planar ΔP = {p3 - pp:+.3g}; "
                   f"{len(unconservative)} pair(s) overturn in 3D but not in the planar analysis"},
        {"name": "Polyakov rule 2 per component: median SD_max < 2B (information)",
         "utilisation": float(np.median([max(r["polyakov_ratio_x"], r["polyakov_ratio_y"]) for r in records])),
         "passed": True, "governs_verdict": False, "detail": "informative only: Polyakov's rule is planar"},
    ]
    verdict = "PASS" if all(c["passed"] for c in checks if c["governs_verdict"]) else "FAIL"
    cylinder = {"height": 2.0 * cyl.half_height, "diameter": 2.0 * cyl.base_radius, "slenderness": cyl.tan_alpha,
                "mass": cyl.mass, "contact": cyl.contact, "overturn_tilt": cyl.overturn_tilt, "g": cyl.g}
    if cyl.damped:
        cylinder.update(contact_frequency=cyl.contact_frequency, contact_damping=cyl.contact_damping)
    settings = {"rtol": a.rtol, "atol": a.atol, "rest_velocity": a.rest_velocity, "free_vibration": a.free_vibration,
                "overturn_probability_limit": limit, "sd_max_damping": a.sdmax_damping,
                "sd_max_band": list(a.sdmax_band)}
    return {"project": {"name": project.name, "file": project.path, "system": "cylinder", "contact": cyl.contact,
                        "kernels_sha256": sources_digest()},
            "cylinder": cylinder, "units": CYLINDER_UNITS, "suites": suites, "settings": settings,
            "quantities": quantities_json(project)["quantities"],
            "model": {"chosen": "cylinder-" + ("damped" if cyl.damped else "undamped"),
                      "reason": "[cylinder] project: the 3D rocking and wobbling model of thesis Ch. 5"},
            "records": records, "summary": summary, "checks": checks, "verdict": verdict}


GOVERNING_PAIRS = 2
"""θ(t)/orbit histories kept for the report: the pairs with the largest 3D θ_max/α."""

FIGURE_FILES = ("cylinder_vs_planar.png", "wobbling_period.png")
"""The figures written beside results.json (besides the report, which embeds its own)."""


@dataclasses.dataclass
class CylinderCheckResult:
    """The check of a cylinder project: ``as_json()`` is results.json (``check --json``).

    ``histories`` maps the ids of the governing pairs (largest 3D θ_max/α) to
    ``(CylinderResponse, scaled MotionPair)`` for the report's θ(t)/orbit figures.
    """

    project: object
    data: dict
    histories: dict = dataclasses.field(default_factory=dict)

    @property
    def verdict(self) -> str:
        return self.data["verdict"]

    @property
    def records(self) -> list[dict]:
        return self.data["records"]

    @property
    def checks(self) -> list[dict]:
        return self.data["checks"]

    @property
    def summary(self) -> dict:
        return self.data["summary"]

    def as_json(self) -> dict:
        return self.data


MAX_HISTORIES = 8
"""At most this many time histories in the report (every overturning pair up to it)."""


def governing_ids(data: dict, n: int = GOVERNING_PAIRS) -> list[str]:
    """Ids of the pairs whose histories the report shows: every overturning pair (up to MAX_HISTORIES),
    at least ``n`` pairs, by decreasing 3D θ_max/α (overturned pairs first; stable order)."""
    rows = sorted(data["records"], key=lambda r: (not r["overturned"], -r["theta_max_over_alpha"]))
    count = min(max(n, sum(r["overturned"] for r in rows)), MAX_HISTORIES)
    return [r["id"] for r in rows[:count]]


def cylinder_check(project, progress=None) -> CylinderCheckResult:
    """:func:`run_cylinder_check` plus the histories of the governing pairs (re-analysed: the engine is
    deterministic, so they are the histories behind the rows of results.json)."""
    from ..cylinder.engine import simulate_cylinder
    from ..motions.pairs import load_pair
    data = run_cylinder_check(project, progress=progress)
    cyl, a = project.system, project.analysis
    rows = {r["id"]: r for r in data["records"]}
    histories = {}
    for rid in governing_ids(data):
        pair = load_pair(rid, gravity=cyl.g).scaled(rows[rid]["scale"])
        histories[rid] = (simulate_cylinder(cyl, pair, free_vibration=a.free_vibration, rtol=a.rtol, atol=a.atol,
                                            rest_velocity=a.rest_velocity), pair)
    return CylinderCheckResult(project, data, histories)


CYLINDER_UNITS = {"height": "m", "diameter": "m", "slenderness": "-", "mass": "kg", "overturn_tilt": "-",
                  "g": "m/s^2", "contact_frequency": "rad/s", "contact_damping": "-", "scale": "-",
                  "resultant_pga": "m/s^2", "theta_max_over_alpha": "-", "uplift_time": "s", "rtol": "-",
                  "atol": "-", "rest_velocity": "rad/s", "free_vibration": "s", "sd_max_band": "s"}
"""Units of the numbers of results.json's ``cylinder``, ``records`` and ``settings`` (SI)."""

CSV_COLUMNS = ["id", "suite", "event", "station", "scale", "resultant_pga", "theta_max_over_alpha", "overturned",
               "overturn_mode", "quasi_impacts", "uplift_time", "planar_theta_max_over_alpha", "planar_overturned",
               "polyakov_ratio_x", "polyakov_ratio_y", "min_contact_force_over_weight"]


def write_cylinder_results(data: dict, out_dir) -> None:
    """results.json, results.csv and a figure (3D against planar θ_max/α per record pair) into ``out_dir``."""
    import csv
    import json
    from pathlib import Path

    from ..plots import save
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / "results.json").write_text(json.dumps(data, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    with open(out_dir / "results.csv", "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(CSV_COLUMNS)
        for row in data["records"]:
            w.writerow(["" if row.get(c) is None else row.get(c) for c in CSV_COLUMNS])
    save(comparison_figure(data), out_dir / "cylinder_vs_planar.png")


def comparison_figure(data: dict, cap: float = 2.0):
    """3D θ_max/α against the planar Housner θ_max/α (worse component) per record pair; planar values
    beyond ``cap`` (the planar block overturned) are drawn at ``cap``."""
    from ..plots import STYLE, plt
    tilt = data.get("cylinder", {}).get("overturn_tilt")
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(5.0, 4.6))
        x = np.minimum([r["planar_theta_max_over_alpha"] for r in data["records"]], cap)
        y = np.array([r["theta_max_over_alpha"] for r in data["records"]])
        ot = np.array([r["overturned"] for r in data["records"]])
        top = max(cap, float(np.max(y)) * 1.05)
        ax.plot([0, cap], [0, cap], color="0.6", lw=0.8)
        ax.axvline(1.0, color="0.3", lw=0.7, ls=":", label=r"planar overturning ($\theta_{max}$ = α)")
        if tilt:
            ax.axhline(tilt, color="C3", lw=0.7, ls="--", label=r"$\theta_{ot}$ (3D overturning)")
        ax.scatter(x[~ot], y[~ot], s=14, color="C0", label="3D survives")
        ax.scatter(x[ot], y[ot], s=18, color="C3", marker="x", label=r"3D overturns ($\theta_{ot}$)")
        ax.set_xlim(0, cap * 1.03)
        ax.set_ylim(0, top * 1.03)
        ax.set_xlabel(f"planar Housner $\\theta_{{max}}$/α (worse component; drawn at {cap:g} beyond)")
        ax.set_ylabel(r"3D cylinder $\theta_{max}$/α")
        ax.legend(fontsize=7, loc="upper left")
        return fig
