"""When a resting cylinder lifts off: the first time the resultant ground acceleration reaches the uplift
acceleration (Eq 5.24), exactly on a piecewise-linear record pair and by a fine scan under pulses.
Split from :mod:`rockdesign.cylinder.kernel`, whose integrator calls it while the cylinder rests.
"""
from __future__ import annotations

import math

from numba import njit

from ..motions.excitation import EXC_NONE, EXC_SAMPLES, ground_acceleration


@njit(cache=True)
def uplift_time(t, t_stop, up, kind, params, sx, sy, dirx, diry):
    """First time in [t, t_stop) at which √(ü_gx² + ü_gy²) ≥ up (Eq 5.24), or +inf."""
    if kind == EXC_NONE:
        return math.inf
    if kind == EXC_SAMPLES:
        dt = params[1]
        npts = sx.shape[0]
        i0 = int(math.floor(t / dt + 1e-9))
        for i in range(max(i0, 0), npts - 1):
            ta = i * dt
            if ta + dt <= t:
                continue
            if ta >= t_stop:
                return math.inf
            ax0 = params[0] * sx[i] * dirx
            ay0 = params[0] * sy[i] * diry
            dx = params[0] * sx[i + 1] * dirx - ax0
            dy = params[0] * sy[i + 1] * diry - ay0
            # |a0 + s d|² = up², s ∈ [s0, 1]
            s0 = max(0.0, (t - ta) / dt)
            qa = dx * dx + dy * dy
            qb = 2.0 * (ax0 * dx + ay0 * dy)
            qc = ax0 * ax0 + ay0 * ay0 - up * up
            if qc + s0 * (qb + s0 * qa) >= 0.0:
                return ta + s0 * dt
            if qa > 0.0:
                disc = qb * qb - 4.0 * qa * qc
                if disc >= 0.0:
                    r = (-qb + math.sqrt(disc)) / (2.0 * qa)      # the rising root
                    if s0 <= r <= 1.0:
                        return ta + r * dt
        return math.inf
    # analytic pulse along (dirx, diry): scan and bisect
    hs = params[1] / 2000.0
    ta = t
    while ta < t_stop:
        tb = min(ta + hs, t_stop)
        ga = abs(ground_acceleration(tb, kind, params, sx))
        if ga >= up:
            lo, hi = ta, tb
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                if abs(ground_acceleration(mid, kind, params, sx)) >= up:
                    hi = mid
                else:
                    lo = mid
            return hi
        ta = tb
    return math.inf
