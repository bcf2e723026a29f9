"""``check`` for a cylinder (thesis Ch. 5): the statistical verdict over a suite of record pairs, and
whether a planar analysis would have sufficed — judged like every other check.

For every record pair of the suite (default ``p695-farfield-pairs``, scaled as ``[excitation]`` says,
Table 5.4's scaling):

* the 3D model of the project (undamped or damped) gives θ_max/α, quasi-impacts and overturning
  (θ reaching θ_ot = overturn_tilt·α);
* the planar Housner model of the same cylinder (a rocking block of equal inertia,
  λ = (3 + cos²α)/12, c_r of Eq 5.41) runs along each component alone — the planar analysis an engineer
  would make; it overturns when θ_max ≥ α (the static capacity of the non-spinning cylinder);
* Polyakov's rule 2 per component, SD_max/2B, is reported as information only.

Each pair is one typed :class:`PairOutcome` (one ground motion: ``ground_motion`` is the pair id).  The
verdict is :func:`~rockdesign.acceptance.criteria.decide` over the criteria of :func:`cylinder_criteria`
(:mod:`rockdesign.cylinder.criteria`), under the project's acceptance rule as for every kind: every
analysis completed; the ASCE 7-22 §16.4.1.1 count of pairs overturning at the design level and at some
intensity up to it; and the FEMA P695 collapse margin at the risk category's target, from each pair's
first overturning intensity of the resultant PGA (each pair scanned up to ``[analysis]
margin_max_scale``, :mod:`rockdesign.cylinder.margins`; the fragility of
:mod:`rockdesign.acceptance.fragility`, Ŝ_CT counted per FEMA P695 Ch. 6).  ``--no-margins`` skips the
scan and the verdict says so.  Its robustness: a seeded perturbation ensemble (``[analysis]
ensemble_size`` runs of the whole suite, each pair's amplitude × (1 ± 0.1 %), tolerances one decade
tighter).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from .. import __version__
from .batch import PairRun, PairRunner
from .engine import simulate_cylinder
from .quantities import cylinder_quantities, restitution_root, wobbling_curve
from ..planar.dynamics.simulate import simulate
from ..jsonable import SerialisedOnce
from ..kernel_cache import sources_digest
from ..motions.motion import record_motion
from .pairs import suite_pairs
from ..motions.scaling_report import headline_basis
from ..motions.spectra import sd_max_of_samples
from ..planar.system import Column, RockingSystem
from ..acceptance.summary import acceptance_summary
from ..acceptance.rule import (AcceptanceRule, acceptance_rule, count_rule, minimum_records,
                         require_suite_size)
from ..acceptance.criteria import CheckContext, decide, evaluate_criteria
from .criteria import cylinder_criteria
from .margins import pair_fragility, pair_margins, pair_need
from ..acceptance.collapse_margin import collapse_margin
from ..acceptance.scans import SCAN_RATIO, Margin
from .ensemble import suite_ensembles
from ..acceptance.statistics import overturning_probability

GOVERNING_PAIRS = 2
"""θ(t)/orbit histories kept for the report: the pairs with the largest 3D θ_max/α."""



def planar_block(cyl) -> RockingSystem:
    """The planar Housner model of the cylinder: a block with λ = I1*/R² = (3 + cos²α)/12 (Eq 5.20) and
    c_r of Eq 5.41."""
    lam = (3.0 + math.cos(cyl.alpha) ** 2) / 12.0
    system = RockingSystem(f"{cyl.name} (planar)", "column", Column(cyl.half_height, cyl.base_radius, cyl.mass, lam),
                           g=cyl.g)
    return system.with_restitution(restitution_root(cyl.alpha) ** 2)


@dataclasses.dataclass
class PairOutcome:
    """One record pair of the suite — one ground motion — with its 3D run, the planar runs along each
    component and Polyakov's ratio per component.

    Units: ``scale`` [-] (factor on the pair as recorded), ``resultant_pga`` [m/s²] (scaled); the planar
    dicts hold θ_max/α [-], overturned, impacts.
    """

    id: str
    suite: str
    meta: dict
    scale: float
    resultant_pga: float
    run: PairRun
    planar_x: dict
    planar_y: dict
    polyakov_ratio_x: float
    polyakov_ratio_y: float
    damped: bool = False
    ensemble_fraction: float | None = None
    outcome_robust: bool | None = None
    margin: Margin | None = None  # overturning factors at and below the design level (checks/cylinder_margins.py)
    klass: str = ""               # (Fig 4.9 classes are planar)

    @property
    def ground_motion(self) -> str:
        """The ground motion this outcome belongs to: for a cylinder, the record pair itself."""
        return self.id

    @property
    def polyakov_ratio(self) -> float:
        """SD_max/2B of the worse component [-] (information only)."""
        return max(self.polyakov_ratio_x, self.polyakov_ratio_y)

    @property
    def planar_theta_max_over_alpha(self) -> float | None:
        """θ_max/α of the worse planar component [-] (None: the planar runs were skipped, design grid)."""
        if self.planar_x is None:
            return None
        return max(self.planar_x["theta_max_over_alpha"], self.planar_y["theta_max_over_alpha"])

    @property
    def planar_overturned(self) -> bool | None:
        if self.planar_x is None:
            return None
        return self.planar_x["overturned"] or self.planar_y["overturned"]

    def as_json(self) -> dict:
        r = self.run
        row = {"id": self.id, "ground_motion": self.ground_motion, "suite": self.suite,
               "event": self.meta.get("event"), "station": self.meta.get("station"), "scale": self.scale,
               "resultant_pga": self.resultant_pga, "theta_max_over_alpha": r.theta_max_over_alpha,
               "overturned": r.overturned, "overturn_mode": r.overturn_mode, "quasi_impacts": r.quasi_impacts,
               "uplift_time": r.uplift_time, "status": r.engine_status}
        if self.damped:
            row["min_contact_force_over_weight"] = r.min_contact_force_over_weight
        row.update(polyakov_ratio_x=self.polyakov_ratio_x, planar_x=self.planar_x,
                   polyakov_ratio_y=self.polyakov_ratio_y, planar_y=self.planar_y,
                   planar_theta_max_over_alpha=self.planar_theta_max_over_alpha,
                   planar_overturned=self.planar_overturned, theta_max_over_theta_ot=r.response_ratio,
                   analysis_failed=r.status != "completed", ensemble_overturn_fraction=self.ensemble_fraction,
                   outcome_robust=self.outcome_robust)
        m = self.margin
        row.update(overturn_scale=None if m is None else m.overturn_scale,
                   overturn_intervals=None if m is None else [list(iv) for iv in m.intervals],
                   margin_scanned_up_to=None if m is None else m.scanned_up_to)
        return row


def _slow_notes(progress):
    """``note(pair id, text)`` printing one line per slow pair (the first slow run of each pair) through the
    progress display's ``note``, or None without one."""
    say = getattr(progress, "note", None)
    if say is None:
        return None
    seen = set()

    def note(name, text):
        if name not in seen:
            seen.add(name)
            say(f"slow 3D analysis, {name}: {text}")
    return note


def _planar_component(block, samples, dt, a) -> dict:
    motion = record_motion("component", samples, dt)
    r = simulate(block, motion, model="exact", rtol=a.rtol, atol=a.atol, t_end=motion.duration + a.free_vibration,
                 overturn="static", rest_velocity=a.rest_velocity)
    return {"theta_max_over_alpha": r.theta_max_over_alpha, "overturned": bool(r.overturned), "impacts": r.impacts}


def _median(values) -> float | None:
    """The median, None for no values (a suite where nothing rocks has no ratio to take the median of)."""
    values = list(values)
    return float(np.median(values)) if values else None


@dataclasses.dataclass
class CylinderCheckResult(SerialisedOnce):
    """The check of a cylinder project: ``as_json()`` is results.json (``check --json``), with the sections
    of a planar check (project, quantities, model, excitation, records, summary, sensitivity, verdict,
    verdict_reason, verdict_robust, failed_records, checks, settings, fragility, collapse_margin,
    ensemble) and the cylinder's own (cylinder, units, suites).

    ``histories`` maps the ids of the governing pairs (largest 3D θ_max/α) to
    ``(CylinderResponse, scaled MotionPair)`` for the report's θ(t)/orbit figures.
    """

    project: object
    records: list[PairOutcome]
    summary: dict
    checks: list[dict]
    verdict: str
    verdict_reason: str
    verdict_robust: bool
    governing_check: str | None
    ensemble: dict | None
    acceptance: dict | None = None
    fragility: dict | None = None          # acceptance/fragility.py on the pairs' resultant PGA (docs/fragility.md)
    collapse_margin: dict | None = None    # acceptance/collapse_margin.py
    histories: dict = dataclasses.field(default_factory=dict)
    decided_at_design_level: bool | None = None   # verdict_only (design grid): the incremental scan was not needed
    quantities: dict = dataclasses.field(default_factory=dict)     # cylinder_quantities, computed once by the check
    figure_data: dict = dataclasses.field(default_factory=dict)    # the report's wobbling curve (Fig 5.2), not in JSON

    @property
    def statistics(self) -> dict:
        return self.summary

    @property
    def failed_records(self) -> list[PairOutcome]:
        return [o for o in self.records if o.run.status != "completed"]

    def serialise(self) -> dict:
        """results.json (``as_json()``: built once, when the check is complete)."""
        p, cyl, a = self.project, self.project.system, self.project.analysis
        e = p.excitation
        cylinder = {"height": 2.0 * cyl.half_height, "diameter": 2.0 * cyl.base_radius, "slenderness": cyl.tan_alpha,
                    "mass": cyl.mass, "contact": cyl.contact, "overturn_tilt": cyl.overturn_tilt, "g": cyl.g}
        if cyl.damped:
            cylinder.update(contact_frequency=cyl.contact_frequency, contact_damping=cyl.contact_damping)
        settings = {"rtol": a.rtol, "atol": a.atol, "rest_velocity": a.rest_velocity,
                    "free_vibration": a.free_vibration, "overturn_probability_limit": a.overturn_probability_limit,
                    "sd_max_damping": a.sdmax_damping, "sd_max_band": list(a.sdmax_band),
                    "margin_precision": a.margin_precision, "margin_max_scale": a.margin_max_scale,
                    "margin_scan_ratio": SCAN_RATIO, "margin_rtol": max(a.rtol, a.scan_rtol),
                    "scale_basis": "overturn_scale multiplies the design-level (scaled) record pair"}
        quantities = {k: q.as_json() for k, q in self.quantities.items()}
        return {"project": {"name": p.name, "file": p.path, "system": "cylinder", "contact": cyl.contact,
                            "kind": "cylinder", "sha256": p.sha256, "kernels_sha256": sources_digest(),
                            **{k: v for k, v in p.info.items() if k != "name"}, "tool_version": __version__,
                            "warnings": list(p.warnings)},
                "cylinder": cylinder, "units": CYLINDER_UNITS, "suites": list(e.suites), "settings": settings,
                "quantities": quantities,
                "model": {"chosen": "cylinder-" + ("damped" if cyl.damped else "undamped"),
                          "reason": "[cylinder] project: the 3D rocking and wobbling model of thesis Ch. 5"},
                "excitation": {"suites": list(e.suites), "scaling": e.scaling_block(self.records, cyl.g),
                               "default_used": e.default_used, "missing": [], "record_warnings": []},
                "records": [o.as_json() for o in self.records], "summary": self.summary,
                "sensitivity": dict(SENSITIVITY),
                "checks": self.checks, "verdict": self.verdict, "verdict_reason": self.verdict_reason,
                "verdict_robust": self.verdict_robust,
                "failed_records": [{"id": o.id, "status": o.run.engine_status} for o in self.failed_records],
                "fragility": self.fragility, "collapse_margin": self.collapse_margin, "ensemble": self.ensemble,
                "acceptance": self.acceptance}


SENSITIVITY = {"variation": None, "runs": {}, "verdict_flips": 0,
               "note": "no c_r ± variation for a cylinder under record pairs: the 3D model has no impact law "
                       "(quasi-impacts are resolved by the step control, docs/cylinder.md); its robustness is "
                       "the perturbation ensemble"}
"""results.json ``sensitivity`` of a cylinder check (the section of a planar check, saying why it is empty)."""


def _summary(records: list[PairOutcome], e, ensemble: dict | None, planar_run: bool = True) -> dict:
    valid = [o for o in records if o.run.status == "completed"]
    n = len(valid)
    k3 = sum(o.run.overturned for o in valid)
    p3, lo3, hi3 = overturning_probability(k3, n, 0.90)
    out = {
        "n_records": n, "n_overturned": k3, "p_overturn": p3, "p_overturn_ci90": [lo3, hi3],
        "median_theta_max_over_alpha": _median(o.run.theta_max_over_alpha for o in valid),
        "total_quasi_impacts": sum(o.run.quasi_impacts for o in valid),
        "planar": None, "difference_p_overturn": None, "n_planar_unconservative": None,
        "planar_unconservative_records": None, "median_theta_ratio_3d_over_planar": None,
        "max_polyakov_ratio": max((o.polyakov_ratio for o in valid), default=None),
        "scaling": e.as_json(),
        "overturn_criterion": "θ reaching θ_ot",
        "n_failed": len(records) - n,
        "p_overturn_ensemble": None if ensemble is None else ensemble["p_overturn"],
    }
    if planar_run:        # (the design grid skips the planar runs: information only)
        kp = sum(o.planar_overturned for o in valid)
        pp, lop, hip = overturning_probability(kp, n, 0.90)
        unconservative = [o.id for o in valid if o.run.overturned and not o.planar_overturned]
        survived = [o for o in valid if not o.run.overturned and not o.planar_overturned]
        out.update({
            "planar": {"n_overturned": kp, "p_overturn": pp, "p_overturn_ci90": [lop, hip],
                       "median_theta_max_over_alpha": _median(o.planar_theta_max_over_alpha for o in valid),
                       "criterion": "θ_max ≥ α along either component (Housner block of equal inertia, c_r Eq 5.41)"},
            "difference_p_overturn": p3 - pp,
            "n_planar_unconservative": len(unconservative), "planar_unconservative_records": unconservative,
            "median_theta_ratio_3d_over_planar": _median(
                o.run.theta_max_over_alpha / o.planar_theta_max_over_alpha for o in survived
                if o.planar_theta_max_over_alpha > 0)})
    return out


def cylinder_rule(analysis) -> AcceptanceRule:
    """The rule that decides a cylinder's verdict (CONTRACT §6.1), the same as every kind's: the project's
    acceptance rule (``[analysis] risk_category``, ``acceptance``) over the record pairs, each pair one
    ground motion: under ``asce7`` the ASCE 7-22 §16.4.1.1 count (at the design level and on each pair's
    first overturning intensity) and the FEMA P695 collapse margin at the category's target decide."""
    return acceptance_rule(analysis)


@dataclasses.dataclass(frozen=True)
class SuitePairs:
    """The record pairs of a cylinder's excitation as its check analyses them (the ``records`` hook of
    :func:`run_cylinder_check`): read and scaled once, e.g. for every variant of a design grid that shares
    the excitation (:func:`suite_pairs_key`).

    Units: ``factors`` [-] (on each pair as recorded), ``accel`` the scaled components [m/s²],
    ``sd_max`` SD_max [m] of each scaled component (the ``[analysis]`` damping and band).
    """

    pairs: tuple            # ((suite, MotionPair as recorded), ...)
    factors: tuple[float, ...]
    accel: tuple            # ((x, y) scaled samples, ...)
    sd_max: tuple           # ((SD_max x, SD_max y), ...)


def suite_pairs_key(project) -> str:
    """Which projects share their :class:`SuitePairs`: the same typed excitation (suites, scaling rule and
    target), g and SD_max settings — a variant that changes the geometry keeps them, unless the default
    excitation (1.5 g tan α, Table 5.4) ties the target to its slenderness."""
    a = project.analysis
    return repr((project.excitation, project.system.g, a.sdmax_damping, tuple(a.sdmax_band)))


def suite_pair_records(project) -> SuitePairs:
    """The :class:`SuitePairs` of a cylinder project (the suites of ``[excitation]``, scaled as it says);
    a suite too small for the acceptance rule raises a :class:`~rockdesign.errors.ProjectError` first."""
    cyl, a, e = project.system, project.analysis, project.excitation
    pairs = tuple((s, p) for s in e.suites for p in suite_pairs(s, gravity=cyl.g))
    require_suite_size(cylinder_rule(a), len(pairs), len(pairs), e.suites, file=getattr(project, "path", None),
                       key="excitation")
    factors = tuple(e.factor(p.resultant_pga) for _, p in pairs)
    accel = tuple((f * p.x, f * p.y) for (_, p), f in zip(pairs, factors))
    sd = tuple(tuple(sd_max_of_samples(c, p.dt, a.sdmax_damping, a.sdmax_band)[0] for c in xy)
               for (_, p), xy in zip(pairs, accel))
    return SuitePairs(pairs, factors, accel, sd)


def decided_at_design_level(rule, outcomes: list[PairOutcome]) -> bool:
    """True when the design-level runs alone already make the verdict FAIL (SPEC §15): an analysis
    failed, or the design-level rule fails (the §16.4.1.1 count, or the binomial bound); the incremental
    scan can only add a failing criterion, never remove one."""
    if any(o.run.status != "completed" for o in outcomes):
        return True
    return not count_rule(rule, outcomes, {o.id for o in outcomes if o.run.overturned})[0]


def run_cylinder_check(project, progress=None, margins: bool = True, *, records: SuitePairs | None = None,
                       verdict_only: bool = False, executor=None) -> CylinderCheckResult:
    """The cylinder check (see module docstring): typed outcomes, the criteria and the one verdict.
    ``margins``: scan each pair below the design level for overturning (the incremental criterion).

    Hooks of the design grid (:mod:`rockdesign.design_space.grid`): ``records`` — the
    :class:`SuitePairs` of :func:`suite_pair_records`, read and scaled once for many variants;
    ``verdict_only`` — compute only what the verdict's word and the design table need: no planar runs
    along the components and no perturbation ensemble (informative and robustness criteria), and no
    incremental scan when the design-level runs already decide FAIL (:func:`decided_at_design_level`).
    ``executor``: where the 3D analyses run, a batch per stage (:class:`~rockdesign.cylinder.batch.PairRunner`;
    None: this process); the runs, and so the verdict, are the same.
    """
    cyl, a, e = project.system, project.analysis, project.excitation
    sp = suite_pair_records(project) if records is None else records
    pairs = sp.pairs
    rule = cylinder_rule(a)
    # the acceptance rule's suite size, before any analysis (a record pair is one ground motion)
    require_suite_size(rule, len(pairs), len(pairs), e.suites, file=getattr(project, "path", None),
                       key="excitation")
    block = planar_block(cyl)
    runner = PairRunner(cyl, a, executor=executor, note=_slow_notes(progress))
    scaled = [pair.scaled(factor) for (_, pair), factor in zip(pairs, sp.factors)]
    stage = "cylinder analyses" if verdict_only else "cylinder and planar analyses"
    runs = runner([(p,) for p in scaled], None if progress is None else
                  lambda k: progress(stage, k if verdict_only else k // 2, len(pairs)))
    records = []
    for i, ((suite, pair), factor) in enumerate(zip(pairs, sp.factors)):
        planar = {"x": None, "y": None}
        if not verdict_only:
            for comp, accel in zip(("x", "y"), sp.accel[i]):
                planar[comp] = _planar_component(block, accel, pair.dt, a)
                runner.count(1)
            if progress is not None:
                progress(stage, (len(pairs) + i + 1) // 2, len(pairs))
        ratios = [sd / (2.0 * cyl.base_radius) for sd in sp.sd_max[i]]
        records.append(PairOutcome(pair.meta.get("id", pair.name), suite, pair.meta, factor, scaled[i].resultant_pga,
                                   runs[i], planar["x"], planar["y"], ratios[0], ratios[1], cyl.damped))
    decided = verdict_only and decided_at_design_level(rule, records)
    need = pair_need(rule, records, decided) if verdict_only and margins else None
    flip_scans = None
    if (margins and not decided) or need is not None:
        found = pair_margins(cyl, scaled, [o.run for o in records], a, runner, progress, need=need)
        if decided:         # a decided FAIL: scanned below the design level for its distance to the flip alone
            flip_scans = found
        else:
            for o, m in zip(records, found):
                o.margin = m
    margins = margins and not decided
    runner.note = _slow_notes(progress)          # (a pair slow in the scans is noted again in the ensembles)
    ens = None if verdict_only else suite_ensembles(runner, [p for _, p in pairs], sp.factors,
                                                    [o.run for o in records], a, progress)
    if ens is not None:
        for i, o in enumerate(records):
            o.ensemble_fraction, o.outcome_robust = float(ens["fractions"][i]), bool(ens["robust"][i])
    summary = _summary(records, e, ens, planar_run=not verdict_only)
    summary["min_records_for_bound"] = minimum_records(a.overturn_probability_limit)
    summary["min_margin"] = min((o.margin.overturn_scale for o in records
                                 if o.margin is not None and o.margin.overturn_scale is not None), default=None)
    summary["n_margin_below_design"] = sum(1 for o in records if o.margin is not None
                                           and o.margin.overturn_scale is not None and o.margin.overturn_scale < 1.0)
    valid = [o for o in records if o.run.status == "completed"]
    fragility = pair_fragility(valid, a, summary["n_overturned"]) if margins else None
    margin_fema = collapse_margin(fragility, dict(a.quality), rule.target)
    context = CheckContext(records, a, {}, {}, margins_run=margins,
                           extra={"ensemble": ens, "cylinder": cyl, "summary": summary,
                                  "collapse_margin": margin_fema}, rule=rule)
    items, skipped = evaluate_criteria(context, cylinder_criteria(rule))
    decision = decide(items, skipped, rule, basis=headline_basis(e.scaling_block(records, cyl.g)))
    acceptance = acceptance_summary(rule, items, decision, context.valid, margin_fema,
                                    scans=None if flip_scans is None else
                                    [m for o, m in zip(records, flip_scans) if o.run.status == "completed"])
    checks = [i.as_json() for i in items]
    checks.sort(key=lambda c: (not c["governs_verdict"], -c["utilisation"]))
    ensemble_json = None if ens is None else {
        k: ens[k] for k in ("size", "seed", "amplitude_variation", "tolerance_factor", "p_overturn", "n_not_robust")}
    return CylinderCheckResult(project, records, summary, checks, decision.verdict, decision.reason,
                               decision.robust, decision.governing, ensemble_json, acceptance, fragility,
                               margin_fema, decided_at_design_level=decided if verdict_only else None,
                               quantities=cylinder_quantities(cyl))


MAX_HISTORIES = 8
"""At most this many time histories in the report (every overturning pair up to it)."""


def governing_ids(data: dict, n: int = GOVERNING_PAIRS) -> list[str]:
    """Ids of the pairs whose histories the report shows: every overturning pair (up to MAX_HISTORIES),
    at least ``n`` pairs, by decreasing 3D θ_max/α (overturned pairs first; stable order)."""
    rows = sorted(data["records"], key=lambda r: (not r["overturned"], -r["theta_max_over_alpha"]))
    count = min(max(n, sum(r["overturned"] for r in rows)), MAX_HISTORIES)
    return [r["id"] for r in rows[:count]]


def cylinder_check(project, progress=None, margins: bool = True, executor=None) -> CylinderCheckResult:
    """:func:`run_cylinder_check` (its 3D analyses on ``executor``, None: this process) plus the histories of the
    governing pairs (re-analysed here: the engine is deterministic, so they are the histories behind the rows of
    results.json)."""
    suite = suite_pair_records(project)           # (the pairs read and scaled once, for the histories too)
    result = run_cylinder_check(project, progress=progress, margins=margins, records=suite, executor=executor)
    cyl, a = project.system, project.analysis
    by_id, pairs = {o.id: o for o in result.records}, {p.meta.get("id", p.name): p for _, p in suite.pairs}
    result.figure_data["wobbling"] = dict(zip(("theta_over_alpha", "Tw_p", "T_housner_p"), wobbling_curve(cyl)))
    for rid in governing_ids(result.as_json()):
        pair = pairs[rid].scaled(by_id[rid].scale)
        result.histories[rid] = (simulate_cylinder(cyl, pair, free_vibration=a.free_vibration, rtol=a.rtol,
                                                   atol=a.atol, rest_velocity=a.rest_velocity), pair)
    return result


CYLINDER_UNITS = {"height": "m", "diameter": "m", "slenderness": "-", "mass": "kg", "overturn_tilt": "-",
                  "g": "m/s^2", "contact_frequency": "rad/s", "contact_damping": "-", "scale": "-",
                  "resultant_pga": "m/s^2", "theta_max_over_alpha": "-", "uplift_time": "s", "rtol": "-",
                  "atol": "-", "rest_velocity": "rad/s", "free_vibration": "s", "sd_max_band": "s"}
"""Units of the numbers of results.json's ``cylinder``, ``records`` and ``settings`` (SI)."""

CSV_COLUMNS = ["id", "suite", "event", "station", "scale", "resultant_pga", "theta_max_over_alpha", "overturned",
               "overturn_mode", "quasi_impacts", "uplift_time", "planar_theta_max_over_alpha", "planar_overturned",
               "polyakov_ratio_x", "polyakov_ratio_y", "min_contact_force_over_weight",
               "ensemble_overturn_fraction", "outcome_robust", "status", "analysis_failed"]
"""Columns of a cylinder check's results.csv (one row per record pair)."""
