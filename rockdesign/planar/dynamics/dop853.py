"""Dormand–Prince 8(5,3) (Hairer's DOP853) with its 7th-order dense output, as small numba kernels.

The second stepper of the engine, beside DP5(4) (:mod:`rockdesign.planar.dynamics.rk`): where steps are
bound by the tolerance rather than by the record samples (the 2DOF podium, whose uplifted
superstructure makes DP5(4) take ≈ 8 steps per sample at rtol 1e-10), an 8th-order step covers a
sample in one or two steps.  Which system uses which method is decided by the work-precision data
(``benchmarks/bench_engine.py``; :func:`rockdesign.planar.dynamics.model.default_method`).

Written by hand (not scipy's ``DOP853`` class) because the event-driven integrator needs one step,
one error norm and one dense output as allocation-free kernels it can call from its own loop.  The
coefficients are the published ones, written out below from Hairer & Wanner's Fortran ``dop853.f`` (the
``parameter`` block of its core integrator ``DP86CO``; E. Hairer, S. P. Nørsett, G. Wanner, *Solving
Ordinary Differential Equations I*, 2nd ed., Springer 1993, Sec. II.5–II.6; code at
http://www.unige.ch/~hairer/software.html) — the same decimal literals scipy's ``solve_ivp(method="DOP853")``
uses, so the doubles are the same to the bit.  The step, the combined 5th/3rd-order error norm and the
dense output follow ``dop853.f`` (and scipy's ``DOP853``, which transcribes it).

The dense output is returned in the engine's common monomial form
``y(t + x h) = y + h Σ_{k=1..7} Q[:, k−1] x^k`` (x ∈ [0, 1]), so event location
(:mod:`rockdesign.planar.dynamics.events`) evaluates the 4th-order DP5 and the 7th-order DOP853 interpolants
with the same code.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ...dop853_tableau import (A853, B853, C853, D853, E3, E5, N_STAGES,  # noqa: F401  (the tableau, shared)
                               N_STAGES_EXTENDED)
from .eom import rhs

ERROR_EXPONENT_853 = -1.0 / 8.0       # error estimator of order 7
FSAL_ROW_853 = N_STAGES


@njit(cache=True)
def dop853_step(t, y, f0, h, K, y_new, ytmp, rocking, side, phase, kind, xp, samples, sp, n):
    """One DOP853 step of size h from (t, y) with f0 = f(t, y) (Hairer–Nørsett–Wanner II.5; dop853.f's stages).

    Fills K[0..12] with the stage derivatives (K[12] = f(t+h, y_new), FSAL) and ``y_new``; only the
    first ``n`` components take part.  Returns the number of right-hand-side evaluations (12).
    Sums run over the stages in order, skipping the tableau's zeros (stage-outer loops: the
    components' sums are independent chains the processor overlaps).
    """
    for i in range(n):
        K[0, i] = f0[i]
    # one call site of the (inlined) right-hand side: stages 1–11, then f at the new point
    for s in range(1, N_STAGES + 1):
        for i in range(n):
            ytmp[i] = 0.0
        for j in range(s):
            a = A853[s, j]          # row 12 holds the weights B
            if a != 0.0:
                for i in range(n):
                    ytmp[i] += a * K[j, i]
        for i in range(n):
            ytmp[i] = y[i] + h * ytmp[i]
        if s == N_STAGES:
            for i in range(n):
                y_new[i] = ytmp[i]
        rhs(t + C853[s] * h, ytmp, K[s], rocking, side, phase, kind, xp, samples, sp)
    return N_STAGES


@njit(cache=True)
def dop853_error_norm(y, y_new, K, h, rtol, atol, n, work):
    """dop853.f's error norm (as scipy's DOP853): |h|·‖e5‖² / √((‖e5‖² + 0.01‖e3‖²)·n), scaled by
    atol + rtol·max(|y|, |y_new|).

    ``work``: scratch of at least 8 floats.
    """
    for i in range(n):
        work[i] = 0.0
        work[4 + i] = 0.0
    for j in range(N_STAGES + 1):
        a5 = E5[j]
        a3 = E3[j]
        for i in range(n):
            work[i] += a5 * K[j, i]
            work[4 + i] += a3 * K[j, i]
    e5 = 0.0
    e3 = 0.0
    for i in range(n):
        sc = atol + rtol * max(abs(y[i]), abs(y_new[i]))
        e5 += (work[i] / sc) ** 2
        e3 += (work[4 + i] / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@njit(cache=True)
def dop853_dense(t, y, y_new, h, K, Q, ytmp, rocking, side, phase, kind, xp, samples, sp, n, work):
    """The 7th-order dense output of an accepted step into Q (monomial form); 3 more evaluations.

    As dop853.f's dense output (and scipy's ``DOP853``): stages 13–15 into K, then F₀ = Δy,
    F₁ = h f₀ − Δy, F₂ = 2Δy − h(f₁ + f₀), F₃.. = h D K and
    y(x) = y + x(F₀ + (1−x)(F₁ + x(F₂ + (1−x)(F₃ + …)))), expanded here into powers of x.
    ``work``: scratch of at least 8 floats.  Returns the number of evaluations (3).
    """
    for s in range(N_STAGES + 1, N_STAGES_EXTENDED):
        for i in range(n):
            ytmp[i] = 0.0
        for j in range(s):
            a = A853[s, j]
            if a != 0.0:
                for i in range(n):
                    ytmp[i] += a * K[j, i]
        for i in range(n):
            ytmp[i] = y[i] + h * ytmp[i]
        rhs(t + C853[s] * h, ytmp, K[s], rocking, side, phase, kind, xp, samples, sp)
    # F₃.. = h D K into Q[:, 3..6] (stage-outer sums), then F₀..F₂ and the expansion per component
    for r in range(D853.shape[0]):
        for i in range(n):
            Q[i, 3 + r] = 0.0
        for j in range(N_STAGES_EXTENDED):
            d = D853[r, j]
            if d != 0.0:
                for i in range(n):
                    Q[i, 3 + r] += d * K[j, i]
    c = work
    for i in range(n):
        dy = y_new[i] - y[i]
        f_0 = dy
        f_1 = h * K[0, i] - dy
        f_2 = 2.0 * dy - h * (K[FSAL_ROW_853, i] + K[0, i])
        # Horner in the mixed basis, from the innermost factor outwards: p ← (p + F_k)·(x or 1 − x)
        for k in range(8):
            c[k] = 0.0
        c[0] = h * Q[i, 6]
        for k in range(5, -1, -1):
            if k % 2 == 1:          # multiply by x (shift up)
                for m in range(7, 0, -1):
                    c[m] = c[m - 1]
                c[0] = 0.0
            else:                   # multiply by (1 − x)
                for m in range(7, 0, -1):
                    c[m] = c[m] - c[m - 1]
            if k == 0:
                c[0] += f_0
            elif k == 1:
                c[0] += f_1
            elif k == 2:
                c[0] += f_2
            else:
                c[0] += h * Q[i, k]
        # the outermost factor x: y(x) − y = Σ_{m=0..6} c[m] x^(m+1) = h Σ Q[i, m] x^(m+1)
        for m in range(7):
            Q[i, m] = c[m] / h
    return N_STAGES_EXTENDED - N_STAGES - 1
