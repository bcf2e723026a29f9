"""Event location on a step's dense output and on the ground acceleration (numba).

Every accepted step is scanned at interior points; inside each sub-interval a sign change of θ̇
reveals an extremum of θ, so each sub-interval splits into monotone pieces that cross any level at
most once.  Two crossings in one step — which scipy's solve_ivp documents it can miss — are
therefore found as long as θ̇ changes sign at most once between scan points.
"""
from __future__ import annotations

import math

from numba import njit

from ...motions.excitation import (EXC_NONE, EXC_SAMPLES, excitation_end, ground_acceleration,
                                  next_breakpoint)
from .rk import dense_value


@njit(cache=True)
def root_on_dense(y, Q, h, comp, sign, level, xa, xb):
    """x ∈ [xa, xb] where sign·y_comp(x) − level = 0 on the dense output (Illinois method).

    The caller guarantees a sign change between xa and xb.
    """
    fa = sign * dense_value(y, Q, h, xa, comp) - level
    fb = sign * dense_value(y, Q, h, xb, comp) - level
    if fa == 0.0:
        return xa
    if fb == 0.0:
        return xb
    side = 0
    for _ in range(200):
        xm = (xa * fb - xb * fa) / (fb - fa)
        if not (xa < xm < xb) and not (xb < xm < xa):
            xm = 0.5 * (xa + xb)
        fm = sign * dense_value(y, Q, h, xm, comp) - level
        if fm == 0.0:
            return xm
        if (fm > 0.0) == (fb > 0.0):
            xb, fb = xm, fm
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            xa, fa = xm, fm
            if side == 1:
                fb *= 0.5
            side = 1
        if abs(xb - xa) <= 1e-15 * max(1.0, abs(xa)) or abs(fm) <= 1e-300:
            break
    return xa if abs(fa) < abs(fb) else xb


@njit(cache=True)
def _acc_root(t_lo, t_hi, level, kind, xp, samples):
    """Bisection for ü_g(t) = level on [t_lo, t_hi] (a crossing is bracketed; jumps allowed)."""
    f_lo = ground_acceleration(t_lo, kind, xp, samples) - level
    for _ in range(200):
        tm = 0.5 * (t_lo + t_hi)
        if tm <= t_lo or tm >= t_hi:
            break
        fm = ground_acceleration(tm, kind, xp, samples) - level
        if (fm > 0.0) == (f_lo > 0.0) and fm != 0.0:
            t_lo, f_lo = tm, fm
        else:
            t_hi = tm
    return t_hi


@njit(cache=True)
def _extremum(t_a, t_b, kind, xp, samples, sgn):
    """Golden-section search for the maximum (sgn = 1.0) or minimum (sgn = −1.0) of ü_g on [t_a, t_b];
    returns (t, value).  (A float flag: numba would compile one specialisation per literal bool.)"""
    gr = 0.6180339887498949
    c = t_b - gr * (t_b - t_a)
    d = t_a + gr * (t_b - t_a)
    fc = sgn * ground_acceleration(c, kind, xp, samples)
    fd = sgn * ground_acceleration(d, kind, xp, samples)
    for _ in range(80):
        if fc > fd:
            t_b, d, fd = d, c, fc
            c = t_b - gr * (t_b - t_a)
            fc = sgn * ground_acceleration(c, kind, xp, samples)
        else:
            t_a, c, fc = c, d, fd
            d = t_a + gr * (t_b - t_a)
            fd = sgn * ground_acceleration(d, kind, xp, samples)
        if t_b - t_a < 1e-13 * max(1.0, t_a):
            break
    tm = 0.5 * (t_a + t_b)
    return tm, ground_acceleration(tm, kind, xp, samples)


@njit(cache=True)
def next_threshold_crossing(t, t_stop, lo, hi, kind, xp, samples):
    """First time τ ∈ [t, t_stop] with ü_g(τ) ≤ lo or ü_g(τ) ≥ hi; returns (τ, side) or (inf, 0).

    side = +1 when ü_g ≤ lo (uplift to θ > 0), −1 when ü_g ≥ hi.  Records: exact roots on each
    linear segment.  Analytic pulses: scan at T_p/256 with a golden-section check of every local
    extremum, then bisection.  After the excitation has ended ü_g = 0 and nothing can cross.
    """
    a0 = ground_acceleration(t, kind, xp, samples)
    if a0 <= lo:
        return t, 1.0
    if a0 >= hi:
        return t, -1.0
    if kind == EXC_NONE:
        return math.inf, 0.0
    t_exc = excitation_end(kind, xp, samples)
    t_stop = min(t_stop, t_exc)
    if kind == EXC_SAMPLES:
        dt = xp[1]
        scale = xp[0]
        n = samples.shape[0]
        i = int(math.floor(t / dt)) if t > 0.0 else 0
        ts = t
        a_s = a0
        while i < n - 1:
            te = (i + 1) * dt
            if te > t_stop:
                te = t_stop
                a_e = ground_acceleration(te, kind, xp, samples)
            else:
                a_e = scale * samples[i + 1]
            if a_e <= lo or a_e >= hi:
                level = lo if a_e <= lo else hi
                side = 1.0 if a_e <= lo else -1.0
                if a_e == a_s:
                    return ts, side
                tau = ts + (level - a_s) / (a_e - a_s) * (te - ts)
                return min(max(tau, ts), te), side
            if te >= t_stop:
                break
            ts = te
            a_s = a_e
            i += 1
        return math.inf, 0.0
    # analytic pulses
    step = xp[1] / 256.0
    t_prev2 = t
    a_prev2 = a0
    t_prev = t
    a_prev = a0
    tc = t
    while tc < t_stop:
        tb = next_breakpoint(tc, kind, xp, samples)
        tn = min(tc + step, t_stop, tb)
        a_n = ground_acceleration(tn, kind, xp, samples)
        if a_n <= lo:
            return _acc_root(tc, tn, lo, kind, xp, samples), 1.0
        if a_n >= hi:
            return _acc_root(tc, tn, hi, kind, xp, samples), -1.0
        # local extremum at t_prev (between t_prev2 and tn): refine it
        if t_prev > t_prev2:
            if a_prev >= a_prev2 and a_prev >= a_n:
                tm, am = _extremum(t_prev2, tn, kind, xp, samples, 1.0)
                if am >= hi:
                    return _acc_root(t_prev2, tm, hi, kind, xp, samples), -1.0
            if a_prev <= a_prev2 and a_prev <= a_n:
                tm, am = _extremum(t_prev2, tn, kind, xp, samples, -1.0)
                if am <= lo:
                    return _acc_root(t_prev2, tm, lo, kind, xp, samples), 1.0
        t_prev2, a_prev2 = t_prev, a_prev
        t_prev, a_prev = tn, a_n
        tc = tn
    return math.inf, 0.0
