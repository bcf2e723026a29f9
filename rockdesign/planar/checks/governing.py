"""The governing records of a suite: which records the check looks at more closely, in one place.

Two uses, two rankings by θ_max/θc (the rotation-capacity ratio, Eq 3.56), both stable (ties keep
suite order, so results are deterministic):

* :func:`history_records` — the records whose time histories the report shows: those that come
  closest to, or go past, the capacity (ratio capped at 2, so every overturning record ties at the top).
* :func:`model_check_records` — the records on which the chosen structural model is verified
  against the full model (docs/model.md §7): those nearest the capacity *without* overturning first
  (ratio capped at 1.5; an overturning record counts as 1.0), because there the model's small
  differences can change the outcome, while an overturning record overturns in both models.
"""
from __future__ import annotations

HISTORY_RECORDS = 3
"""Time histories in the report."""
MODEL_CHECK_RECORDS = 4
"""Records re-run with the full model to verify a simpler one."""


def history_records(ratios: list[float], n: int = HISTORY_RECORDS) -> list[int]:
    """Indices of the ``n`` records with the largest θ_max/θc (capped at 2)."""
    return sorted(range(len(ratios)), key=lambda i: -min(ratios[i], 2.0))[:n]


def capped_ratio(ratio: float, overturned: bool) -> float:
    """θ_max/θc as the model verification compares it: capped at 1.5, and 1.0 for an overturning run."""
    return min(ratio, 1.0) if overturned else min(ratio, 1.5)


def model_check_records(ratios: list[float], overturned: list[bool], n: int = MODEL_CHECK_RECORDS) -> list[int]:
    """Indices of the ``n`` records nearest the capacity for the model verification (see module docstring)."""
    return sorted(range(len(ratios)), key=lambda i: -capped_ratio(ratios[i], overturned[i]))[:n]
