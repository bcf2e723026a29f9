"""Which outcome counts as overturning under each criterion (SPEC §3, docs/model.md §6, thesis §2.2).

The table, written out: ``static`` — θ_max ≥ θc (Eq 3.56) or a fall; ``dynamic`` — a fall (|θ| = π/2)
only.  Checked on :func:`classify` (one engine summary row, as ``simulate`` and the check use it) and
on :func:`overturned_by` with arrays (as the rocking spectra use it).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.planar.dynamics.layout import (N_SUMMARY, S_DYNAMIC, S_IMPACTS_BEFORE_EXCEEDED, S_IMPACTS_BEFORE_OVERTURN,
                                        S_THETA_MAX)
from rockdesign.planar.dynamics.overturning import CRITERIA, capacity_exceeded, classify, overturned_by

THETA_C = 0.2   # [rad]

# outcome: (θ_max [rad], fell) → mode, overturned under "static", overturned under "dynamic"
TABLE = {
    "well below θc":      ((0.5 * THETA_C, False), "none", False, False),
    "just below θc":      ((THETA_C * (1 - 1e-12), False), "none", False, False),
    "exactly θc":         ((THETA_C, False), "exceeded", True, False),
    "above θc, came back": ((1.5 * THETA_C, False), "exceeded", True, False),
    "fell":               ((math.pi / 2, True), "dynamic", True, True),
}


def _summary(theta_max: float, fell: bool) -> np.ndarray:
    row = np.zeros(N_SUMMARY)
    row[S_THETA_MAX] = theta_max
    row[S_DYNAMIC] = 1.0 if fell else 0.0
    row[S_IMPACTS_BEFORE_OVERTURN] = 3 if fell else -1
    row[S_IMPACTS_BEFORE_EXCEEDED] = 2 if theta_max >= THETA_C else -1
    return row


@pytest.mark.parametrize("outcome", list(TABLE))
@pytest.mark.parametrize("criterion", CRITERIA)
def test_classify_follows_the_criterion_table(outcome, criterion):
    (theta_max, fell), mode, static, dynamic = TABLE[outcome]
    result = classify(_summary(theta_max, fell), THETA_C, criterion)
    assert result.mode == mode
    assert result.overturned is {"static": static, "dynamic": dynamic}[criterion]
    assert result.impacts_before == {"none": None, "exceeded": 2, "dynamic": 3}[mode]


def test_overturned_by_on_arrays_follows_the_same_table():
    theta = np.array([TABLE[k][0][0] for k in TABLE])
    fell = np.array([TABLE[k][0][1] for k in TABLE])
    exceeded = np.array([capacity_exceeded(t, THETA_C, f) for t, f in zip(theta, fell)])
    assert list(overturned_by("static", exceeded, fell)) == [TABLE[k][2] for k in TABLE]
    assert list(overturned_by("dynamic", exceeded, fell)) == [TABLE[k][3] for k in TABLE]

