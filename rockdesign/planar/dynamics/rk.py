"""Dormand–Prince 5(4) with its 4th-order dense output, as small numba kernels (DOP853: dop853.py).

The decomposition follows scipy.integrate._ivp (rk.py: tableau, step, dense output; common.py:
initial step), adapted to fixed-size float arrays: one step, one error norm, one dense-output
evaluation, one initial-step guess.  The right-hand side is :func:`rockdesign.planar.dynamics.eom.rhs`.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .eom import rhs

C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
])
B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
P = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])
ERROR_EXPONENT = -1.0 / 5.0
SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0


@njit(cache=True)
def dp5_step(t, y, f0, h, K, y_new, ytmp, rocking, side, phase, kind, xp, samples, sp, n):
    """One Dormand–Prince step of size h from (t, y) with f0 = f(t, y).

    Fills K[0..6] with the stage derivatives (K[6] = f(t+h, y_new), FSAL) and ``y_new``.
    Only the first ``n`` components take part (2 for SDOF systems, 4 with a superstructure); the
    others must be zero and stay untouched.
    Returns the number of right-hand-side evaluations (6).
    """
    for i in range(n):
        K[0, i] = f0[i]
    # one call site of the (inlined) right-hand side for all six evaluations: stages 1–5, then the
    # FSAL evaluation at the new point (stage 6 combines with B into y_new)
    for s in range(1, 7):
        if s < 6:
            for i in range(n):
                acc = 0.0
                for j in range(s):
                    acc += A[s, j] * K[j, i]
                ytmp[i] = y[i] + h * acc
            ts = t + C[s] * h
        else:
            for i in range(n):
                acc = 0.0
                for j in range(6):
                    acc += B[j] * K[j, i]
                y_new[i] = y[i] + h * acc
                ytmp[i] = y_new[i]
            ts = t + h
        rhs(ts, ytmp, K[s], rocking, side, phase, kind, xp, samples, sp)
    return 6


@njit(cache=True)
def error_norm(y, y_new, K, h, rtol, atol, n):
    """RMS of the embedded error estimate scaled by atol + rtol·max(|y|, |y_new|) (scipy's norm)."""
    total = 0.0
    for i in range(n):
        e = 0.0
        for j in range(7):
            e += E[j] * K[j, i]
        e *= h
        sc = atol + rtol * max(abs(y[i]), abs(y_new[i]))
        total += (e / sc) ** 2
    return math.sqrt(total / n)


@njit(cache=True)
def dense_coefficients(K, Q, n):
    """Q = Kᵀ P (first n rows): y(t + x h) = y + h Σ_j Q[:, j] x^(j+1), x ∈ [0, 1] (4th-order interpolant).

    Q has 4 columns for DP5(4) runs (7 for the DOP853 interpolant, :mod:`rockdesign.planar.dynamics.dop853`;
    powers above 4 are then zeroed here).
    """
    for i in range(n):
        for j in range(4):
            acc = 0.0
            for k in range(7):
                acc += K[k, i] * P[k, j]
            Q[i, j] = acc
        for j in range(4, Q.shape[1]):
            Q[i, j] = 0.0


@njit(cache=True, inline="always")
def dense_value(y, Q, h, x, i):
    """Component ``i`` of the dense output at fraction x of the step: Q has 4 columns (DP5(4), powers
    x¹ … x⁴) or 7 (DOP853, x¹ … x⁷)."""
    if Q.shape[1] == 4:
        return y[i] + h * x * (Q[i, 0] + x * (Q[i, 1] + x * (Q[i, 2] + x * Q[i, 3])))
    return y[i] + h * x * (Q[i, 0] + x * (Q[i, 1] + x * (Q[i, 2] + x * (Q[i, 3] + x * (
        Q[i, 4] + x * (Q[i, 5] + x * Q[i, 6]))))))


@njit(cache=True)
def initial_step(t, y, f0, t_bound, rtol, atol, ytmp, f1, rocking, side, phase, kind, xp, samples, sp, n,
                 error_order=4):
    """First step size by Hairer–Nørsett–Wanner II.4 (as scipy's select_initial_step); 1 evaluation.

    ``error_order`` is the order of the method's error estimator (4 for DP5(4), 7 for DOP853).
    """
    interval = t_bound - t
    if interval <= 0.0:
        return 0.0
    d0 = 0.0
    d1 = 0.0
    for i in range(n):
        sc = atol + abs(y[i]) * rtol
        d0 += (y[i] / sc) ** 2
        d1 += (f0[i] / sc) ** 2
    d0 = math.sqrt(d0 / n)
    d1 = math.sqrt(d1 / n)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, interval)
    for i in range(4):
        ytmp[i] = y[i] + h0 * f0[i]
    rhs(t + h0, ytmp, f1, rocking, side, phase, kind, xp, samples, sp)
    d2 = 0.0
    for i in range(n):
        sc = atol + abs(y[i]) * rtol
        d2 += ((f1[i] - f0[i]) / sc) ** 2
    d2 = math.sqrt(d2 / n) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (error_order + 1.0))
    return min(100.0 * h0, h1, interval)
