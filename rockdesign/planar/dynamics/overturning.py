"""Overturning: the one classification of a run's outcome used by ``simulate``, the suite runner of the
check and the rocking spectra (docs/model.md §6).

* mode ``dynamic`` — |θ| reached π/2 (the column fell);
* mode ``exceeded`` — θ_max ≥ θc without falling (the static rotation capacity, Eq 3.56, was exceeded);
* mode ``none`` — neither.
A run *overturns* by the project's criterion: ``static`` counts both ``exceeded`` and ``dynamic``,
``dynamic`` counts only a fall.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from .layout import S_DYNAMIC, S_IMPACTS_BEFORE_EXCEEDED, S_IMPACTS_BEFORE_OVERTURN, S_THETA_MAX

CRITERIA = ("static", "dynamic")
MODES = ("none", "exceeded", "dynamic")


@njit(cache=True)
def capacity_exceeded(theta_max, theta_c, dynamic):
    """θ_max ≥ θc [rad], or a fall (a fallen column has passed its capacity)."""
    return dynamic or theta_max >= theta_c


def overturned_by(criterion: str, exceeded, dynamic):
    """Overturning by ``criterion`` (``static``: capacity exceeded; ``dynamic``: a fall); booleans or
    boolean arrays alike."""
    return exceeded if criterion == "static" else dynamic


@dataclass(frozen=True)
class Overturning:
    """A run's outcome: ``mode`` (none | exceeded | dynamic), ``overturned`` by the criterion, and the
    impacts before the fall (dynamic) or before θc was first exceeded (None when neither happened or
    the engine did not count them)."""

    mode: str
    overturned: bool
    impacts_before: int | None


def classify(summary: np.ndarray, theta_c: float, criterion: str) -> Overturning:
    """Classify one engine summary row (θ_max, dynamic flag, impact counts) against θc [rad]."""
    dynamic = bool(summary[S_DYNAMIC] != 0.0)
    exceeded = bool(capacity_exceeded(float(summary[S_THETA_MAX]), float(theta_c), dynamic))
    mode = "dynamic" if dynamic else ("exceeded" if exceeded else "none")
    if dynamic:
        before = int(summary[S_IMPACTS_BEFORE_OVERTURN])
    elif exceeded and summary[S_IMPACTS_BEFORE_EXCEEDED] >= 0:
        before = int(summary[S_IMPACTS_BEFORE_EXCEEDED])
    else:
        before = None
    return Overturning(mode, bool(overturned_by(criterion, exceeded, dynamic)), before)
