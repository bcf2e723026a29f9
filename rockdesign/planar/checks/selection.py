"""Model selection: the simplest model that is accurate enough, chosen and verified with numbers (SPEC §6).

1. Structure: a rigid superstructure (frame with γ̂ = γ(1+η), Polyakov rule 1) when ω_s/p is at or
   above the switch ratio (default 10), else the 2DOF podium.
2. Equations: the linearized EOM first (``equations = "auto"``), the exact EOM otherwise.
3. Verification: the governing records are re-run with the full model (2DOF podium where the
   superstructure is elastic, exact equations).  If any verdict changes, or θ_max/θc differs by more
   than the tolerance, the simpler model is rejected for the whole suite — and the report shows the
   measured differences either way.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from ..dynamics.model import ModelChoice, default_structure, resolve_structure
from .runner import RunSummary, run_jobs
from .governing import capped_ratio, model_check_records


@dataclass
class ModelSelection:
    """The analysed model, why, and the measured error of the simplifications."""

    chosen: ModelChoice
    full: ModelChoice
    reason: str
    structure_reason: str
    equations_reason: str
    verification: list[dict] = field(default_factory=list)   # per governing record
    max_difference: float = 0.0          # max |Δ(θ_max/θc)| chosen vs full on the governing records
    verdict_changes: int = 0
    rejected: list[str] = field(default_factory=list)


def select_model(system, analysis, motions, run_kw, *, progress=None) -> tuple[ModelSelection, list[RunSummary]]:
    """Choose and verify the model; returns the selection and the suite results with the chosen model."""
    a = analysis
    if a.model == "auto":
        structure, s_reason = default_structure(system, a.rigid_superstructure_ratio)
    else:
        structure = resolve_structure(system, a.model)
        s_reason = f"forced by [analysis] model = \"{a.model}\""
    full_structure = "podium-2dof" if system.has_elastic_superstructure else structure
    if a.equations == "auto":
        equations = "linear"
        e_reason = (f"linearized equations tried first; kept only if θ_max/θc changes by less than "
                    f"{a.linearization_tolerance:g} and no verdict changes on the governing records (docs/model.md §7)")
    else:
        equations = a.equations
        e_reason = f"forced by [analysis] equations = \"{a.equations}\""
    full = ModelChoice(full_structure, "exact")
    chosen = ModelChoice(structure, equations)
    rejected = []
    while True:
        results = run_jobs(system, chosen, motions, [1.0] * len(motions), progress=progress, **run_kw)
        order = model_check_records([r.theta_max_over_theta_c for r in results], [r.overturned for r in results])
        if chosen == full:
            selection = ModelSelection(chosen, full, "", s_reason, e_reason, rejected=rejected)
            sub = [results[i] for i in order]
            _verify(selection, system, [motions[i] for i in order], sub, sub, run_kw, ids=order)
            break
        full_results = run_jobs(system, full, [motions[i] for i in order], [1.0] * len(order), **run_kw)
        selection = ModelSelection(chosen, full, "", s_reason, e_reason, rejected=rejected)
        _verify(selection, system, [motions[i] for i in order], [results[i] for i in order], full_results, run_kw,
                ids=order)
        ok = selection.verdict_changes == 0 and selection.max_difference <= a.linearization_tolerance
        if ok:
            break
        # reject the cheaper part that differs: equations first (auto), then the structure (auto)
        why = (f"{chosen.label} rejected: max |Δ(θ_max/θc)| = {selection.max_difference:.3g} "
               f"(tolerance {a.linearization_tolerance:g}), {selection.verdict_changes} verdict "
               f"change{'' if selection.verdict_changes == 1 else 's'} "
               f"on the governing records")
        rejected.append(why)
        if chosen.equations == "linear" and a.equations == "auto":
            chosen = ModelChoice(chosen.structure, "exact")
            e_reason = "exact equations: " + why
        elif chosen.structure != full.structure and a.model == "auto":
            chosen = ModelChoice(full.structure, chosen.equations)
            s_reason = "2DOF podium: " + why
        else:
            selection.reason = (f"{chosen.label} (forced); differs from the full model by "
                                f"{selection.max_difference:.3g} in θ_max/θc")
            break
    selection.chosen = chosen
    selection.structure_reason = s_reason
    selection.equations_reason = e_reason
    if not selection.reason:
        selection.reason = (f"{chosen.label}: {s_reason}; {e_reason}. Verified against the full model "
                            f"({full.label}) on the {len(selection.verification)} governing records: "
                            f"max |Δ(θ_max/θc)| = {selection.max_difference:.3g}, "
                            f"{selection.verdict_changes} verdict change{'' if selection.verdict_changes == 1 else 's'}.")
    return selection, results


def _verify(selection, system, motions, chosen_results, full_results, run_kw, ids=None):
    rows = []
    for k, (m, r, f) in enumerate(zip(motions, chosen_results, full_results)):
        rows.append({"record": m.name, "index": ids[k] if ids is not None else k,
                     "theta_max_over_theta_c": r.theta_max_over_theta_c,
                     "theta_max_over_theta_c_full": f.theta_max_over_theta_c,
                     "difference": abs(capped_ratio(r.theta_max_over_theta_c, r.overturned)
                                       - capped_ratio(f.theta_max_over_theta_c, f.overturned)),
                     "overturned": r.overturned, "overturned_full": f.overturned})
    selection.verification = rows
    selection.max_difference = max((r["difference"] for r in rows), default=0.0)
    selection.verdict_changes = sum(r["overturned"] != r["overturned_full"] for r in rows)
