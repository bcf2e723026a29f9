"""Accuracy metrics of one run against a reference (pure functions on arrays; SI units, radians).

* ``error_theta`` — max |θ(t_i) − θ_ref(t_i)| [rad] over the points t_i where the method reports θ
  (our engine: its output grid and every event; scipy: every accepted step and event).  Events are
  included, so a wrong impact time shows up as |θ_ref| at the method's impact instant.
* ``error_theta_max`` — |θ_max − θ_max,ref| [rad] of the peak tilt.
* ``error_impact_times`` — max |t_k − t_k,ref| [s] over the first :data:`IMPACTS_COMPARED` impacts
  of the reference.  An impact the method does not produce counts as happening at the end of the
  analysis (a finite, conservative stand-in for "missed").  0 when the reference has no impact and
  neither has the method.
* ``overturn_agrees`` — the method's overturning mode (none / exceeded / dynamic, SPEC §3.7) equals
  the reference's.
"""
from __future__ import annotations

import math

import numpy as np

IMPACTS_COMPARED = 5
"""Number of leading impacts whose times are compared."""


def max_abs_difference(values, reference_values) -> float:
    """max |a_i − b_i| over paired samples (same units as the inputs); NaN pairs give inf."""
    a = np.asarray(values, dtype=float)
    b = np.asarray(reference_values, dtype=float)
    if a.shape != b.shape:
        raise ValueError(f"shapes differ: {a.shape} vs {b.shape}")
    if a.size == 0:
        return 0.0
    d = np.abs(a - b)
    if not np.all(np.isfinite(d)):
        return math.inf
    return float(d.max())


def theta_max_error(theta_max: float, reference_theta_max: float) -> float:
    """|θ_max − θ_max,ref| [rad]."""
    return abs(float(theta_max) - float(reference_theta_max))


def impact_time_error(impact_times, reference_impact_times, t_end: float, count: int = IMPACTS_COMPARED) -> float:
    """Max error [s] of the first ``count`` impact times (missing impacts count as at ``t_end``).

    Args:
        impact_times: the method's impact times [s] (any order; sorted here).
        reference_impact_times: the reference's impact times [s].
        t_end: end of the analysis [s], the stand-in time of a missed impact.
        count: number of leading reference impacts compared.
    """
    ref = np.sort(np.asarray(reference_impact_times, dtype=float))[:count]
    got = np.sort(np.asarray(impact_times, dtype=float))[:count]
    if ref.size == 0:
        # spurious impacts (the reference has none): their distance to the end of the analysis
        return float(np.max(np.abs(t_end - got))) if got.size else 0.0
    padded = np.full(ref.size, float(t_end))
    padded[:got.size] = got[:ref.size]
    return float(np.max(np.abs(padded - ref)))


def overturn_agreement(mode: str, reference_mode: str) -> bool:
    """True when the overturning modes (``none`` | ``exceeded`` | ``dynamic``) agree."""
    return str(mode) == str(reference_mode)


def error_history(t, theta, reference_theta):
    """(t, |θ − θ_ref|) sorted by time — the error-versus-time curve of thesis Fig B.3."""
    t = np.asarray(t, dtype=float)
    order = np.argsort(t, kind="stable")
    d = np.abs(np.asarray(theta, dtype=float) - np.asarray(reference_theta, dtype=float))
    return t[order], d[order]


def cost_at_accuracy(points: list[dict], target: float, key: str = "error_theta") -> float | None:
    """Smallest ``seconds`` among the points whose ``key`` error is ≤ ``target`` (None if none is)."""
    ok = [p["seconds"] for p in points if p.get(key) is not None and p[key] <= target]
    return min(ok) if ok else None


def median_seconds(samples) -> float:
    """Median of repeated wall times [s]."""
    return float(np.median(np.asarray(samples, dtype=float)))
