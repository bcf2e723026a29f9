"""The design grid's hooks of a planar structure (SPEC §15, :mod:`rockdesign.design_space.grid`): which
variants share their scaled records, the check of one variant with ``verdict_only``, and its cell."""
from __future__ import annotations

import json
import statistics

from .checks.check import characteristic_periods, run_check, suite_records
from .checks.runner import analysis_failed, run_jobs
from ..acceptance.perturbations import TOLERANCE_FACTOR, draw_words, perturbations
from ..acceptance.rule import acceptance_rule, count_rule
from .design.quantities import design_quantities

RULE = ("ASCE 7-22 §16.4.1.1 count of unacceptable ground motions and the FEMA P695 collapse margin at the risk "
        "category's target")
"""What decides a planar cell's verdict (the design report's words)."""

SKIPPED = ("margin scans and demand skipped where the design-level suite already fails the acceptance rule's "
           "count; report histories skipped everywhere; the perturbation draws (c_r ± 2 % and the ensembles) run "
           "only for a variant that passes, and stop at the first draw that fails")
"""What the grid skips for a planar variant (design.json ``settings.early_stopping``)."""


def records_key(project) -> str:
    """Which variants can share the scaled records: same excitation, same g — and for ``uplift`` scaling
    the same uplift acceleration, for ``asce7-22`` scaling without ``periods`` the same characteristic
    periods (the §16.2.1 period range follows the structure)."""
    exc = project.excitation_raw or {}
    scale = exc.get("scale") if isinstance(exc.get("scale"), dict) else {}
    key = [json.dumps(exc, sort_keys=True, default=str), repr(project.system.g),
           getattr(project.analysis, "risk_category", ""), getattr(project.analysis, "acceptance", "")]
    if scale.get("method") == "uplift":
        q = design_quantities(project.system, project.analysis.rigid_superstructure_ratio)
        key.append(repr(q["uplift_acceleration"].value))
    if scale.get("method") == "asce7-22" and "periods" not in scale:
        q = design_quantities(project.system, project.analysis.rigid_superstructure_ratio)
        key.append(repr(sorted(characteristic_periods(project.system, q).items())))
    return "\n".join(key)


def grid_records(project, records_dir):
    """(excitation, resolved records) of :func:`~rockdesign.planar.checks.check.suite_records` (input errors raise)."""
    return suite_records(project, records_dir)


def grid_check(project, *, records, records_dir, executor, progress):
    """The check of one variant with the grid's hooks (``records``, ``verdict_only``)."""
    return run_check(project, records_dir=records_dir, executor=executor, progress=progress, records=records,
                     verdict_only=True)


def saved_by_stopping(result, decided_early: bool) -> int:
    """Analyses a full ``rockdesign check`` of this variant runs that the grid did not (a lower bound):
    the c_r sensitivity (2 per record), the ensembles, and for a variant decided at the design level the
    demand's 2DOF re-run (its scan below the design level, for the distance to the flip, the grid runs too)."""
    a = result.project.analysis
    n = len(result.records)
    saved = 2 * n + (a.ensemble_size or 0) * n
    if decided_early:
        s = result.project.system
        chosen = result.selection.chosen
        if s.kind == "podium" and s.superstructure is not None and not s.superstructure.rigid \
                and chosen.structure != "podium-2dof":
            saved += n
    return saved


def grid_cell(result, analyses: int) -> dict:
    """The check's numbers of a planar variant's cell (design.json ``cells``, SI units; CONTRACT §6.3)."""
    decided = bool(result.settings.get("decided_at_design_level"))
    data_acc = result.acceptance or {}
    valid = [o for o in result.records if not analysis_failed(o.run.status)]
    ratios = [min(o.run.theta_max_over_theta_c, 1e300) for o in valid]
    sup = (result.statistics.get("superstructure") or {})
    shear = (sup.get("shear_coefficient") or {}) if sup.get("n_records") else {}
    drift = (sup.get("drift") or {}) if sup.get("n_records") else {}
    q = result.quantities
    s = result.project.system
    return {
        "verdict": result.verdict if result.verdict in ("PASS", "FAIL") else "ERROR",
        "reason": result.verdict_reason,
        "governing": result.governing_check,
        "decided_at_design_level": decided,
        "acmr": data_acc.get("acmr"), "acmr_required": data_acc.get("acmr_required"),
        "p_collapse_design": data_acc.get("p_collapse_design"),
        "target_p_collapse": data_acc.get("target_p_collapse"),
        "n_unacceptable": data_acc.get("n_unacceptable"), "allowed_unacceptable": data_acc.get("allowed_unacceptable"),
        "n_ground_motions": data_acc.get("n_ground_motions"),
        "n_failed_analyses": len(result.records) - len(valid),
        "superstructure_shear_p84": shear.get("p84"),
        "superstructure_drift_p84": drift.get("p84"),
        "median_theta_max_over_theta_c": statistics.median(ratios) if ratios else None,
        "uplift_acceleration": q["uplift_acceleration"].value,
        "uplift_shear_coefficient": q["uplift_acceleration"].value / s.g,
        "theta_c": q["theta_c"].value if "theta_c" in q else None,
        "column_material": s.n_columns * s.column.mass,
        # the neutral words the shared design code ranks by: the material [kg] and the demand (the superstructure's
        # 84th-percentile shear coefficient, None without an elastic superstructure)
        "material": s.n_columns * s.column.mass, "demand": shear.get("p84"),
        "model": result.selection.chosen.label,
        "analyses": analyses, "analyses_saved": saved_by_stopping(result, decided),
    }


def grid_draws(result, *, records, executor):
    """The perturbation draws of a passing variant, as its check runs them (SPEC §15; the check's
    restitution sensitivity and perturbation ensembles, same seed): c_r × (1 − variation) and
    c_r × (1 + variation) at the check's tolerances, then ``ensemble_size`` runs of the whole suite with
    the amplitude × (1 ± 0.1 %) per record, c_r × (1 ± 2 %) and the tolerances ÷ 10.  A draw fails when the
    design-level acceptance rule (ASCE 7-22 §16.4.1.1 count or the binomial bound) fails in it; the draws
    stop at the first that fails.  Returns ``{"n": draws run, "failed": 0 or 1, "size": draws planned,
    "first_failure": its words or None, "what": what the draws vary}``."""
    project = result.project
    system, a = project.system, project.analysis
    chosen = result.selection.chosen
    outcomes = result.records
    motions = [o.motion for o in outcomes]
    n = len(motions)
    rule = acceptance_rule(a)
    ok = [not analysis_failed(o.run.status) for o in outcomes]
    valid = [o for o, good in zip(outcomes, ok) if good]
    run_kw = dict(rtol=a.rtol, atol=a.atol, free_vibration=a.free_vibration, criterion=a.overturn,
                  rest_velocity=a.rest_velocity, executor=executor)
    draws = []
    for f in (1.0 - a.restitution_variation, 1.0 + a.restitution_variation):
        draws.append((f"c_r {'−' if f < 1 else '+'} {100 * abs(1 - f):g} %",
                      dict(run_kw, scales=[1.0] * n, restitution_factor=f, energy_stop=True), True))
    size = a.ensemble_size or 0
    amplitude, restitution = perturbations(n, size, a.seed)
    for m in range(size):
        draws.append((f"perturbed suite run {m + 1} of {size} (c_r × {float(restitution[m]):.4f})",
                      dict(run_kw, scales=list(amplitude[m]), rtol=a.rtol * TOLERANCE_FACTOR,
                           atol=a.atol * TOLERANCE_FACTOR, energy_stop=True,
                           stop_at_capacity=(a.overturn == "static"), restitution_factor=float(restitution[m])),
                      False))
    what = f"c_r ± {100 * a.restitution_variation:g} %, then the suite with {draw_words()}"
    for k, (label, kw, failures_count) in enumerate(draws):
        scales = kw.pop("scales")
        res = run_jobs(system, chosen, motions, scales, **kw)
        failed = [o.id for o, r, good in zip(outcomes, res, ok) if good and analysis_failed(r.status)]
        ids = {o.id for o, r, good in zip(outcomes, res, ok)      # (as the check's robustness criteria count)
               if good and r.overturned and not (failures_count and analysis_failed(r.status))}
        holds, unacceptable, total, _ = count_rule(rule, valid, ids)
        if not holds or (failures_count and failed):
            why = f"{label}: {unacceptable} of {total} ground motions unacceptable" \
                + (f", analyses failed: {', '.join(failed)}" if failures_count and failed else "")
            return {"n": k + 1, "failed": 1, "size": len(draws), "first_failure": why, "what": what}
    return {"n": len(draws), "failed": 0, "size": len(draws), "first_failure": None, "what": what}
