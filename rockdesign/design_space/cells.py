"""design.json's cells (CONTRACT §6.3, §7.4, §8.1): the cell of a checked variant, of one that could not be
checked and of one left unanalysed, and the words of a passing cell's robustness (SPEC §15)."""
from __future__ import annotations

import re

NOT_NEEDED = (("no incremental analysis: the check ran without margins", "not needed: the design-level suite decides"),
              ("intensities below the design level not analysed (the check ran without margins)",
               "intensities below the design level not analysed (not needed: the design-level suite decides)"))
"""A decided variant's reason: the skipped incremental analysis was not needed (the check did not skip it)."""

QUALIFIED = re.compile(r" \(not covered: (?:c_r sensitivity not analysed|perturbation ensembles not analysed)"
                       r"(?:; (?:c_r sensitivity not analysed|perturbation ensembles not analysed))*\)")
"""The check's "(not covered: c_r sensitivity not analysed …)": in a cell the perturbation draws cover both (a
passing cell's ``robustness`` says how they went; a FAIL needs none), so the cell's reason drops it."""


def checked_cell(kind, variant, variables, result, analyses: int) -> dict:
    """design.json's cell of a checked variant: the variant's values, the kind's numbers and the distance of its
    verdict to the flip (the shared ``acceptance.flip`` of every kind's result, :mod:`rockdesign.acceptance.flip`)."""
    cell = {**base_cell(variant, variables), **kind.grid_cell(result, analyses), **flip_keys(result)}
    if cell["decided_at_design_level"]:
        for old, new in NOT_NEEDED:
            cell["reason"] = cell["reason"].replace(old, new)
    cell["reason"] = QUALIFIED.sub("", cell["reason"])
    return cell


def base_cell(variant, variables) -> dict:
    """The keys every cell has: its index in the grid, its values (SI) and labels, the notes on replaced keys."""
    values = variant.values if variant.values is not None else \
        {v.key: v.si[k] for v, k in zip(variables, variant.index)}
    labels = variant.labels if variant.labels is not None else \
        {v.key: v.label(k) for v, k in zip(variables, variant.index)}
    return {"index": list(variant.index), "values": dict(values), "labels": dict(labels), "notes": list(variant.notes)}


def flip_keys(result) -> dict:
    """The cell's distance to the flip from its check's ``acceptance`` section (CONTRACT §8.1)."""
    flip = (getattr(result, "acceptance", None) or {}).get("flip") or {}
    return {"flip_margin": flip.get("value"), "flip_margin_is_lower_bound": bool(flip.get("lower_bound")),
            "flip_governing": flip.get("governing"), "flip_note": flip.get("note")}


def not_passing() -> dict:
    """The robustness keys of a cell that does not pass (CONTRACT §7.4: ``robust`` is null unless PASS)."""
    return {"analysed": True, "robust": None, "draws": {"n": 0, "failed": 0}, "robustness": None}


def margin_undecided(cell: dict, precision: float) -> str | None:
    """Why a passing cell's collapse margin cannot be told from its requirement, or None.  The ACMR comes from
    scans that bisect each record's first overturning intensity to ``precision`` (``[analysis]
    margin_precision``); an ACMR above its requirement by less than that resolution (plus the draws'
    ± 0.1 % amplitude) is not a robust PASS — the rule the grid states instead of scanning every draw.  An ACMR
    below its requirement in a passing cell is informative (the acceptance rule is another one) and is left
    alone."""
    acmr, need = cell.get("acmr"), cell.get("acmr_required")
    if acmr is None or not need:
        return None
    from ..acceptance.perturbations import AMPLITUDE_VARIATION
    if need <= acmr < need * (1.0 + precision + AMPLITUDE_VARIATION):   # (below its requirement the margin did not
        # decide the PASS: it informs under another acceptance rule, e.g. the binomial bound)
        return (f"ACMR {acmr:.4g} within the scans' resolution ({100 * precision:g} % + {100 * AMPLITUDE_VARIATION:g} %"
                f") of the {need:.4g} required")
    return None


def robustness(draws: dict | None, near: str | None = None) -> dict:
    """The robustness keys of a passing cell from its perturbation draws (``grid_draws``), or from a margin
    too close to its requirement (``near``; no draws run)."""
    if near is not None:
        return {"robust": False, "draws": {"n": 0, "failed": 0}, "robustness": f"not robust: {near}"}
    n, failed, size = draws["n"], draws["failed"], draws.get("size", draws["n"])
    if size == 0:
        return {"robust": False, "draws": {"n": 0, "failed": 0},
                "robustness": "not robust: no perturbation draws ([analysis] ensemble_size = 0 and no c_r draws)"}
    if failed:
        return {"robust": False, "draws": {"n": n, "failed": failed},
                "robustness": f"not robust: fails in {failed} of {n} draws (stopped at the first that fails, "
                              f"{size} planned; {draws['first_failure']})"}
    return {"robust": True, "draws": {"n": n, "failed": 0},
            "robustness": f"robust: passes in all {n} perturbation draws ("
                          f"{draws.get('what') or 'as the check draws them'})"}


EMPTY = {**dict.fromkeys(("governing", "acmr", "acmr_required", "p_collapse_design", "target_p_collapse",
                          "n_unacceptable", "allowed_unacceptable", "n_ground_motions", "superstructure_shear_p84",
                          "superstructure_drift_p84", "median_theta_max_over_theta_c", "model", "flip_margin",
                          "material", "demand",
                          "flip_governing", "flip_note")), "flip_margin_is_lower_bound": False}
"""The check's numbers of a cell that has none (INVALID, ERROR)."""




def inferred_cell(variant, variables, between: str) -> dict:
    """The cell of a variant left unanalysed between agreeing neighbours that are far from their flip (SPEC §15):
    no verdict word, only the region its neighbours agree on (``between``)."""
    from ..acceptance.flip import FAR
    return {**base_cell(variant, variables), **EMPTY, "verdict": None,
            "reason": f"not analysed: the analysed variants around it are all {between} and far from their flip "
                      f"(flip margin ≥ {FAR:g}, or ≤ {1 / FAR:g} for a FAIL)",
            "decided_at_design_level": False, "n_failed_analyses": 0, "analyses": 0, "analyses_saved": 0,
            "analysed": False, "between": between, "robust": None, "draws": {"n": 0, "failed": 0},
            "robustness": None, "resumed": False}


def invalid_cell(variant, variables) -> dict:
    """The cell of a variant the project rules do not allow (its loader's message)."""
    return {**base_cell(variant, variables), **EMPTY, "verdict": "INVALID", "reason": variant.invalid,
            "decided_at_design_level": False, "n_failed_analyses": 0, "analyses": 0, "analyses_saved": 0,
            **not_passing()}
