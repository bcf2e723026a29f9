"""The distance of a verdict to its flip (SPEC §15, CONTRACT §8.1, docs/design.md "Distance to the flip").

The §16.4.1.1 count is a step function of the design variables in a chaotic system, so a verdict alone does not
say how close it is to changing.  Its distance is expressed as one number, a factor λ on the design intensity
(every record of the suite multiplied by λ) at which the governing rule would change its answer:

- the count: λ_count, the factor at which the number of ground motions unacceptable *at or below* it first
  exceeds the allowance A — the (A+1)-th smallest first unacceptable factor over the ground motions (a ground
  motion's first unacceptable factor is the least of its components' first overturning factors, found by the
  incremental scans, or 1 when its design-level analysis overturned below that);
- the collapse margin (where it governs): λ_margin = ACMR / ACMR_required — multiplying the design intensity
  S_MT by λ divides ACMR = Ŝ_CT/S_MT by λ (Ŝ_CT is an intensity of the records, not of the design);
- the flip margin is the smaller of the two: > 1 where the verdict passes (it fails only at a larger
  intensity), ≤ 1 where it fails (it would pass, at the latest, below that factor).

A PASS whose flip margin is ≤ 1 is possible and says something true: more ground motions than allowed overturn
in bands *below* the design level, though not at it — the count holds only at the exact design level.

The scans resolve each first overturning factor to ``margin_precision`` (bisection) on a grid of ratio
:data:`~rockdesign.acceptance.scans.SCAN_RATIO` (a band narrower than that can be missed, as in the check).
Where fewer than A+1 ground motions overturn within the scan, λ_count is only known to exceed the scan's limit
(a lower bound, flagged); likewise λ_margin when Ŝ_CT is only bounded below.
"""
from __future__ import annotations

import math

from .rule import AcceptanceRule, ground_motion_of, probability_bound

FAR = 1.25
"""A verdict is far from its flip when its flip margin is ≥ FAR (a PASS) or ≤ 1/FAR (a FAIL): the design intensity
would have to change by a quarter before the verdict does.  The design grid infers a cell's verdict from its
neighbours only between cells that are far from their flip (docs/design.md "Inference only where it is safe")."""


def allowance(rule: AcceptanceRule, n_ground_motions: int) -> int:
    """A: the most ground motions with an unacceptable response the rule accepts — §16.4.1.1's allowance (asce7),
    or the largest k whose one-sided 95 % bound of P(overturn) over ``n_ground_motions`` stays within the limit
    (binomial; −1 when even k = 0 does not)."""
    if rule.method != "binomial":
        return rule.allowed
    k = -1
    while k + 1 <= n_ground_motions and probability_bound(k + 1, n_ground_motions) <= rule.binomial_limit:
        k += 1
    return k


def _gm_rows(outcomes, margins) -> dict[str, dict]:
    """Per ground motion: its first unacceptable factor (None: none found) and how far it was scanned."""
    rows: dict[str, dict] = {}
    for o, m in zip(outcomes, margins):
        g = ground_motion_of(o)
        row = rows.setdefault(g, {"first": None, "scanned": math.inf})
        s = None if m is None else m.overturn_scale
        if o.run.overturned and (s is None or s > 1.0):
            s = 1.0
        if s is not None:
            row["first"] = s if row["first"] is None else min(row["first"], s)
        elif m is not None:
            row["scanned"] = min(row["scanned"], m.scanned_up_to)
        else:
            row["scanned"] = min(row["scanned"], 1.0)   # only the design level is known
    return rows


def count_flip(rule: AcceptanceRule, outcomes, margins) -> dict:
    """λ_count of the module docstring from the outcomes (``id``, ``ground_motion``, ``run.overturned``) and their
    scans (a :class:`~rockdesign.acceptance.scans.Margin` each, or None where only the design level ran):
    ``{"value", "lower_bound", "allowance", "n_ground_motions"}``; ``value`` None when nothing was scanned."""
    rows = _gm_rows(outcomes, margins)
    a = allowance(rule, len(rows))
    out = {"value": None, "lower_bound": False, "allowance": a, "n_ground_motions": len(rows)}
    if all(m is None for m in margins):
        return out                           # no incremental analysis: nothing below or above the design level
    if a < 0:
        out["value"] = 0.0
        return out
    firsts = sorted(r["first"] for r in rows.values() if r["first"] is not None)
    candidate = firsts[a] if len(firsts) > a else math.inf
    # a ground motion not found overturning is known safe only up to where it was scanned
    unknown = min((r["scanned"] for r in rows.values() if r["first"] is None), default=math.inf)
    if unknown < candidate:
        out.update(value=unknown, lower_bound=True)
    else:
        out["value"] = candidate
    return out


def flip_margin(rule: AcceptanceRule, outcomes, margins, collapse_margin: dict | None = None,
                margin_governs: bool = True) -> dict:
    """The distance to the flip of a check's verdict (module docstring), results.json ``acceptance.flip``:
    ``{"value", "lower_bound", "governing": "count" | "collapse margin" | None, "count", "margin", "note"}``.

    Args:
        outcomes: the completed analyses (``id``, ``ground_motion``, ``run.overturned``).
        margins: their incremental scans (:class:`~rockdesign.acceptance.scans.Margin` or None), aligned.
        collapse_margin: the ``collapse_margin`` section (``ACMR``, ``ACMR_target``, ``CMR_is_lower_bound``)
            or None.
        margin_governs: the collapse margin is a governing criterion of the rule (asce7 with an incremental
            analysis).
    """
    count = count_flip(rule, outcomes, margins)
    lam_margin, margin_low = None, False
    if margin_governs and collapse_margin is not None and collapse_margin.get("ACMR_target"):
        lam_margin = collapse_margin["ACMR"] / collapse_margin["ACMR_target"]
        margin_low = bool(collapse_margin.get("CMR_is_lower_bound"))
    parts = [(count["value"], count["lower_bound"], "count"), (lam_margin, margin_low, "collapse margin")]
    parts = [p for p in parts if p[0] is not None]
    if not parts:
        return {"value": None, "lower_bound": False, "governing": None, "count": count, "margin": None,
                "note": "not computed: no incremental analysis (only the design level was analysed)"}
    exact = [p for p in parts if not p[1]]
    best = min(parts, key=lambda p: p[0])
    # a lower bound that lies above an exact value does not decide the minimum
    lower = best[1] and not any(p[0] <= best[0] for p in exact)
    note = _note(best, lower, count)
    if margin_governs and lam_margin is None and best[2] == "count" and best[0] <= 1.0:
        note += ("; the collapse margin was not needed (the count decides the FAIL), so the verdict passes at "
                 "most below this factor")
    return {"value": best[0], "lower_bound": lower, "governing": best[2], "count": count,
            "margin": None if lam_margin is None else {"value": lam_margin, "lower_bound": margin_low},
            "note": note}


def _note(best, lower: bool, count: dict) -> str:
    value, _, what = best
    bound = "at least " if lower else ""
    a = count["allowance"]
    if what == "count":
        head = (f"the count of ground motions unacceptable at or below λ × the design intensity exceeds the "
                f"allowance ({a}) at λ = {bound}{value:.3g}")
    else:
        head = f"the collapse margin reaches its requirement at λ = ACMR / ACMR required = {bound}{value:.3g}"
    if lower:
        head += " (a lower bound: the scans found no flip below their limit)"
    return head


def far_from_flip(cell: dict, far: float = FAR) -> bool:
    """True when an analysed cell's verdict is far from its flip (:data:`FAR`): a PASS with flip margin ≥ far, a
    FAIL with flip margin ≤ 1/far.  A cell without a flip margin is never far."""
    x = cell.get("flip_margin")
    if x is None:
        return False
    if cell.get("verdict") == "PASS":
        return x >= far
    if cell.get("verdict") == "FAIL":
        return x <= 1.0 / far and not cell.get("flip_margin_is_lower_bound")
    return False
