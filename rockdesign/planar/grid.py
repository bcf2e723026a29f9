"""The design grid's hooks of a planar structure (SPEC §15, :mod:`rockdesign.design_space.grid`): which
variants share their scaled records, the check of one variant with ``verdict_only``, and its cell."""
from __future__ import annotations

import json
import statistics

from .checks.check import characteristic_periods, run_check, suite_records
from .checks.runner import analysis_failed
from ..acceptance.scans import SCAN_BLOCK, SCAN_RATIO, scan_grid
from .design.quantities import design_quantities

RULE = ("ASCE 7-22 §16.4.1.1 count of unacceptable ground motions and the FEMA P695 collapse margin at the risk "
        "category's target")
"""What decides a planar cell's verdict (the design report's words)."""

SKIPPED = ("margin scans and demand skipped where the design-level suite already fails the acceptance rule's "
           "count; c_r sensitivity, ensembles and report histories skipped everywhere (they never change the "
           "verdict's word)")
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
    first round of its margin scan (at least min(4, grid) factors per record) and the demand's 2DOF re-run."""
    a = result.project.analysis
    n = len(result.records)
    saved = 2 * n + (a.ensemble_size or 0) * n
    if decided_early:
        up = result.quantities["uplift_acceleration"].value
        for o in result.records:
            f_up = up / o.motion.pga if o.motion.pga > 0 else a.margin_max_scale
            grid = scan_grid(min(max(0.5 * f_up, 1e-3), a.margin_max_scale / 4), a.margin_max_scale, SCAN_RATIO)
            saved += min(SCAN_BLOCK, len(grid))
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
        "model": result.selection.chosen.label,
        "analyses": analyses, "analyses_saved": saved_by_stopping(result, decided),
    }
