"""``rockdesign check``: the Polyakov design check over record suites (the product's main job).

project → design quantities → records (suites, scaling) → model selection → suite RHA →
Polyakov's rule and Fig 4.9 classes → overturning margins → statistics and c_r sensitivity →
checks and verdict.  :func:`run_check` returns a :class:`CheckResult`; its :meth:`~CheckResult.as_json`
is ``results.json`` (CONTRACT §3, SI units).
"""
from __future__ import annotations

import math
import statistics as pystats
from dataclasses import dataclass, field

import numpy as np

from .. import __version__
from ..design.quantities import design_quantities
from ..errors import ProjectError
from ..motions.config import default_excitation, parse_excitation, resolve_motions
from ..motions.spectra import sd_max
from ..project import Project
from .margins import SCAN_AFTER_FIRST, SCAN_RATIO, Margin, overturning_margins
from .polyakov import CLASS_MEANING, CLASSES, PolyakovRule, classify
from .runner import RunSummary, run_jobs
from .selection import ModelSelection, select_model
from .statistics import empirical_cdf, overturning_probability

GOVERNING_HISTORIES = 3


@dataclass
class RecordOutcome:
    """One record of the suite: input, Polyakov's prediction, RHA response, class and margin.

    Units: ``scale`` [-] (factor on the record as recorded), ``pga`` [m/s²] (scaled), ``sd_max`` [m] and
    ``sd_period`` [s] (peak elastic displacement spectrum in the rule's band), ``polyakov_ratio`` [-]
    (SD_max/capacity), ``polyakov_scale`` [-]; ``run`` holds θ_max/α, θ_max/θc, u_B,max [m], impacts,
    overturned; ``klass`` is the Fig 4.9 class; ``margin`` the overturning scales found (or None).
    """

    id: str
    suite: str | None
    meta: dict
    scale: float
    motion: object
    pga: float
    sd_max: float
    sd_period: float
    polyakov_ratio: float
    polyakov_scale: float
    run: RunSummary
    klass: str
    margin: Margin | None
    sensitivity_flip: bool = False

    def as_json(self) -> dict:
        r = self.run
        m = self.margin
        return {
            "id": self.id,
            "suite": self.suite,
            "event": self.meta.get("event"),
            "station": self.meta.get("station"),
            "rsn": self.meta.get("rsn"),
            "component": self.meta.get("component"),
            "scale": self.scale,
            "pga": self.pga,
            "sd_max": self.sd_max,
            "sd_max_period": self.sd_period,
            "polyakov_ratio": self.polyakov_ratio,
            "theta_max_over_alpha": r.theta_max_over_alpha,
            "theta_max_over_theta_c": r.theta_max_over_theta_c,
            "u_B_max": r.u_B_max,
            "u_B_max_over_2B": r.u_B_max_over_capacity,
            "impacts": r.impacts,
            "uplift_time": r.uplift_time,
            "time_uplifted": r.time_uplifted,
            "overturned": r.overturned,
            "overturn_mode": r.overturn_mode,
            "impacts_before_overturn": r.impacts_before_overturn,
            "class": self.klass,
            "overturn_scale": None if m is None else m.overturn_scale,
            "overturn_intervals": None if m is None else [list(iv) for iv in m.intervals],
            "margin_scanned_up_to": None if m is None else m.scanned_up_to,
            "polyakov_scale": self.polyakov_scale,
            "verdict_flips_with_restitution": self.sensitivity_flip,
            "status": r.status,
        }


@dataclass
class CheckResult:
    """A design check: everything the report and results.json need (SI units throughout).

    ``verdict`` "PASS" | "FAIL"; ``records`` one :class:`RecordOutcome` per record; ``checks`` the
    criteria with utilisation [-] and result; ``statistics`` the suite summary (P(overturn) with its
    bound, classes, margins); ``quantities`` the design quantities (value + unit); ``as_json()`` is
    results.json (= ``rockdesign check --json``).
    """

    fragility = None   # the suite's fragility (CONTRACT §5.3) once computed; a class default until then

    project: Project
    quantities: dict
    rule: PolyakovRule
    selection: ModelSelection
    records: list[RecordOutcome]
    missing: list
    scale_description: str
    default_excitation_used: bool
    suites: list[str]
    statistics: dict
    checks: list[dict]
    verdict: str
    histories: dict = field(default_factory=dict)
    sensitivity: dict = field(default_factory=dict)
    settings: dict = field(default_factory=dict)

    def as_json(self) -> dict:
        p = self.project
        s = p.system
        return {
            "project": {"name": p.name, "file": p.path, "sha256": p.sha256, "kind": s.kind,
                        **{k: v for k, v in p.info.items() if k != "name"}, "tool_version": __version__,
                        "warnings": list(p.warnings)},
            "quantities": {k: q.as_json() for k, q in self.quantities.items()},
            "model": {"chosen": self.selection.chosen.label, "structure": self.selection.chosen.structure,
                      "equations": self.selection.chosen.equations, "reason": self.selection.reason,
                      "structure_reason": self.selection.structure_reason,
                      "equations_reason": self.selection.equations_reason,
                      "full_model": self.selection.full.label, "rejected": self.selection.rejected,
                      "verification": self.selection.verification,
                      "max_difference_theta_over_theta_c": self.selection.max_difference,
                      "verdict_changes": self.selection.verdict_changes,
                      "equivalent_block": self.settings.get("equivalent_block")},
            "excitation": {"suites": self.suites, "scaling": self.scale_description,
                           "default_used": self.default_excitation_used,
                           "missing": [{"id": i, "reason": r, "suite": su} for i, r, su in self.missing],
                           "sd_max_damping": self.rule.damping, "sd_max_band": list(self.rule.band),
                           "capacity": self.rule.capacity},
            "records": [r.as_json() for r in self.records],
            "summary": self.statistics,
            "sensitivity": self.sensitivity,
            "verdict": self.verdict,
            "checks": self.checks,
            "settings": self.settings,
        }


def _excitation(project: Project):
    g = project.system.g
    if project.excitation_raw is None:
        raise ProjectError("the design check needs an excitation", file=project.path, key="excitation.design_pga",
                           expected="[excitation] with design_pga = \"0.3 g\" (the default runs the FEMA P695 "
                                    "far-field suite scaled to it) or suites/records with a scale rule",
                           found="no [excitation] table")
    spec = parse_excitation(project.excitation_raw, file=project.path, gravity=g)
    if not project.excitation_raw.get("suites") and not project.excitation_raw.get("records"):
        if spec.design_pga is None:
            raise ProjectError("missing required value", file=project.path, key="excitation.design_pga",
                               expected="design_pga (the FEMA P695 far-field suite is scaled to it)", found="none")
        spec = default_excitation(spec.design_pga, file=project.path) if spec.scale is None else spec
    return spec


def run_check(project: Project, *, records_dir: str | None = None, margins: bool = True, progress=None,
              executor=None) -> CheckResult:
    """Run the design check of a project (see module docstring).

    ``progress(stage, done, total)`` is called as work proceeds (the CLI draws rich progress bars).
    ``executor``: run the analyses on the chunked executor of :mod:`rockdesign.spectra.executor`
    (e.g. a dask.distributed cluster); default in-process on all cores.  Results are identical.
    """
    system = project.system
    a = project.analysis
    q = design_quantities(system)
    capacity = q["u_capacity"].value
    rule = PolyakovRule(capacity, a.sdmax_damping, tuple(a.sdmax_band))
    spec = _excitation(project)
    resolved = resolve_motions(spec, gravity=system.g, uplift_acceleration=q["uplift_acceleration"].value,
                               records_dir=records_dir)
    if not resolved.records:
        raise ProjectError("no record of the excitation could be found", file=project.path, key="excitation",
                           expected="at least one available record",
                           found="; ".join(f"{i}: {r}" for i, r, _ in resolved.missing) or "an empty suite")
    motions = [r.motion for r in resolved.records]
    n = len(motions)

    def stage(name, total):
        if progress is None:
            return None
        progress(name, 0, total)
        return lambda done: progress(name, done, total)

    tick = stage("elastic spectra (SD_max)", n)
    sds = []
    for k, m in enumerate(motions):
        sds.append(sd_max(m, rule.damping, rule.band))
        if tick:
            tick(k + 1)
    run_kw = dict(rtol=a.rtol, atol=a.atol, free_vibration=a.free_vibration, criterion=a.overturn,
                  rest_velocity=a.rest_velocity, executor=executor)
    selection, runs = select_model(system, a, motions, run_kw, progress=stage("suite analysis (RHA)", n))
    chosen = selection.chosen

    # incremental analyses need verdicts to 1 %, not histories to 1e-10: a looser tolerance there
    scan_kw = dict(run_kw, rtol=max(a.rtol, a.scan_rtol))
    margin_list: list[Margin | None] = [None] * n
    if margins:
        up = q["uplift_acceleration"].value
        uplift_factors = [up / m.pga if m.pga > 0 else a.margin_max_scale for m in motions]
        total = 0
        from .margins import _scan_grid
        for f_up in uplift_factors:
            total += len(_scan_grid(min(max(0.5 * f_up, 1e-3), a.margin_max_scale / 4), a.margin_max_scale,
                                    SCAN_RATIO))
        margin_list = overturning_margins(system, chosen, motions, uplift_factors=uplift_factors,
                                          max_scale=a.margin_max_scale, precision=a.margin_precision,
                                          progress=stage("overturning margins (incremental RHA)", total), **scan_kw)

    # sensitivity of the verdicts to c_r ± variation
    tick = stage(f"restitution sensitivity (c_r ± {100 * a.restitution_variation:g} %)", 2 * n)
    flips = [False] * n
    sens = {}
    for j, factor in enumerate((1.0 - a.restitution_variation, 1.0 + a.restitution_variation)):
        res = run_jobs(system, chosen, motions, [1.0] * n, restitution_factor=factor, energy_stop=True,
                       progress=(lambda d, j=j: tick(j * n + d)) if tick else None, **run_kw)
        # (same tolerance as the nominal suite run: a verdict flip must come from c_r, not from rtol)
        changed = [i for i in range(n) if res[i].overturned != runs[i].overturned]
        for i in changed:
            flips[i] = True
        sens[f"{factor:.4g}"] = {"restitution_factor": factor, "verdict_changes": len(changed),
                                 "records": [resolved.records[i].id for i in changed],
                                 "n_overturned": sum(r.overturned for r in res)}
    sensitivity = {"variation": a.restitution_variation, "runs": sens,
                   "verdict_flips": sum(flips), "note": "c_r ≤ 1 (capped)"}

    outcomes = []
    for i, (rec, (sd, t_sd), run) in enumerate(zip(resolved.records, sds, runs)):
        ratio = rule.utilisation(sd)
        outcomes.append(RecordOutcome(rec.id, rec.suite, rec.meta, rec.scale, rec.motion, rec.motion.pga, sd, t_sd,
                                      ratio, rule.predicted_scale(sd), run,
                                      classify(ratio, run.u_B_max_over_capacity, run.overturned), margin_list[i],
                                      flips[i]))
    stats = _statistics(outcomes, a, margins)
    checks, verdict = _checks(outcomes, q, a, stats, sensitivity)
    histories = {}
    from ..dynamics.simulate import simulate
    governing = sorted(outcomes, key=lambda o: -min(o.run.theta_max_over_theta_c, 2.0))[:GOVERNING_HISTORIES]
    for o in governing:
        histories[o.id] = simulate(system, o.motion, model=chosen.equations, structure=chosen.structure, rtol=a.rtol,
                                   atol=a.atol, t_end=o.motion.duration + a.free_vibration, overturn=a.overturn,
                                   rest_velocity=a.rest_velocity)
    settings = {"rtol": a.rtol, "atol": a.atol, "overturn_criterion": a.overturn, "g": system.g,
                "rest_velocity": a.rest_velocity, "free_vibration": a.free_vibration,
                "linearization_tolerance": a.linearization_tolerance, "margin_precision": a.margin_precision,
                "margin_max_scale": a.margin_max_scale, "margin_scan_ratio": SCAN_RATIO,
                "margin_scan_after_first": SCAN_AFTER_FIRST,
                "margin_rtol": max(a.rtol, a.scan_rtol),
                "overturn_probability_limit": a.overturn_probability_limit,
                "rigid_superstructure_ratio": a.rigid_superstructure_ratio,
                "scale_basis": "overturn_scale and polyakov_scale multiply the design-level (scaled) record"}
    from ..design.quantities import at_critical_curvature
    if at_critical_curvature(system) and "R_hat" in q:
        settings["equivalent_block"] = (
            f"ρ = ρc: to linear order and up to the first impact the columns respond like flat-based blocks of "
            f"size R̂ = {q['R_hat'].value:.4g} m ({q['R_hat'].equation}); not used as a substitute model because "
            "impacts differ (c_r) — the curved column itself is analysed (SPEC §6)")
    # the engine's error against a closed form at the tolerance used (report appendix)
    from ..bench.accuracy import engine_accuracy
    acc = engine_accuracy(a.rtol, a.atol)
    settings["engine_accuracy"] = {k: v for k, v in acc.items() if k != "seconds"}
    return CheckResult(project, q, rule, selection, outcomes, resolved.missing, resolved.scale_description,
                       resolved.default_used or spec.default_used, resolved.suites, stats, checks, verdict, histories,
                       sensitivity, settings)


def _statistics(outcomes: list[RecordOutcome], a, with_margins: bool) -> dict:
    n = len(outcomes)
    k = sum(o.run.overturned for o in outcomes)
    k_dyn = sum(o.run.overturn_mode == "dynamic" for o in outcomes)
    p, lo, hi = overturning_probability(k, n, 0.90)
    classes = {c: sum(o.klass == c for o in outcomes) for c in CLASSES}
    x, f = empirical_cdf([o.run.theta_max_over_alpha for o in outcomes])
    out = {
        "n_records": n,
        "n_overturned": k,
        "n_overturned_dynamic": k_dyn,
        "n_exceeded_capacity": sum(o.run.overturn_mode != "none" for o in outcomes),
        "overturn_criterion": a.overturn,
        "n_false_negative": classes["b"],
        "classes": classes,
        "class_meaning": CLASS_MEANING,
        "p_overturn": p,
        "p_overturn_ci90": [lo, hi],
        "theta_max_over_alpha_ecdf": {"x": [float(v) for v in x], "F": [float(v) for v in f]},
        "median_theta_max_over_alpha": float(np.median(x)) if n else None,
        "max_polyakov_ratio": max(o.polyakov_ratio for o in outcomes),
        "max_theta_max_over_theta_c": max(o.run.theta_max_over_theta_c for o in outcomes),
    }
    if with_margins:
        vals = [o.margin.overturn_scale if o.margin.overturn_scale is not None else math.inf for o in outcomes]
        finite = [v for v in vals if math.isfinite(v)]
        censored = len(vals) - len(finite)
        med = pystats.median(vals)
        out.update({
            "median_margin": None if math.isinf(med) else med,
            "median_margin_censored": bool(math.isinf(med)),
            "min_margin": min(finite) if finite else None,
            "n_margin_above_scan": censored,
            "n_margin_below_design": sum(1 for v in finite if v < 1.0),
            "margin_scan_max": a.margin_max_scale,
            "median_polyakov_scale": pystats.median(o.polyakov_scale for o in outcomes),
            "n_polyakov_unconservative_margin": sum(
                1 for o in outcomes if o.margin.overturn_scale is not None and o.margin.overturn_scale < o.polyakov_scale),
            "n_nonmonotonic": sum(1 for o in outcomes if len(o.margin.intervals) > 1 or (
                o.margin.intervals and o.margin.intervals[0][1] is not None)),
        })
    else:
        out["median_margin"] = None
    return out


def _checks(outcomes: list[RecordOutcome], q: dict, a, stats: dict, sensitivity: dict) -> tuple[list[dict], str]:
    """The checks, sorted by utilisation (governing first), and the verdict.

    The verdict is statistical (thesis Ch. 6–7: single histories are not predictable): the one-sided
    95 % upper bound of P(overturn) over the suite (the upper end of the 90 % interval) must not exceed
    the limit (default 10 %; with 44 records this admits no overturning record).  Polyakov's rules are
    evaluated and compared but do not decide — the RHA does.
    """
    crit = a.overturn
    n = len(outcomes)
    n_ot = stats["n_overturned"]
    upper = stats["p_overturn_ci90"][1]
    limit = a.overturn_probability_limit
    sds = sorted(o.polyakov_ratio for o in outcomes)
    median_sd = float(np.median(sds))
    checks = [
        {"name": f"RHA: P(overturn) ≤ {100 * limit:g} % at 95 % confidence ({crit} criterion: "
                 + ("θ_max ≥ θc" if crit == "static" else "|θ| = π/2") + " counts as overturning)",
         "utilisation": upper / limit if limit > 0 else math.inf,
         "passed": upper <= limit, "governs_verdict": True,
         "detail": f"{n_ot} of {n} records overturn; P = {stats['p_overturn']:.3g}, 90 % interval "
                   f"[{stats['p_overturn_ci90'][0]:.3g}, {upper:.3g}]"},
        {"name": "RHA: largest θ_max/θc of the suite",
         "utilisation": max(o.run.theta_max_over_theta_c for o in outcomes),
         "passed": n_ot == 0, "governs_verdict": False,
         "detail": "informative: every record below capacity" if n_ot == 0 else
                   f"informative: {n_ot} record(s) reach the capacity θc"},
        {"name": "Polyakov rule 2: median SD_max < u_B(θc)",
         "utilisation": median_sd, "passed": median_sd < 1.0, "governs_verdict": False,
         "detail": f"informative: {sum(x >= 1 for x in sds)} of {n} records with SD_max ≥ capacity; "
                   f"{stats['n_false_negative']} false negative(s) (class b)"},
        {"name": f"Robustness: verdicts unchanged for c_r ± {100 * a.restitution_variation:g} %",
         "utilisation": sensitivity["verdict_flips"] / n, "passed": sensitivity["verdict_flips"] == 0,
         "governs_verdict": False,
         "detail": f"informative: {sensitivity['verdict_flips']} record verdict(s) flip"},
    ]
    margins = [(o.id, o.margin.overturn_scale) for o in outcomes if o.margin is not None and
               o.margin.overturn_scale is not None]
    if any(o.margin is not None for o in outcomes):
        below = sorted((m, i) for i, m in margins if m < 1.0)
        checks.append({
            "name": "RHA incremental: no overturning at any amplitude up to the design level",
            "utilisation": (1.0 / min(m for _, m in margins)) if margins else 0.0,
            "passed": not below, "governs_verdict": False,
            "detail": ("informative: every record's smallest overturning factor is above 1" if not below else
                       "informative: overturning below the design level (responses are not monotonic in "
                       "amplitude): " + ", ".join(f"{i} at {m:.3g}" for m, i in below))})
    if "omega_s_over_p" in q:
        ratio = q["omega_s_over_p"].value
        checks.append({"name": f"Polyakov rule 1: rigid superstructure (ω_s/p ≥ {a.rigid_superstructure_ratio:g})",
                       "utilisation": a.rigid_superstructure_ratio / ratio,
                       "passed": ratio >= a.rigid_superstructure_ratio, "governs_verdict": False,
                       "detail": "informative: the flexible superstructure is analysed (2DOF) when this fails"})
    checks.sort(key=lambda c: (not c["governs_verdict"], -c["utilisation"]))
    verdict = "PASS" if all(c["passed"] for c in checks if c["governs_verdict"]) else "FAIL"
    return checks, verdict
