"""``rockdesign check``: the Polyakov design check over record suites (the product's main job).

project → design quantities → records (suites, scaling) → model selection → suite RHA →
Polyakov's rule and Fig 4.9 classes → overturning margins → statistics and c_r sensitivity →
checks and verdict.  :func:`run_check` returns a :class:`CheckResult`; its :meth:`~CheckResult.as_json`
is ``results.json`` (SI units; keys documented in docs/model.md, "Verdict").

The verdict comes from the criteria classes of :mod:`rockdesign.acceptance.criteria` (one class per
criterion, one :func:`~rockdesign.acceptance.criteria.decide`).  Analyses that fail (engine status other
than completed / overturned / energy stop) are listed, excluded from the statistics and make the
verdict FAIL — never counted as safe.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ... import __version__
from ..design.quantities import at_critical_curvature, design_quantities
from ..dynamics.accuracy import engine_accuracy
from ..dynamics.simulate import simulate
from ...jsonable import SerialisedOnce
from ...kernel_cache import sources_digest
from ...errors import ProjectError
from ...motions.asce7_22 import rocking_structure_periods, scaling_period_range
from ...motions.config import default_excitation, resolve_motions
from ...motions.scaling_report import headline_basis, method_block, scaling_block, scaling_sentence, suite_target
from ...motions.measures import plausibility_warnings
from ...motions.spectra import sd_max
from .figure_data import report_figure_data
from ..project import Project
from ...motions.grouping import earthquake_id, ground_motion_id
from ...acceptance.rule import acceptance_rule, minimum_records, require_suite_size
from ...acceptance.summary import acceptance_summary
from ...acceptance.criteria import CheckContext, decide, evaluate_criteria
from .criteria import criteria_for
from .runner import analysis_failed
from ...acceptance.collapse_margin import collapse_margin
from .ensemble import ensemble_summary, record_fields, run_ensembles
from ...acceptance.fragility import check_fragility
from ...acceptance.scans import SCAN_AFTER_FIRST, SCAN_RATIO, Margin, scan_grid
from .margins import decided_at_design_level, overturning_margins, scan_need
from .polyakov import PolyakovRule, classify
from .runner import RunSummary, run_jobs
from .selection import ModelSelection, select_model
from .governing import history_records
from .suite_statistics import suite_statistics
from .demand import governing_demand_history, superstructure_demand



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
    ensemble: dict = field(default_factory=lambda: record_fields(None, 0))
    superstructure: dict | None = None     # CONTRACT §6.2 (checks/demand.py)
    cap_beam: dict | None = None           # frames and rigid superstructures: the cap beam's demand
    ground_motion: str = ""     # the ground motion (station and event) the record belongs to (motions.grouping)

    def as_json(self) -> dict:
        r = self.run
        m = self.margin
        return {
            "id": self.id,
            "ground_motion": self.ground_motion or self.id,
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
            "analysis_failed": analysis_failed(r.status),
            **self.ensemble,
            "superstructure": self.superstructure,
            **({} if self.cap_beam is None else {"cap_beam": self.cap_beam}),
        }


@dataclass
class CheckResult(SerialisedOnce):
    """A design check: everything the report and results.json need (SI units throughout).

    ``verdict`` "PASS" | "FAIL" | "NOT DECIDED" (criteria.decide); ``records`` one
    :class:`RecordOutcome` per record; ``checks`` the
    criteria with utilisation [-] and result; ``statistics`` the suite summary (P(overturn) with its
    bound, classes, margins); ``quantities`` the design quantities (value + unit); ``as_json()`` is
    results.json (= ``rockdesign check --json``).
    """

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
    verdict_reason: str = ""
    verdict_robust: bool = True
    intensity: dict = field(default_factory=dict)

    @property
    def failed_records(self) -> list[RecordOutcome]:
        """Records whose analysis failed (listed loudly; never counted as safe)."""
        return [o for o in self.records if analysis_failed(o.run.status)]
    fragility: dict | None = None          # checks/fragility.py (docs/fragility.md)
    collapse_margin: dict | None = None    # checks/collapse_margin.py
    ensemble: dict | None = None           # checks/ensemble.py
    governing_check: str | None = None     # criterion key of the governing check (criteria.decide)
    demand_history: tuple | None = None    # (record id, 2DOF Response) of the largest superstructure demand
    acceptance: dict | None = None         # checks/acceptance.py: the rule, its numbers and the per-ground-motion table
    scaling: dict | None = None            # excitation.scaling (CONTRACT §7.1, motions/scaling_report.py)
    figure_data: dict = field(default_factory=dict)   # what the report draws beyond results.json (figure_data.py)

    def serialise(self) -> dict:
        """results.json (``as_json()``: built once, when the check is complete)."""
        p = self.project
        s = p.system
        return {
            "project": {"name": p.name, "file": p.path, "sha256": p.sha256, "kind": s.kind,
                        **{k: v for k, v in p.info.items() if k != "name"}, "tool_version": __version__,
                        "kernels_sha256": sources_digest(),   # which kernel sources produced the numbers
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
            "excitation": {"suites": self.suites, "scaling": self.scaling,
                           "default_used": self.default_excitation_used,
                           "missing": [{"id": i, "reason": r, "suite": su} for i, r, su in self.missing],
                           **self.intensity,
                           "sd_max_damping": self.rule.damping, "sd_max_band": list(self.rule.band),
                           "capacity": self.rule.capacity},
            "records": [r.as_json() for r in self.records],
            "summary": self.statistics,
            "sensitivity": self.sensitivity,
            "verdict": self.verdict,
            "verdict_reason": self.verdict_reason,
            "verdict_robust": self.verdict_robust,
            "failed_records": [{"id": o.id, "status": o.run.status} for o in self.failed_records],
            "checks": self.checks,
            "settings": self.settings,
            "fragility": self.fragility, "collapse_margin": self.collapse_margin, "ensemble": self.ensemble,
            "acceptance": self.acceptance,
        }


def _excitation(project: Project):
    """The excitation the check analyses: the typed ``project.excitation`` (parsed once, at load), with
    the default suite scaled to ``design_pga`` when the table names no suite or record."""
    spec = project.excitation
    if spec is None:
        raise ProjectError("the design check needs an excitation", file=project.path, key="excitation.design_pga",
                           expected="[excitation] with design_pga = \"0.3 g\" (the default runs the FEMA P695 "
                                    "far-field suite scaled to it) or suites/records with a scale rule",
                           found="no [excitation] table")
    given = project.excitation_raw or {}        # (which keys the user wrote; their values are in ``spec``)
    if not given.get("suites") and not given.get("records"):
        if spec.design_pga is None:
            raise ProjectError("missing required value", file=project.path, key="excitation.design_pga",
                               expected="design_pga (the FEMA P695 far-field suite is scaled to it)", found="none")
        spec = default_excitation(spec.design_pga, file=project.path) if spec.scale is None else spec
    return spec


def check_records(project: Project, records_dir: str | None = None):
    """The records of a project's excitation, read and scaled as the check will analyse them
    (:func:`rockdesign.motions.config.resolve_motions`); a :class:`ProjectError` when the excitation is
    invalid or none of its records can be found.  ``rockdesign check`` calls it before compiling its
    kernels on a first run, so such an input error stops the command at once."""
    return prepared_records(project, records_dir)[1]


def characteristic_periods(system, q) -> dict[str, float]:
    """The periods [s] of a planar rocking structure that bound the ASCE 7-22 §16.2.1 period range
    (:func:`rockdesign.motions.asce7_22.rocking_structure_periods`; docs/records.md): the elastic
    superstructure's fixed-base T_s and uplifted T_s/S_r (Eq 4.25), and the rocking period at the design
    rotation θ = α/2, T_R = (4/p̂) acosh(1/(1 − θ/α)) = (4/p̂) acosh 2 (Eq 2.8) with the system's frequency
    parameter p̂ (Eq 4.32 for a podium; p, Eq 3.13, for a column)."""
    s = system.superstructure
    elastic = s is not None and not s.rigid and "S_r" in q
    t_s = 2.0 * math.pi / s.omega_s if elastic else None
    periods = rocking_structure_periods(fixed_base=t_s, uplifted=t_s / q["S_r"].value if elastic else None)
    # named with its frequency parameter and rotation, as the quantities table names T_R (one value per symbol)
    if "p_hat" in q:
        label = f"rocking period T_R(α/2; p̂) = (4/p̂) acosh 2 (Eq 2.8 with p̂, {q['p_hat'].equation})"
        periods[label] = 4.0 / q["p_hat"].value * math.acosh(2.0)
    else:
        periods["rocking period T_R(α/2; p) (Eq 2.8)"] = 4.0 / q["p"].value * math.acosh(2.0)
    return periods


def project_quantities(project: Project) -> dict:
    """The design quantities of a project, computed once per project (``project.derived``)."""
    if "quantities" not in project.derived:
        project.derived["quantities"] = design_quantities(project.system, project.analysis.rigid_superstructure_ratio)
    return project.derived["quantities"]


def prepared_records(project: Project, records_dir: str | None = None):
    """(excitation spec, resolved records) of :func:`suite_records`, read and scaled once per project and records
    folder: ``prepare_check`` reads them before a first run compiles, the check analyses the same ones."""
    key = ("records", records_dir)
    if key not in project.derived:
        project.derived[key] = _records(project, project_quantities(project), records_dir)
    return project.derived[key]


def _records(project: Project, q, records_dir):
    spec = _excitation(project)
    resolved = resolve_motions(spec, gravity=project.system.g, uplift_acceleration=q["uplift_acceleration"].value,
                               records_dir=records_dir, characteristic_periods=characteristic_periods(project.system, q))
    if not resolved.records:
        raise ProjectError("no record of the excitation could be found", file=project.path, key="excitation",
                           expected="at least one available record",
                           found="; ".join(f"{i}: {r}" for i, r, _ in resolved.missing) or "an empty suite")
    # the acceptance rule's suite size, before any analysis (ground motions, not components)
    gms = {ground_motion_id(r.id, r.meta) for r in resolved.records}
    require_suite_size(acceptance_rule(project.analysis), len(gms), len(resolved.records), resolved.suites,
                       file=project.path, key="excitation", missing=[i for i, _, _ in resolved.missing])
    return spec, resolved


def run_check(project: Project, *, records_dir: str | None = None, margins: bool = True, progress=None,
              executor=None, records=None, verdict_only: bool = False) -> CheckResult:
    """Run the design check of a project (see module docstring).

    ``progress(stage, done, total)`` is called as work proceeds (the CLI draws rich progress bars).
    ``executor``: run the analyses on the chunked executor of :mod:`rockdesign.execution.executor`
    (e.g. a dask.distributed cluster); default in-process on all cores.  Results are identical.
    Hooks of the design grid (:mod:`rockdesign.design_space.grid`): ``records`` — the (excitation,
    resolved records) pair of :func:`suite_records`, read and scaled once for many variants;
    ``verdict_only`` — compute only what the verdict word and the design table need: no c_r
    sensitivity, ensembles, report histories or engine-accuracy appendix, and, when the design-level
    suite already decides FAIL (:func:`decided_at_design_level`), no margin scans or demand either.
    """
    system = project.system
    a = project.analysis
    q = project_quantities(project)
    capacity = q["u_capacity"].value
    rule = PolyakovRule(capacity, a.sdmax_damping, tuple(a.sdmax_band))
    spec, resolved = prepared_records(project, records_dir) if records is None else records
    motions = [r.motion for r in resolved.records]
    n = len(motions)
    record_warnings = [w for r in resolved.records for w in plausibility_warnings(r.motion, system.g)]
    record_warnings += [f"{r.id}: amplitude factor {r.scale:.3g} is implausible — check the record's units"
                        for r in resolved.records if not 1e-3 <= r.scale <= 1e3]

    def stage(name, total):
        if progress is None:
            return None
        progress(name, 0, total)
        return lambda done: progress(name, done, total)

    tick = stage("elastic spectra (SD_max)", n)
    sds = resolved.derived.get(("sd_max", rule.damping, tuple(rule.band)))
    if sds is None:          # (the records' own property: shared by the variants of a design grid)
        sds = []
        for k, m in enumerate(motions):
            sds.append(sd_max(m, rule.damping, rule.band))
            if tick:
                tick(k + 1)
        resolved.derived[("sd_max", rule.damping, tuple(rule.band))] = sds
    elif tick:
        tick(n)
    run_kw = dict(rtol=a.rtol, atol=a.atol, free_vibration=a.free_vibration, criterion=a.overturn,
                  rest_velocity=a.rest_velocity, executor=executor)
    selection, runs = select_model(system, a, motions, run_kw, progress=stage("suite analysis (RHA)", n))
    chosen = selection.chosen

    # incremental analyses need verdicts to 1 %, not histories to 1e-10: a looser tolerance there
    scan_kw = dict(run_kw, rtol=max(a.rtol, a.scan_rtol))
    margin_list: list[Margin | None] = [None] * n
    flip_scans = None
    decided_fail = verdict_only and decided_at_design_level(acceptance_rule(a), resolved.records, runs)
    margins_run = margins and not decided_fail
    need = scan_need(a, resolved.records, runs, motions, sds, decided_fail) if verdict_only and margins else None
    if margins_run or need is not None:
        up = q["uplift_acceleration"].value
        uplift_factors = [up / m.pga if m.pga > 0 else a.margin_max_scale for m in motions]
        total = 0
        for f_up in uplift_factors:
            total += len(scan_grid(min(max(0.5 * f_up, 1e-3), a.margin_max_scale / 4), a.margin_max_scale,
                                    SCAN_RATIO))
        scanned = overturning_margins(system, chosen, motions, uplift_factors=uplift_factors,
                                      max_scale=a.margin_max_scale, precision=a.margin_precision, need=need,
                                      progress=stage("overturning margins (incremental RHA)", total), **scan_kw)
        if margins_run:
            margin_list = scanned
        else:       # a decided FAIL: scanned below the design level for its distance to the flip alone
            flip_scans = scanned

    # sensitivity of the verdicts to c_r ± variation
    tick = stage(f"restitution sensitivity (c_r ± {100 * a.restitution_variation:g} %)", 2 * n)
    flips = [False] * n
    sens = {}
    for j, factor in enumerate(() if verdict_only else (1.0 - a.restitution_variation, 1.0 + a.restitution_variation)):
        res = run_jobs(system, chosen, motions, [1.0] * n, restitution_factor=factor, energy_stop=True,
                       progress=(lambda d, j=j: tick(j * n + d)) if tick else None, **run_kw)
        # (same tolerance as the nominal suite run: a verdict flip must come from c_r, not from rtol)
        ok = [i for i in range(n) if not analysis_failed(res[i].status) and not analysis_failed(runs[i].status)]
        changed = [i for i in ok if res[i].overturned != runs[i].overturned]
        for i in changed:
            flips[i] = True
        sens[f"{factor:.4g}"] = {"restitution_factor": factor, "verdict_changes": len(changed),
                                 "records": [resolved.records[i].id for i in changed],
                                 "n_overturned": sum(res[i].overturned for i in ok), "n_records": len(ok),
                                 "failed": [resolved.records[i].id for i in range(n) if analysis_failed(res[i].status)]}
    sensitivity = {"variation": a.restitution_variation, "runs": sens,
                   "verdict_flips": sum(flips), "note": "c_r ≤ 1 (capped)"}

    ens = None
    if a.ensemble_size and not verdict_only:
        ens = run_ensembles(system, chosen, motions, runs, size=a.ensemble_size, seed=a.seed,
                            progress=stage(f"perturbation ensembles ({a.ensemble_size} runs per record)",
                                           a.ensemble_size * n), **run_kw)
    target = suite_target(resolved)
    demand, caps, demand_summary, demand_runs = superstructure_demand(
        system, chosen, motions, runs, run_kw, q["uplift_acceleration"].value, stage=stage,
        names=[(r.id, ground_motion_id(r.id, r.meta)) for r in resolved.records],
        target=target) if not decided_fail else ([None] * n, [None] * n, None, None)
    # report data, not in a design grid's cell: a verdict-only check skips the spectra a suite scaled otherwise than
    # per §16.2 is compared with (a §16.2.3 suite carries its block already)
    scaling = None if verdict_only and getattr(resolved, "asce7_22", None) is None else scaling_block(
        resolved, period_range=scaling_period_range(characteristic_periods(system, q)), gravity=system.g)
    outcomes = []
    for i, (rec, (sd, t_sd), run) in enumerate(zip(resolved.records, sds, runs)):
        ratio = rule.utilisation(sd)
        outcomes.append(RecordOutcome(rec.id, rec.suite, rec.meta, rec.scale, rec.motion, rec.motion.pga, sd, t_sd,
                                      ratio, rule.predicted_scale(sd), run,
                                      classify(ratio, run.u_B_max_over_capacity, run.overturned), margin_list[i],
                                      flips[i], record_fields(ens, i), demand[i], caps[i],
                                      ground_motion_id(rec.id, rec.meta)))
    valid = [o for o in outcomes if not analysis_failed(o.run.status)]
    stats = suite_statistics(valid, a, margins_run)
    stats["n_failed"] = n - len(valid)
    acc_rule = acceptance_rule(a)
    stats["n_ground_motions"] = len({o.ground_motion for o in outcomes})
    stats["n_earthquakes"] = len({e for e in (earthquake_id(o.meta) for o in outcomes) if e}) or None
    stats["min_records_for_bound"] = minimum_records(acc_rule.binomial_limit)
    stats["superstructure"] = demand_summary
    ens_json = ens and ensemble_summary([o.id for o in outcomes], ens, size=a.ensemble_size, seed=a.seed,
                                        rtol=a.rtol, atol=a.atol, nominal_overturned=stats["n_overturned"])
    stats["p_overturn_ensemble"] = ens_json["p_overturn"] if ens_json else None
    fragility = check_fragility(valid, a, empirical=(stats["n_overturned"], len(valid)), stripe_ratio=SCAN_RATIO)
    margin_fema = collapse_margin(fragility, dict(a.quality), acc_rule.target)
    extra = {"ensemble": ens, "collapse_margin": margin_fema}
    items, skipped = evaluate_criteria(CheckContext(outcomes, a, q, sensitivity, margins_run, extra, acc_rule),
                                       criteria_for(acc_rule))
    decision = decide(items, skipped, acc_rule,
                      basis=headline_basis(scaling if scaling is not None else method_block(resolved)))
    acceptance = acceptance_summary(acc_rule, items, decision, valid, margin_fema,
                                    scans=None if flip_scans is None else
                                    [flip_scans[i] for i, o in enumerate(outcomes) if not analysis_failed(o.run.status)])
    checks = [i.as_json() for i in items]
    checks.sort(key=lambda c: (not c["governs_verdict"], -c["utilisation"]))
    verdict = decision.verdict
    histories = {}
    for o in (valid[i] for i in ([] if verdict_only else
                                 history_records([o.run.theta_max_over_theta_c for o in valid]))):
        histories[o.id] = simulate(system, o.motion, model=chosen.equations, structure=chosen.structure, rtol=a.rtol,
                                   atol=a.atol, t_end=o.motion.duration + a.free_vibration, overturn=a.overturn,
                                   rest_velocity=a.rest_velocity)
    demand_history = None if verdict_only else governing_demand_history(system, outcomes, chosen, a)
    settings = {"rtol": a.rtol, "atol": a.atol, "overturn_criterion": a.overturn, "g": system.g,
                "rest_velocity": a.rest_velocity, "free_vibration": a.free_vibration,
                "linearization_tolerance": a.linearization_tolerance, "margin_precision": a.margin_precision,
                "margin_max_scale": a.margin_max_scale, "margin_scan_ratio": SCAN_RATIO,
                "margin_scan_after_first": SCAN_AFTER_FIRST,
                "margin_rtol": max(a.rtol, a.scan_rtol),
                "overturn_probability_limit": a.overturn_probability_limit,
                "rigid_superstructure_ratio": a.rigid_superstructure_ratio,
                "scale_basis": "overturn_scale and polyakov_scale multiply the design-level (scaled) record"}
    if verdict_only:
        settings["decided_at_design_level"] = decided_fail
    if at_critical_curvature(system) and "R_hat" in q:
        settings["equivalent_block"] = (
            f"ρ = ρc: to linear order and up to the first impact the columns respond like flat-based blocks of "
            f"size R̂ = {q['R_hat'].value:.4g} m ({q['R_hat'].equation}); not used as a substitute model because "
            "impacts differ (c_r) — the curved column itself is analysed (docs/model.md §3)")
    # the engine's error against a closed form at the tolerance used (report appendix)
    if not verdict_only:
        acc = engine_accuracy(a.rtol, a.atol)
        settings["engine_accuracy"] = {k: v for k, v in acc.items() if k != "seconds"}
    intensity = {"design_pga": spec.design_pga, "intensity_analysed": resolved.scale_description,
                 "scaling_sentence": None if scaling is None else scaling_sentence(scaling, system.g),
                 "record_warnings": record_warnings}
    return CheckResult(project, q, rule, selection, outcomes, resolved.missing, resolved.scale_description,
                       resolved.default_used or spec.default_used, resolved.suites, stats, checks, verdict, histories,
                       sensitivity, settings, decision.reason, decision.robust, intensity, fragility, margin_fema,
                       ens_json, decision.governing, demand_history, acceptance, scaling,
                       {} if verdict_only else report_figure_data(system, rule, motions))


def suite_records(project: Project, records_dir: str | None = None):
    """(excitation spec, resolved records) of a project as :func:`run_check` analyses them (its
    ``records`` hook): the records read and scaled once, e.g. for every variant of a design grid."""
    return _records(project, project_quantities(project), records_dir)
