"""Ground acceleration for the reference integrator: integration stretches and uplift search.

ü_g(t) is the shared definition of :mod:`rockdesign.motions.excitation` (records piecewise linear
between samples and zero outside, analytic pulses exact; SPEC §0, §4).  This module only decides
where one ``solve_ivp`` call may run (a record's sample interval, or up to a pulse's kink) and
finds when a body at rest starts to rock (SPEC §2 "Uplift", §3.6).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from rockdesign.motions.excitation import (EXC_NONE, EXC_SAMPLES, ground_acceleration,
                                           ground_acceleration_array, next_breakpoint)
from rockdesign.motions.motion import GroundMotion

PULSE_SEARCH_POINTS_PER_PERIOD = 400
"""Grid density of the uplift search for analytic pulses (then refined by brentq)."""


def _zero(t):
    return 0.0


class GroundInput:
    """ü_g(t) [m/s²] of one :class:`GroundMotion` as the reference integrator uses it.

    Args:
        motion: the ground motion.
        split_at_samples: end every integration stretch at the next record sample (SPEC §9); with
            False a record is integrated across samples (to demonstrate the accuracy loss).
    """

    def __init__(self, motion: GroundMotion, split_at_samples: bool = True):
        self.kind = motion.kind
        self.params = np.asarray(motion.params, dtype=np.float64)
        self.samples = np.asarray(motion.samples, dtype=np.float64)
        self.duration = motion.duration
        self.is_record = motion.is_record
        self.split = split_at_samples
        if self.is_record:
            self.dt = float(self.params[1])
            self.values = self.params[0] * self.samples

    def accel(self, t: float) -> float:
        """ü_g(t) [m/s²]."""
        return ground_acceleration(t, self.kind, self.params, self.samples)

    def stretch(self, t: float, t_end: float):
        """(t_stop, accel): the next stretch [t, t_stop] with a smooth ü_g and its evaluator.

        Records split at samples get the exact linear segment a_i + (t − t_i)(a_{i+1} − a_i)/Δt;
        pulses stop at their kinks (start/end of a sine or cycloidal pulse).
        """
        if self.kind == EXC_NONE:
            return t_end, _zero
        if self.is_record and not self.split:
            return t_end, self.accel
        tb = next_breakpoint(t, self.kind, self.params, self.samples)
        if not self.is_record:
            return min(tb, t_end), self.accel
        if math.isinf(tb):
            return t_end, _zero
        i = int(round(tb / self.dt)) - 1
        t_i = i * self.dt
        a_i = float(self.values[i])
        slope = (float(self.values[i + 1]) - a_i) / self.dt
        return min(tb, t_end), (lambda tt: a_i + slope * (tt - t_i))

    def find_uplift(self, t0: float, lower: float, upper: float, t_limit: float,
                    immediate: bool = True):
        """First time t ≥ t0 (≤ t_limit) where ü_g ≤ lower (uplift to θ > 0, side +1) or
        ü_g ≥ upper (side −1), for constant thresholds (rigid superstructure; lower < 0 < upper).

        Returns ``(t, side)`` or None.  With ``immediate`` a criterion already met at t0 counts;
        otherwise only a fresh crossing after t0 does.  Records: exact root in the linear segment.
        Pulses: grid of 400 points per T_p, refined with brentq.
        """
        if self.kind == EXC_NONE:
            return None
        a0 = self.accel(t0)
        if immediate and (a0 <= lower or a0 >= upper):
            return t0, (1 if a0 <= lower else -1)
        t_limit = min(t_limit, self.duration)
        if t0 >= t_limit:
            return None
        if self.is_record:
            return self._find_in_record(t0, a0, lower, upper, t_limit)
        return self._find_in_pulse(t0, lower, upper, t_limit)

    def _find_in_record(self, t0, a0, lower, upper, t_limit):
        dt, vals = self.dt, self.values
        k0 = int(math.floor(t0 / dt)) + 1
        while k0 * dt <= t0 and k0 < vals.size:
            k0 += 1
        rest = vals[k0:]
        hits = np.flatnonzero((rest <= lower) | (rest >= upper))
        if hits.size == 0:
            return None
        k = k0 + int(hits[0])
        t_a = max(t0, (k - 1) * dt)
        a_a = a0 if t_a == t0 else float(vals[k - 1])
        target, side = (lower, 1) if vals[k] <= lower else (upper, -1)
        t_k = k * dt
        if vals[k] == a_a:
            t_cross = t_k
        else:
            t_cross = t_a + (target - a_a) / (float(vals[k]) - a_a) * (t_k - t_a)
        t_cross = min(max(t_cross, t_a), t_k)
        return (t_cross, side) if t_cross <= t_limit else None

    def _find_in_pulse(self, t0, lower, upper, t_limit):
        h = float(self.params[1]) / PULSE_SEARCH_POINTS_PER_PERIOD
        start = t0
        while start < t_limit:
            ts = start + h * np.arange(1, 2001)
            ts = ts[ts < t_limit]
            ts = np.append(ts, min(start + 2001 * h, t_limit))
            a = ground_acceleration_array(ts, self.kind, self.params, self.samples)
            hits = np.flatnonzero((a <= lower) | (a >= upper))
            if hits.size:
                j = int(hits[0])
                target, side = (lower, 1) if a[j] <= lower else (upper, -1)
                t_a = start if j == 0 else ts[j - 1]
                f = lambda t: self.accel(t) - target  # noqa: E731
                if f(t_a) * f(ts[j]) > 0.0:   # touched within round-off at the grid point
                    return ts[j], side
                return brentq(f, t_a, ts[j], xtol=1e-15, rtol=4 * np.finfo(float).eps), side
            start = ts[-1]
        return None
