"""Ground acceleration ü_g(t) as the numba kernels see it (SPEC §4).

An excitation travels through numba as ``(kind, params, samples)``:

* ``kind`` – one of the ``EXC_*`` integer codes below;
* ``params`` – float64 array, kind-specific (see :func:`ground_acceleration`);
* ``samples`` – float64 array of accelerations [m/s²] at t = i·dt (records only, else empty).

Records are piecewise linear between samples and zero outside ``[0, (n−1)·dt]``; analytic pulses are
evaluated exactly at any t.  All values are SI (m/s², s).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

EXC_SAMPLES = 0
EXC_RICKER_SYM = 1
EXC_RICKER_ANTI = 2
EXC_SINE = 3
EXC_CYCLOIDAL_A = 4
EXC_CYCLOIDAL_B = 5
EXC_CYCLOIDAL_C = 6
EXC_NONE = 7

RICKER_ANTI_BETA = 1.3801190
"""β_R of Eq A.2: max |(x²−3)x e^(−x²/2)| at x² = 3 − √6, so that max |a| = a_p (SPEC §4)."""

CYCLOIDAL_C1_PHASE = 0.21897
"""φ of Makris' type-C1 pulse: root of 2 cos φ = sin φ (3π − 2φ) (zero residual displacement)."""

# params layout -------------------------------------------------------------------------------
# samples:  [scale, dt]                      ü_g(t) = scale · interp(samples)
# ricker-*: [a_p, T_p, t_m]
# sine:     [a_p, T_p, t_0]                  Eq 2.20 shifted to start at t_0 (default 0)
# cyclo-*:  [a_p, T_p, t_0, phi, t_end_rel]  Makris & Roussos (2000) type A, B, C_n
# none:     []


@njit(cache=True, inline="always")
def ground_acceleration(t, kind, params, samples):
    """ü_g(t) in m/s² for the excitation ``(kind, params, samples)``.

    Symmetric Ricker (Eq A.1): −a_p (1 − 2π²τ²/T_p²) exp(−π²τ²/T_p²), τ = t − t_m.
    Antisymmetric Ricker (Eq A.2): −(a_p/β_R)(4π²τ²/(3T_p²) − 3)(2πτ/(√3 T_p)) exp(−2π²τ²/(3T_p²)).
    One-sine pulse (Eq 2.20): −a_p sin(ω_p (t − t_0)) for 0 ≤ t − t_0 ≤ T_p.
    Cycloidal pulses (Makris & Roussos 2000): A: a_p sin(ω_p τ) on [0, T_p];
    B: a_p cos(ω_p τ) on [0, T_p]; C_n: a_p cos(ω_p τ + φ) on [0, (n + ½ − φ/π) T_p].
    Records: linear interpolation between samples, zero outside the record.
    """
    if kind == EXC_SAMPLES:
        dt = params[1]
        n = samples.shape[0]
        if t < 0.0 or n == 0:
            return 0.0
        x = t / dt
        i = int(math.floor(x))
        if i >= n - 1:
            if i == n - 1 and x - i <= 1e-12:
                return params[0] * samples[n - 1]
            return 0.0
        f = x - i
        return params[0] * (samples[i] + f * (samples[i + 1] - samples[i]))
    return pulse_acceleration(t, kind, params, samples)


@njit(cache=True)
def pulse_acceleration(t, kind, params, samples):
    """ü_g(t) in m/s² of an analytic pulse (the formulas of :func:`ground_acceleration`).

    Not inlined: the record branch of :func:`ground_acceleration` is inlined into every Runge–Kutta
    stage and event search, and copying these pulse formulas there too made the engine's first-run
    compilation about 8 s longer (docs/engine.md); a pulse pays one function call per evaluation.
    """
    if kind == EXC_RICKER_SYM:
        a_p = params[0]
        tp = params[1]
        tau = t - params[2]
        z = math.pi * math.pi * tau * tau / (tp * tp)
        return -a_p * (1.0 - 2.0 * z) * math.exp(-z)
    if kind == EXC_RICKER_ANTI:
        a_p = params[0]
        tp = params[1]
        tau = t - params[2]
        x2 = 4.0 * math.pi * math.pi * tau * tau / (3.0 * tp * tp)
        x = 2.0 * math.pi * tau / (math.sqrt(3.0) * tp)
        return -(a_p / RICKER_ANTI_BETA) * (x2 - 3.0) * x * math.exp(-0.5 * x2)
    if kind == EXC_SINE:
        tau = t - params[2]
        if tau < 0.0 or tau > params[1]:
            return 0.0
        return -params[0] * math.sin(2.0 * math.pi * tau / params[1])
    if kind == EXC_CYCLOIDAL_A or kind == EXC_CYCLOIDAL_B or kind == EXC_CYCLOIDAL_C:
        tau = t - params[2]
        if tau < 0.0 or tau > params[4]:
            return 0.0
        w = 2.0 * math.pi / params[1]
        if kind == EXC_CYCLOIDAL_A:
            return params[0] * math.sin(w * tau)
        return params[0] * math.cos(w * tau + params[3])
    return 0.0


@njit(cache=True)
def ground_acceleration_right(t, kind, params, samples):
    """Right limit ü_g(t⁺) [m/s²]: differs from :func:`ground_acceleration` only where ü_g jumps —
    at a record's last sample (the record is zero after it) and at the end of a windowed pulse."""
    if kind == EXC_SAMPLES:
        if samples.shape[0] == 0 or t >= (samples.shape[0] - 1) * params[1]:
            return 0.0
    elif kind == EXC_SINE:
        if t - params[2] >= params[1]:
            return 0.0
    elif kind == EXC_CYCLOIDAL_A or kind == EXC_CYCLOIDAL_B or kind == EXC_CYCLOIDAL_C:
        if t - params[2] >= params[4]:
            return 0.0
    return ground_acceleration(t, kind, params, samples)


@njit(cache=True)
def excitation_end(kind, params, samples):
    """Time [s] after which ü_g is zero (records, sine, cycloidal) or below 1e-40·a_p (Ricker)."""
    if kind == EXC_SAMPLES:
        return (samples.shape[0] - 1) * params[1] if samples.shape[0] > 0 else 0.0
    if kind == EXC_RICKER_SYM or kind == EXC_RICKER_ANTI:
        # exp(−π²τ²/T_p²) < 1e-40 for |τ| > 3.1 T_p; the antisymmetric wavelet decays faster
        return params[2] + 3.5 * params[1]
    if kind == EXC_SINE:
        return params[2] + params[1]
    if kind == EXC_CYCLOIDAL_A or kind == EXC_CYCLOIDAL_B or kind == EXC_CYCLOIDAL_C:
        return params[2] + params[4]
    return 0.0


@njit(cache=True)
def next_breakpoint(t, kind, params, samples):
    """The first time > t (by more than round-off) where ü_g has a kink, or +inf.

    Integration steps must end exactly on these times: records are piecewise linear, so every
    sample is a kink; pulses of finite support have kinks at their start and end.
    """
    eps = 1e-12 * max(1.0, abs(t))
    if kind == EXC_SAMPLES:
        dt = params[1]
        n = samples.shape[0]
        t_last = (n - 1) * dt
        if t < -eps:
            return 0.0
        if t >= t_last - eps:
            return math.inf
        i = int(math.floor((t + eps) / dt)) + 1
        tb = i * dt
        if tb <= t + eps:
            tb = (i + 1) * dt
        return min(tb, t_last)
    if kind == EXC_SINE:
        t0 = params[2]
        t1 = params[2] + params[1]
    elif kind == EXC_CYCLOIDAL_A or kind == EXC_CYCLOIDAL_B or kind == EXC_CYCLOIDAL_C:
        t0 = params[2]
        t1 = params[2] + params[4]
    else:
        return math.inf
    if t < t0 - eps:
        return t0
    if t < t1 - eps:
        return t1
    return math.inf


def ground_acceleration_array(t: np.ndarray, kind: int, params: np.ndarray, samples: np.ndarray) -> np.ndarray:
    """Vectorised :func:`ground_acceleration` for plotting and tests (m/s²)."""
    return _ground_acceleration_many(np.asarray(t, dtype=np.float64), kind, params, samples)


@njit(cache=True)
def _ground_acceleration_many(t, kind, params, samples):
    out = np.empty(t.shape[0])
    for i in range(t.shape[0]):
        out[i] = ground_acceleration(t[i], kind, params, samples)
    return out
