"""One DOP853 step of the cylinder's equations, its error norm and its 7th-order dense output (numba).

Split from :mod:`rockdesign.cylinder.kernel`, whose integrator calls them.  The Runge–Kutta tableau
(Hairer's DOP853: 12 stages, error estimators of order 5 and 3, 3 extra stages for the dense output) is the
one the planar engine steps with (:mod:`rockdesign.dop853_tableau`, written out from Hairer & Wanner's ``dop853.f``); within a step a record's ü_g is linear (no step
crosses a sample), so it is evaluated at the two ends only and interpolated at the stages.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..dop853_tableau import A853 as A, B853 as B, C853 as C, D853 as D, E3, E5, N_STAGES as _STAGES  # noqa: F401
from ..motions.excitation import EXC_SAMPLES
from .eom import ground_xy, rhs_ground

@njit(cache=True)
def dop853_step(t, y, f0, h, K, y_new, ytmp, n, par, active, kind, params, sx, sy, dirx, diry):
    """One DOP853 step of size h: fills K[0..12] (K[12] = f(t+h, y_new)) and y_new.

    A step never crosses a record sample, so a record's ü_g is linear in it: evaluated at both ends
    only and interpolated at the stages (pulses are evaluated at every stage)."""
    for i in range(n):
        K[0, i] = f0[i]
    linear = kind == EXC_SAMPLES or not active
    ax0, ay0 = ground_xy(t, active, kind, params, sx, sy, dirx, diry)
    ax1, ay1 = ground_xy(t + h, active, kind, params, sx, sy, dirx, diry)
    for s in range(1, 12):
        for i in range(n):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * K[j, i]
            ytmp[i] = y[i] + h * acc
        if linear:
            ax = ax0 + C[s] * (ax1 - ax0)
            ay = ay0 + C[s] * (ay1 - ay0)
        else:
            ax, ay = ground_xy(t + C[s] * h, active, kind, params, sx, sy, dirx, diry)
        rhs_ground(ytmp, K[s], par, ax, ay)
    for i in range(n):
        acc = 0.0
        for j in range(12):
            acc += B[j] * K[j, i]
        y_new[i] = y[i] + h * acc
    rhs_ground(y_new, K[12], par, ax1, ay1)


@njit(cache=True)
def error_norm(y, y_new, K, h, rtol, atol, n):
    """scipy's DOP853 error norm (5th- and 3rd-order estimators)."""
    e5 = 0.0
    e3 = 0.0
    for i in range(n):
        sc = atol + rtol * max(abs(y[i]), abs(y_new[i]))
        a5 = 0.0
        a3 = 0.0
        for j in range(13):
            a5 += E5[j] * K[j, i]
            a3 += E3[j] * K[j, i]
        e5 += (a5 / sc) ** 2
        e3 += (a3 / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@njit(cache=True)
def dense_coefficients(t, y, y_new, K, h, F, ytmp, n, par, active, kind, params, sx, sy, dirx, diry):
    """The 7th-order dense-output coefficients F[0..6] of the last step (3 extra stages)."""
    # The stage loop below repeats dop853_step's on purpose: factored into one @njit helper (also with
    # inline="always") the 30-s pair benchmark ran 4-7 % slower; as one helper taking the stage range,
    # 7 % slower (rigid 5.30 → 5.70 ms, spring-dashpot 4.09 → 4.43 ms, same window; 2026-11-23).
    linear = kind == EXC_SAMPLES or not active
    ax0, ay0 = ground_xy(t, active, kind, params, sx, sy, dirx, diry)
    ax1, ay1 = ground_xy(t + h, active, kind, params, sx, sy, dirx, diry)
    for s in range(13, 16):
        for i in range(n):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * K[j, i]
            ytmp[i] = y[i] + h * acc
        if linear:
            ax = ax0 + C[s] * (ax1 - ax0)
            ay = ay0 + C[s] * (ay1 - ay0)
        else:
            ax, ay = ground_xy(t + C[s] * h, active, kind, params, sx, sy, dirx, diry)
        rhs_ground(ytmp, K[s], par, ax, ay)
    for i in range(n):
        dy = y_new[i] - y[i]
        F[0, i] = dy
        F[1, i] = h * K[0, i] - dy
        F[2, i] = 2.0 * dy - h * (K[12, i] + K[0, i])
        for r in range(4):
            acc = 0.0
            for j in range(16):
                acc += D[r, j] * K[j, i]
            F[3 + r, i] = h * acc


@njit(cache=True)
def dense_at(F, y, x, i):
    """Component i of the dense output at x = (t − t_old)/h ∈ [0, 1]."""
    v = 0.0
    for k in range(6, -1, -1):
        v += F[k, i]
        if (6 - k) % 2 == 0:
            v *= x
        else:
            v *= 1.0 - x
    return v + y[i]


@njit(cache=True)
def dense_root(F, y, i, level, xa, xb):
    """x in [xa, xb] where component i of the dense output equals ``level`` (bracketed; bisection+secant)."""
    fa = dense_at(F, y, xa, i) - level
    fb = dense_at(F, y, xb, i) - level
    for _ in range(200):
        if xb - xa <= 1e-15:
            break
        xm = xa - fa * (xb - xa) / (fb - fa) if fb != fa else 0.5 * (xa + xb)
        if not (xa < xm < xb) or _ > 60:
            xm = 0.5 * (xa + xb)
        fm = dense_at(F, y, xm, i) - level
        if fm == 0.0:
            return xm
        if (fm < 0.0) == (fa < 0.0):
            xa, fa = xm, fm
        else:
            xb, fb = xm, fm
        if _ % 3 == 2:                                   # guarantee halving now and then
            xm = 0.5 * (xa + xb)
            fm = dense_at(F, y, xm, i) - level
            if (fm < 0.0) == (fa < 0.0):
                xa, fa = xm, fm
            else:
                xb, fb = xm, fm
    return 0.5 * (xa + xb)
