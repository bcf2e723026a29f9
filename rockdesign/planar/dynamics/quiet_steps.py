"""Quiet steps: accepted steps of the event-driven integrator whose dense output need not be scanned.

A rocking step is *quiet* when the quintic Hermite interpolant of its end values (θ, θ̇, θ̈ at both
ends) cannot hold an event: |dθ/dx| stays above :data:`QUIET_MARGIN` of the larger end rate at every
scan point and no event level lies between the ends.  At rest, a podium's step is quiet when the
Eq 4.7 uplift criterion, read from the same interpolant of u_T, stays below its threshold.  Split from
:mod:`rockdesign.planar.dynamics.engine` (which calls these kernels once per accepted step).
"""
from __future__ import annotations


import numpy as np
from numba import njit

from ...motions.excitation import (ground_acceleration)
from .eom import (uplift_condition)
from .transitions import (crossing_event, top_displacement)





QUIET_MARGIN = 0.05
"""A step is *quiet* (no dense output needed) when the quintic Hermite interpolant of its end values
keeps |dθ/dx| above this fraction of the larger end rate at every scan point (see :func:`quiet_step`)."""


@njit(cache=True)
def hermite_ends(y, y_new, f0, f1, h, i, sign):
    """End data (p0, d0, c0, p1, d1, c1) of component ``i`` (its rate is ``i + 1``) over a step of ``h`` [s],
    times ``sign``: values, x-derivatives and second x-derivatives (x = (t − t0)/h), from the states
    and their derivatives f at both ends."""
    return (sign * y[i], sign * y[i + 1] * h, sign * f0[i + 1] * h * h,
            sign * y_new[i], sign * y_new[i + 1] * h, sign * f1[i + 1] * h * h)


@njit(cache=True)
def hermite_rate(x, p0, d0, c0, p1, d1, c1):
    """d/dx of the quintic Hermite interpolant on [0, 1] with values p, first derivatives d and second
    derivatives c (all with respect to x) at the ends."""
    x2 = x * x
    x3 = x2 * x
    x4 = x3 * x
    return ((p1 - p0) * (30.0 * x2 - 60.0 * x3 + 30.0 * x4) + d0 * (1.0 - 18.0 * x2 + 32.0 * x3 - 15.0 * x4)
            + c0 * 0.5 * (2.0 * x - 9.0 * x2 + 12.0 * x3 - 5.0 * x4) + d1 * (-12.0 * x2 + 28.0 * x3 - 15.0 * x4)
            + c1 * 0.5 * (3.0 * x2 - 8.0 * x3 + 5.0 * x4))


@njit(cache=True)
def hermite_value(x, p0, d0, c0, p1, d1, c1):
    """The quintic Hermite interpolant on [0, 1] (ends: values p, x-derivatives d, second derivatives c)."""
    x2 = x * x
    x3 = x2 * x
    x4 = x3 * x
    x5 = x4 * x
    return (p0 * (1.0 - 10.0 * x3 + 15.0 * x4 - 6.0 * x5) + d0 * (x - 6.0 * x3 + 8.0 * x4 - 3.0 * x5)
            + c0 * 0.5 * (x2 - 3.0 * x3 + 3.0 * x4 - x5) + p1 * (10.0 * x3 - 15.0 * x4 + 6.0 * x5)
            + d1 * (-4.0 * x3 + 7.0 * x4 - 3.0 * x5) + c1 * 0.5 * (x3 - 2.0 * x4 + x5))


@njit(cache=True)
def quiet_step(h, y, y_new, f0, f1, m_scan, side, phase, curved, beta, theta_ot, theta_c, exceeded, two_dof,
                drift_slope, drift_max, sp):
    """True when an accepted rocking step needs no dense output: the scan of :func:`scan_rocking_step`
    would find nothing but the peak candidate at the step's end.

    The test uses only the step's end values and derivatives (θ, θ̇, θ̈ and u_T, u̇_T, ü_T from the
    FSAL stage — no function evaluation): their quintic Hermite interpolant (5th order) must keep θ̇
    of one sign with a margin of :data:`QUIET_MARGIN` at the scan points (so the 7th-order dense
    output, which differs from it by far less, has no extremum there either), sθ must cross no event
    level or θc between the ends (θ is then monotone, so the ends decide), and — for the 2DOF podium —
    the drift |u_T − u_B(θ)| on the interpolants must stay below the drift maximum at the scan points
    (margin 1e-6 of it, thousands of times the interpolants' difference from the dense output).  Any
    doubt returns False and the step is scanned as before: results are unchanged, and DOP853 saves
    its 3 extra evaluations of the 7th-order interpolant on most steps.
    """
    s0, d0, c0, s1, d1, c1 = hermite_ends(y, y_new, f0, f1, h, 0, side)
    margin = QUIET_MARGIN * max(abs(d0), abs(d1))
    if margin == 0.0 or d0 * d1 <= 0.0 or min(abs(d0), abs(d1)) < margin:
        return False
    for k in range(1, m_scan):
        r = hermite_rate(k / m_scan, s0, d0, c0, s1, d1, c1)
        if r * d0 <= 0.0 or abs(r) < margin:
            return False
    kind, _ = crossing_event(s0, s1, curved, phase, beta, theta_ot)
    if kind != 0:
        return False
    if s1 > s0 and not exceeded and s0 < theta_c <= s1:
        return False
    if two_dof:
        # the drift |u_T − u_B(θ)| must not reach the maximum at the scan points (checked on the
        # interpolants, with a margin far above their difference from the dense output) nor at the end
        tol = 1e-6 * drift_max
        s_abs = max(abs(s0), abs(s1))
        u0, v0, a0, u1, v1, a1 = hermite_ends(y, y_new, f0, f1, h, 2, 1.0)
        for k in range(1, m_scan + 1):
            x = k / m_scan
            u = u1 if k == m_scan else hermite_value(x, u0, v0, a0, u1, v1, a1)
            if abs(u) + drift_slope * s_abs + tol <= drift_max:
                continue
            sk = s1 if k == m_scan else hermite_value(x, s0, d0, c0, s1, d1, c1)
            if abs(u - side * top_displacement(sk, sp)) + tol > drift_max:
                return False
    return True


@njit(cache=True)
def rest_uplift_coefficients(sp):
    """(2 × 4) coefficients (c₀, c_ag, c_u, c_u̇) of the uplift criterion at rest on the sides +1 (row 0)
    and −1 (row 1): :func:`~.eom.uplift_condition` is affine in (ü_g, u_T, u̇_T) at θ = θ̇ = 0 (Eq 4.7),
    so s·θ̈ = c₀ + c_ag ü_g + c_u u_T + c_u̇ u̇_T.  Used only to decide that a step is quiet (a filter
    with a margin, :func:`quiet_rest`); uplift itself is located with ``uplift_condition``."""
    c = np.zeros((2, 4))
    for k in range(2):
        s = 1.0 - 2.0 * k
        d = uplift_condition(s, 0.0, 0.0, 0.0, sp)
        c[k, 0] = d
        c[k, 1] = uplift_condition(s, 1.0, 0.0, 0.0, sp) - d
        c[k, 2] = uplift_condition(s, 0.0, 1.0, 0.0, sp) - d
        c[k, 3] = uplift_condition(s, 0.0, 0.0, 1.0, sp) - d
    return c


@njit(cache=True)
def quiet_rest(t, h, y, y_new, f0, f1, m_scan, hyst, kind, xp, samples, coef):
    """True when an accepted step of the resting 2DOF podium needs no dense output: the uplift criterion
    (Eq 4.7, either side; affine, ``coef`` from :func:`rest_uplift_coefficients`) stays below the
    hysteresis by a margin of 1e-6 of its size (plus 1e-12 of its terms, for round-off) at the scan
    points of :func:`scan_podium_uplift`, with u_T, u̇_T from the quintic Hermite interpolant of the
    step's end values (no function evaluation) and ü_g exact.  False in any doubt (the step is then
    scanned)."""
    u0, v0, a0, u1, v1, a1 = hermite_ends(y, y_new, f0, f1, h, 2, 1.0)
    for k in range(1, m_scan + 1):
        x = k / m_scan
        if k == m_scan:
            ut = y_new[2]
            utd = y_new[3]
        else:
            ut = hermite_value(x, u0, v0, a0, u1, v1, a1)
            utd = hermite_rate(x, u0, v0, a0, u1, v1, a1) / h
        ag = ground_acceleration(t + x * h, kind, xp, samples)
        tp = coef[0, 1] * ag + coef[0, 2] * ut + coef[0, 3] * utd
        tm = coef[1, 1] * ag + coef[1, 2] * ut + coef[1, 3] * utd
        cp = coef[0, 0] + tp - hyst
        cm = coef[1, 0] + tm - hyst
        tol = 1e-6 * (abs(cp) + abs(cm)) + 1e-12 * (abs(coef[0, 0]) + abs(coef[1, 0]) + abs(tp) + abs(tm) + hyst)
        if cp >= -tol or cm >= -tol:
            return False
    return True
