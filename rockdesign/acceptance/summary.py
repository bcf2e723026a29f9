"""The ``acceptance`` section of results.json (CONTRACT §6.1, §8.1), shared by every kind: the rule, the numbers
that decided, whether every governing criterion was evaluated, the table per ground motion and the distance of
the verdict to its flip (:mod:`rockdesign.acceptance.flip`)."""
from __future__ import annotations

from .collapse_margin import MEDIAN_DEFINITION
from .flip import flip_margin
from .rule import (AcceptanceRule, ground_motion_table, ground_motions_in_order, probability_bound,
                   unacceptable_ground_motions)


def acceptance_summary(rule: AcceptanceRule, items, verdict, valid, margin: dict | None, scans=None) -> dict:
    """The ``acceptance`` section of results.json (CONTRACT §6.1): the rule, the numbers that decided,
    whether every governing criterion was evaluated, the per-ground-motion table (``valid``: the
    outcomes whose analysis completed) and the distance of the verdict to its flip (``flip_margin``,
    :mod:`rockdesign.acceptance.flip`; ``scans``: the incremental scans it reads, aligned with ``valid`` —
    by default each outcome's ``margin``; a design-grid cell decided at the design level scans below it for
    the flip alone)."""
    flip = flip_margin(rule, valid, [getattr(o, "margin", None) for o in valid] if scans is None else scans,
                       margin, margin_governs=rule.method == "asce7" and rule.collapse_margin_available)
    over = {o.id for o in valid if o.run.overturned}
    bad = unacceptable_ground_motions(valid, over)
    n = len(ground_motions_in_order(valid))
    governing = [i for i in items if i.governs_verdict]
    evaluated = not verdict.not_covered and all(i.evaluated for i in governing)
    acmr = None if margin is None else margin["ACMR"]
    need = None if margin is None else margin["ACMR_target"]
    robustness = {i.key: [{"run": lab, "holds": h} for lab, h in i.perturbations]
                  for i in items if i.role == "robustness"}
    return {
        **rule.as_json(), "label": rule.label,
        "design_intensity_is_mce_r": True,
        "n_ground_motions": n, "n_records": len(valid),
        "n_unacceptable": len(bad), "unacceptable_ground_motions": bad,
        "acmr": acmr if rule.collapse_margin_available else None,
        "acmr_required": need if rule.collapse_margin_available else None,
        "acmr_is_lower_bound": None if margin is None else margin["CMR_is_lower_bound"],
        "p_collapse_design": None if margin is None or not rule.collapse_margin_available
        else margin["p_collapse_design"],
        "median_definition": MEDIAN_DEFINITION,
        "acmr_fitted": None if margin is None or not rule.collapse_margin_available else margin["ACMR_fitted"],
        "p_collapse_design_fitted": None if margin is None or not rule.collapse_margin_available
        else margin["p_collapse_design_fitted"],
        "binomial_bound": probability_bound(len(bad), n),
        "governing_criteria": [i.key for i in governing], "not_evaluated": list(verdict.not_covered)
        + [i.key for i in governing if not i.evaluated],
        "evaluated": evaluated, "passed": verdict.verdict == "PASS", "verdict": verdict.verdict,
        "reason": verdict.reason, "robust": verdict.robust, "perturbed_draws": robustness,
        "ground_motions": ground_motion_table(valid),
        "flip_margin": flip["value"], "flip": flip,
    }
