"""The design grid's runner: the check of every variant, with the work the variants share done once (SPEC §15).

Shared work:

- the records of the excitation are read and scaled once per distinct excitation (every variant of a
  ``pga``/``factor``/``spectrum``/``sdmax``-scaled suite shares them; ``uplift`` scaling depends on the
  variant's uplift acceleration and is keyed on it) and handed to the check's ``records`` hook;
- the kernels compile (or load from the cache) once, in this one process;
- each variant runs the check's own stages (:func:`rockdesign.checks.check.run_check` with
  ``verdict_only``): model selection, the design-level suite in one batch over all cores, the margin
  scans and the demand — so a cell's verdict is the check's verdict of that variant;
- a variant stops once its verdict is decided: when the design-level suite already fails the acceptance
  rule's count (or an analysis failed) the margin scans and the demand re-runs are skipped — the
  margins can only add failing criteria; the c_r sensitivity, ensembles, report histories and the
  engine-accuracy appendix (which never change the verdict's word) are skipped everywhere.

Every finished variant is stored in ``<out>/variants/<digest>.json`` (the digest of the variant's project
text, the tool version and the kernel sources): a run interrupted and started again skips them.
"""
from __future__ import annotations

import hashlib
import json
import math
import statistics
from dataclasses import dataclass, field
from pathlib import Path

from .. import __version__
from ..errors import ProjectError, RockdesignError
from .variants import Variable, Variant, variant_toml


@dataclass
class GridRun:
    """The grid's outcome: ``cells`` (one dict per variant, design.json's ``cells``), the analyses run
    and the lower bound of those saved, how many variants came from a stored earlier run."""

    variables: list[Variable]
    cells: list[dict]
    analyses_run: int = 0
    analyses_saved: int = 0
    resumed: int = 0
    notes: list[str] = field(default_factory=list)


def _digest(text: str) -> str:
    from ..kernel_cache import sources_digest
    return hashlib.sha256(f"{__version__}\n{sources_digest()}\n{text}".encode()).hexdigest()[:20]


def _records_key(project) -> str:
    """Which variants can share the scaled records: same excitation, same g — and for ``uplift`` scaling
    the same uplift acceleration."""
    exc = project.excitation_raw or {}
    scale = exc.get("scale") if isinstance(exc.get("scale"), dict) else {}
    key = [json.dumps(exc, sort_keys=True, default=str), repr(project.system.g),
           getattr(project.analysis, "risk_category", ""), getattr(project.analysis, "acceptance", "")]
    if scale.get("method") == "uplift":
        from ..design.quantities import design_quantities
        q = design_quantities(project.system, project.analysis.rigid_superstructure_ratio)
        key.append(repr(q["uplift_acceleration"].value))
    return "\n".join(key)


def saved_by_stopping(result, decided_early: bool) -> int:
    """Analyses a full ``rockdesign check`` of this variant runs that the grid did not (a lower bound):
    the c_r sensitivity (2 per record), the ensembles, and for a variant decided at the design level the
    first round of its margin scan (at least min(4, grid) factors per record) and the demand's 2DOF re-run."""
    from ..checks.margins import SCAN_BLOCK, SCAN_RATIO, _scan_grid
    a = result.project.analysis
    n = len(result.records)
    saved = 2 * n + (a.ensemble_size or 0) * n
    if decided_early:
        up = result.quantities["uplift_acceleration"].value
        for o in result.records:
            f_up = up / o.motion.pga if o.motion.pga > 0 else a.margin_max_scale
            grid = _scan_grid(min(max(0.5 * f_up, 1e-3), a.margin_max_scale / 4), a.margin_max_scale, SCAN_RATIO)
            saved += min(SCAN_BLOCK, len(grid))
        s = result.project.system
        chosen = result.selection.chosen
        if s.kind == "podium" and s.superstructure is not None and not s.superstructure.rigid \
                and chosen.structure != "podium-2dof":
            saved += n
    return saved


def cell_of(variant: Variant, variables, result, analyses: int, saved: int, decided_early: bool) -> dict:
    """design.json's cell of a checked variant (SI units; CONTRACT §6.3)."""
    from ..checks.criteria import analysis_failed
    data_acc = result.acceptance or {}
    valid = [o for o in result.records if not analysis_failed(o.run.status)]
    ratios = [min(o.run.theta_max_over_theta_c, 1e300) for o in valid]
    sup = (result.statistics.get("superstructure") or {})
    shear = (sup.get("shear_coefficient") or {}) if sup.get("n_records") else {}
    drift = (sup.get("drift") or {}) if sup.get("n_records") else {}
    q = result.quantities
    s = result.project.system
    return {
        **_base_cell(variant, variables),
        "verdict": result.verdict if result.verdict in ("PASS", "FAIL") else "ERROR",
        "reason": result.verdict_reason.replace("no incremental analysis: --no-margins",
                                                "not needed: the design-level suite decides")
        if decided_early else result.verdict_reason,
        "governing": result.governing_check,
        "decided_at_design_level": decided_early,
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
        "analyses": analyses, "analyses_saved": saved,
    }


def _base_cell(variant: Variant, variables) -> dict:
    return {"index": list(variant.index),
            "values": {v.key: v.si[k] for v, k in zip(variables, variant.index)},
            "labels": {v.key: v.label(k) for v, k in zip(variables, variant.index)},
            "notes": list(variant.notes)}


EMPTY = dict.fromkeys(("governing", "acmr", "acmr_required", "p_collapse_design", "target_p_collapse", "n_unacceptable",
                       "allowed_unacceptable", "n_ground_motions", "superstructure_shear_p84",
                       "superstructure_drift_p84", "median_theta_max_over_theta_c", "uplift_acceleration",
                       "uplift_shear_coefficient", "theta_c", "column_material", "model"))


def run_grid(variant_list: list[Variant], variables, *, records_dir=None, executor=None, store: Path | None = None,
             progress=None, stage_progress=None) -> GridRun:
    """Check every variant (see module docstring); ``progress(done, total, cell)`` after each variant,
    ``stage_progress(stage, done, total)`` inside one (the check's stages); ``store``: the folder of the
    per-variant results that makes the run resumable (None: nothing stored)."""
    from ..checks.check import run_check, suite_records
    from ..checks.runner import AnalysisCount
    run = GridRun(list(variables), [])
    records_cache: dict[str, tuple] = {}
    total = len(variant_list)
    for done, variant in enumerate(variant_list, 1):
        if variant.project is None:
            cell = {**_base_cell(variant, variables), **EMPTY, "verdict": "INVALID", "reason": variant.invalid,
                    "decided_at_design_level": False, "n_failed_analyses": 0, "analyses": 0, "analyses_saved": 0}
        else:
            path = None if store is None else store / f"{_digest(variant_toml(variant.raw))}.json"
            if path is not None and path.is_file():
                cell = json.loads(path.read_text(encoding="utf-8"))
                cell["resumed"] = True
                run.resumed += 1
            else:
                proj = variant.project
                key = _records_key(proj)
                if key not in records_cache:
                    records_cache[key] = suite_records(proj, records_dir)   # input errors stop the grid (exit 2)
                before = AnalysisCount.total
                try:
                    result = run_check(proj, records_dir=records_dir, executor=executor, progress=stage_progress,
                                       records=records_cache[key], verdict_only=True)
                except RockdesignError as exc:  # the variant's own model or geometry is impossible
                    cell = {**_base_cell(variant, variables), **EMPTY, "reason": str(exc),
                            "verdict": "INVALID" if isinstance(exc, ProjectError) else "ERROR",
                            "decided_at_design_level": False, "n_failed_analyses": 0,
                            "analyses": AnalysisCount.total - before, "analyses_saved": 0}
                else:
                    decided = bool(result.settings.get("decided_at_design_level"))
                    ran = AnalysisCount.total - before
                    cell = cell_of(variant, variables, result, ran, saved_by_stopping(result, decided), decided)
                if path is not None:
                    path.parent.mkdir(parents=True, exist_ok=True)
                    tmp = path.with_suffix(".tmp")
                    tmp.write_text(json.dumps(cell, default=_json_default), encoding="utf-8")
                    tmp.replace(path)        # atomic: an interruption leaves no half-written variant
                cell["resumed"] = False
        run.cells.append(cell)
        if not cell.get("resumed"):
            run.analyses_run += cell.get("analyses") or 0
            run.analyses_saved += cell.get("analyses_saved") or 0
        if progress is not None:
            progress(done, total, cell)
    return run


def _json_default(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None
    try:
        return float(x)
    except (TypeError, ValueError):
        raise TypeError(f"not JSON: {type(x).__name__}") from None


def recommended(cells: list[dict]) -> dict | None:
    """The recommended design (SPEC §15): among passing cells the lowest 84th-percentile superstructure
    shear coefficient (equal to 3 significant digits: the least column material n·m_C), with its margin;
    None when no cell passes.  Without an elastic superstructure the least column material decides."""
    passing = [c for c in cells if c["verdict"] == "PASS"]
    if not passing:
        return None

    def rank(c):
        shear = c.get("superstructure_shear_p84")
        return (float(f"{shear:.3g}") if shear is not None else math.inf, c.get("column_material") or math.inf)

    best = min(passing, key=rank)
    margin = []
    if best.get("acmr") is not None and best.get("acmr_required"):
        margin.append(f"ACMR {best['acmr']:.3g} ≥ {best['acmr_required']:.3g} required "
                      f"(×{best['acmr'] / best['acmr_required']:.3g})")
    if best.get("n_unacceptable") is not None:
        margin.append(f"{best['n_unacceptable']} of {best['n_ground_motions']} ground motions unacceptable "
                      f"({best['allowed_unacceptable']} allowed)")
    shear = best.get("superstructure_shear_p84")
    why = ("the passing variant with the lowest superstructure shear coefficient (84th percentile "
           f"{shear:.3g})" if shear is not None else
           "the passing variant with the least column material (no elastic superstructure demand)")
    return {"values": best["values"], "labels": best["labels"], "index": best["index"],
            "reason": f"{why}; margin: " + "; ".join(margin) if margin else why}


def check_exit_code(cells: list[dict]) -> int:
    """0 when at least one variant passes, 1 when none does (CONTRACT §6.3)."""
    return 0 if any(c["verdict"] == "PASS" for c in cells) else 1


__all__ = ["GridRun", "run_grid", "recommended", "check_exit_code"]
