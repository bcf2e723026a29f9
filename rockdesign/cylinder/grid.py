"""The design grid's hooks of a 3D cylinder (SPEC §15, :mod:`rockdesign.design_space.grid`): which
variants share their scaled record pairs, the check of one variant with ``verdict_only``, and its cell."""
from __future__ import annotations

import statistics

from .check import (GOVERNING_PAIRS, MAX_HISTORIES, run_cylinder_check, suite_pair_records,
                                     suite_pairs_key)

RULE = ("the project's acceptance rule over the record pairs, each pair one ground motion: the ASCE 7-22 "
        "§16.4.1.1 count of pairs that overturn (θ reaching θ_ot, thesis Sec 5.5.1) at the design level and at "
        "some intensity up to it and the FEMA P695 collapse margin at the risk category's target, or under "
        "acceptance = \"binomial\" the one-sided 95 % bound of P(overturn) (Clopper–Pearson) within the limit")
"""What decides a cylinder cell's verdict (the design report's words)."""

SKIPPED = ("incremental scans skipped where the design-level runs already fail the acceptance rule; the planar "
           "runs along each component (information), and the report histories skipped "
           "everywhere; the perturbation ensembles run only for a variant that passes, and stop at the first "
           "draw that fails")
"""What the grid skips for a cylinder variant (design.json ``settings.early_stopping``)."""


def records_key(project) -> str:
    """Which variants share their scaled pairs (:func:`~rockdesign.cylinder.check.suite_pairs_key`)."""
    return suite_pairs_key(project)


def grid_records(project, records_dir):
    """The record pairs read and scaled once (:func:`~rockdesign.cylinder.check.suite_pair_records`)."""
    return suite_pair_records(project)


def grid_check(project, *, records, records_dir, executor, progress):
    """The check of one variant with the grid's hooks (``records``, ``verdict_only``), its 3D analyses on the grid's
    ``executor`` (None: this process; ``records_dir`` is refused up front, ``check_options``)."""
    return run_cylinder_check(project, progress=progress, records=records, verdict_only=True, executor=executor)


def saved_by_stopping(result, decided_early: bool) -> int:
    """Analyses a full ``rockdesign check`` of this variant runs that the grid did not (a lower bound): the
    planar runs (2 per pair), the ensembles (``ensemble_size`` per pair) and the report's histories (at least
    2, every overturning pair up to 8); a variant decided at the design level is scanned below it for its
    distance to the flip, as the check scans it."""
    a = result.project.analysis
    n = len(result.records)
    overturned = sum(1 for o in result.records if o.run.overturned)
    return 2 * n + (a.ensemble_size or 0) * n + min(max(GOVERNING_PAIRS, overturned), MAX_HISTORIES, n)


def grid_cell(result, analyses: int) -> dict:
    """The check's numbers of a cylinder variant's cell (design.json ``cells``, SI units; CONTRACT §6.3).

    The acceptance numbers count record pairs (each one ground motion); ``p_overturn`` is the fraction of
    pairs that overturn at the design level and ``p_overturn_bound`` its one-sided 95 % bound
    (Clopper–Pearson), governing under ``acceptance = "binomial"`` against ``binomial_limit``;
    ``median_theta_max_over_theta_c`` is the median θ_max/θ_ot (θ_ot = overturn_tilt·α, Sec 5.5.1: the
    cylinder's rotation capacity); ``theta_c`` is None (Eq 3.56 is the curved planar column's); no
    superstructure, so its shear and drift are None; ``column_material`` is the cylinder's mass [kg]."""
    cyl = result.project.system
    acc = result.acceptance or {}
    valid = [o for o in result.records if o.run.status == "completed"]
    decided = bool(result.decided_at_design_level)
    return {
        "verdict": result.verdict if result.verdict in ("PASS", "FAIL") else "ERROR",
        "reason": result.verdict_reason,
        "governing": result.governing_check,
        "decided_at_design_level": decided,
        "acceptance": acc.get("method"),
        "acmr": acc.get("acmr"), "acmr_required": acc.get("acmr_required"),
        "p_collapse_design": acc.get("p_collapse_design"), "target_p_collapse": acc.get("target_p_collapse"),
        "n_unacceptable": acc.get("n_unacceptable"), "allowed_unacceptable": acc.get("allowed_unacceptable"),
        "n_ground_motions": acc.get("n_ground_motions"),
        "n_incremental_unacceptable": _incremental_count(result),
        "p_overturn": result.summary.get("p_overturn"),
        "p_overturn_bound": acc.get("binomial_bound"), "binomial_limit": acc.get("binomial_limit"),
        "n_failed_analyses": len(result.records) - len(valid),
        "superstructure_shear_p84": None, "superstructure_drift_p84": None,
        "median_theta_max_over_theta_c": statistics.median(o.run.response_ratio for o in valid)
        if valid else None,
        "median_theta_max_over_alpha": result.summary.get("median_theta_max_over_alpha"),
        "uplift_acceleration": cyl.g * cyl.tan_alpha,
        "uplift_shear_coefficient": cyl.tan_alpha,
        "theta_c": None, "alpha": cyl.alpha, "theta_overturn": cyl.theta_overturn,
        "column_material": cyl.mass,
        "material": cyl.mass, "demand": None,      # (the neutral words the shared design code ranks by)
        "model": "cylinder-" + ("damped" if cyl.damped else "undamped"),
        "analyses": analyses, "analyses_saved": saved_by_stopping(result, decided),
    }


def _incremental_count(result) -> int | None:
    """Ground motions (pairs) overturning at some intensity up to the design level (None: not scanned)."""
    rows = (result.acceptance or {}).get("ground_motions") or []
    if any(o.margin is None for o in result.records):
        return None
    return sum(1 for r in rows if r.get("first_overturn_scale") is not None and r["first_overturn_scale"] <= 1.0)


from .grid_draws import grid_draws  # noqa: E402,F401  (the perturbation draws of a passing variant)
