"""The rocking-spectrum job kernel: many pulse analyses of one system in parallel (numba prange).

A spectrum is a grid of analyses of one system under one pulse shape: row i has amplitude a_p[i],
column j has period T_p[j].  :func:`spectrum_kernel` builds the pulse parameters of every grid point
inside numba (no Python loop over 321 201 jobs) and runs :func:`rockdesign.planar.dynamics.engine.integrate`
on each, exactly as :func:`rockdesign.planar.dynamics.simulate.simulate` would for
``pulse_motion(kind, a_p, T_p)`` with ``t_end = excitation end + t_free`` — so every grid point equals
a direct ``simulate`` call bit for bit (tests/spectra/test_grid_points.py).

Each grid point is independent and computed by the same compiled code, so results do not depend on
how rows are chunked, on the number of threads, or on which process (or dask worker) ran them.

This module is importable on dask workers: :func:`spectrum_rows` is the chunk function,
:func:`warm_up` loads the compiled kernel from numba's cache (or compiles it once).
"""
from __future__ import annotations

import math
import time

import numpy as np
from numba import njit, prange

from ..dynamics.engine import integrate
from ..dynamics.layout import (D_STATUS, D_STEPS, O_T_END, S_DYNAMIC, S_IMPACTS, S_IMPACTS_BEFORE_EXCEEDED,
                               S_IMPACTS_BEFORE_OVERTURN, S_THETA_MAX, S_T_END, S_T_UPLIFT)
from ..dynamics.eom import P_THETA_C
from ..dynamics.overturning import capacity_exceeded
from ...execution.scheduling import take, worker_count
from ...kernel_cache import sources_digest
from ...motions.excitation import (EXC_CYCLOIDAL_A, EXC_CYCLOIDAL_B, EXC_CYCLOIDAL_C, EXC_RICKER_ANTI,
                                  EXC_RICKER_SYM, EXC_SINE, excitation_end)
from ...motions.motion import PULSE_KINDS, cycloidal_c_phase

# pulse shape array (dimensionless, relative to T_p) ----------------------------------------------
SH_TM_RATIO = 0      # t_m/T_p of Ricker wavelets (1.5: thesis, SPEC §4)
SH_T0 = 1            # start time t_0 [s] of sine and cycloidal pulses
SH_PHI = 2           # phase φ [rad] of cycloidal pulses (type C_n)
SH_SPAN_RATIO = 3    # support of cycloidal pulses / T_p (1 for A and B, n + ½ − φ/π for C_n)
N_SHAPE = 4

# per-point outputs ----------------------------------------------------------------------------------
OUT_THETA_MAX = 0                  # max |θ| [rad] (π/2 after dynamic overturning)
OUT_EXCEEDED = 1                   # 1.0: θ_max ≥ θc (static overturning, capacity exceeded)
OUT_DYNAMIC = 2                    # 1.0: |θ| reached π/2 (dynamic overturning)
OUT_IMPACTS_BEFORE_DYNAMIC = 3     # impacts before dynamic overturning (−1: none)
OUT_IMPACTS_BEFORE_EXCEEDED = 4    # impacts before θc was first reached (−1: never)
OUT_IMPACTS = 5                    # impacts counted until the analysis stopped
OUT_STATUS = 6                     # engine status code (ST_*)
OUT_STEPS = 7                      # accepted integration steps
OUT_T_STOP = 8                     # time the analysis stopped [s]
OUT_T_UPLIFT = 9                   # first uplift [s] (NaN: no uplift)
N_OUT = 10
OUT_NAMES = ("theta_max", "exceeded", "dynamic", "impacts_before_dynamic", "impacts_before_exceeded",
             "impacts", "status", "steps", "t_stop", "t_uplift")

_MAX_PULSE_PARAMS = 5


@njit(cache=True)
def pulse_parameters(kind, a_p, T_p, shape):
    """The excitation parameter row (:mod:`rockdesign.motions.excitation` layout) of one pulse.

    Ricker (Eqs A.1/A.2): [a_p, T_p, t_m = (t_m/T_p)·T_p]; sine (Eq 2.20): [a_p, T_p, t_0];
    cycloidal (Makris & Roussos): [a_p, T_p, t_0, φ, span]. a_p [m/s²], T_p [s]. The arithmetic is
    that of :func:`rockdesign.motions.motion.pulse_motion`, so both give identical floats.
    """
    xp = np.zeros(_MAX_PULSE_PARAMS)
    xp[0] = a_p
    xp[1] = T_p
    if kind == EXC_RICKER_SYM or kind == EXC_RICKER_ANTI:
        xp[2] = shape[SH_TM_RATIO] * T_p
    elif kind == EXC_SINE:
        xp[2] = shape[SH_T0]
    else:
        xp[2] = shape[SH_T0]
        xp[3] = shape[SH_PHI]
        if kind == EXC_CYCLOIDAL_A or kind == EXC_CYCLOIDAL_B:
            xp[4] = T_p
        else:
            xp[4] = shape[SH_SPAN_RATIO] * T_p
    return xp


@njit(cache=True)
def run_pulse(sp, kind, shape, T_p, a_p, opts, t_free, out):
    """One analysis: pulse (kind, shape) of period T_p [s] and amplitude a_p [m/s²] until its end +
    t_free [s]; writes the ``OUT_*`` values into ``out`` (length N_OUT)."""
    samples = np.zeros(0)
    xp = pulse_parameters(kind, a_p, T_p, shape)
    o = opts.copy()
    o[O_T_END] = excitation_end(kind, xp, samples) + t_free
    y0 = np.zeros(4)
    t_out = np.zeros(0)
    out_y = np.zeros((0, 4))
    ev_t = np.zeros(0)
    ev_k = np.zeros(0, dtype=np.int64)
    ev_y = np.zeros((0, 4))
    summ, diag, _ = integrate(sp, kind, xp, samples, y0, 1.0, 0.0, o, t_out, out_y, ev_t, ev_k, ev_y)
    dynamic = summ[S_DYNAMIC] != 0.0
    out[OUT_THETA_MAX] = summ[S_THETA_MAX]
    out[OUT_EXCEEDED] = 1.0 if capacity_exceeded(summ[S_THETA_MAX], sp[P_THETA_C], dynamic) else 0.0
    out[OUT_DYNAMIC] = 1.0 if dynamic else 0.0
    out[OUT_IMPACTS_BEFORE_DYNAMIC] = summ[S_IMPACTS_BEFORE_OVERTURN]
    out[OUT_IMPACTS_BEFORE_EXCEEDED] = summ[S_IMPACTS_BEFORE_EXCEEDED]
    out[OUT_IMPACTS] = summ[S_IMPACTS]
    out[OUT_STATUS] = diag[D_STATUS]
    out[OUT_STEPS] = diag[D_STEPS]
    out[OUT_T_STOP] = summ[S_T_END]
    out[OUT_T_UPLIFT] = summ[S_T_UPLIFT]


@njit(cache=True, parallel=True)
def spectrum_kernel(sp, kind, shape, periods, amplitudes, opts, t_free, workers):
    """Run the analyses of a block of spectrum rows in parallel: ``workers`` workers (one per numba
    thread), each taking the next grid point from a shared counter until none is left
    (:mod:`rockdesign.execution.scheduling`), so cheap points (no uplift) and costly ones (long rocking)
    balance whatever core is busy.

    Args:
        sp: system parameters (``eom.P_*``, from :func:`rockdesign.planar.dynamics.model.system_parameters`).
        kind: excitation code ``EXC_*`` of the pulse.
        shape: pulse shape array (``SH_*``).
        periods: T_p [s] of the columns (length nx).
        amplitudes: a_p [m/s²] of the rows (length ny).
        opts: engine options (:func:`rockdesign.planar.dynamics.batch.batch_options`; t_end set per point).
        t_free: free vibration [s] after the excitation ends (t_end = excitation end + t_free).

    Returns:
        float64 array (ny, nx, N_OUT) with the ``OUT_*`` values of every grid point.
    """
    ny = amplitudes.shape[0]
    nx = periods.shape[0]
    n = ny * nx
    out = np.empty((ny, nx, N_OUT))
    counter = np.zeros(1, dtype=np.int64)
    for _ in prange(workers):
        job = take(counter)
        while job < n:
            iy = job // nx
            ix = job - iy * nx
            run_pulse(sp, kind, shape, periods[ix], amplitudes[iy], opts, t_free, out[iy, ix])
            job = take(counter)
    return out


@njit(cache=True, parallel=True)
def points_kernel(sp, kind, shape, periods, amplitudes, opts, t_free, workers):
    """Like :func:`spectrum_kernel` for scattered points: point k is (periods[k], amplitudes[k]).

    Returns:
        float64 array (n, N_OUT).
    """
    n = periods.shape[0]
    out = np.empty((n, N_OUT))
    counter = np.zeros(1, dtype=np.int64)
    for _ in prange(workers):
        k = take(counter)
        while k < n:
            run_pulse(sp, kind, shape, periods[k], amplitudes[k], opts, t_free, out[k])
            k = take(counter)
    return out


def pulse_shape(pulse: str, tm_ratio: float = 1.5, n_cycles: int = 1) -> tuple[int, np.ndarray]:
    """(excitation code, shape array) of a pulse name (``ricker-anti`` ... ``cycloidal-c``).

    Args:
        pulse: a key of :data:`rockdesign.motions.motion.PULSE_KINDS`.
        tm_ratio: t_m/T_p of Ricker wavelets (SPEC §4: 1.5).
        n_cycles: n of the cycloidal type-C_n pulse.
    """
    kind = PULSE_KINDS[pulse]
    shape = np.zeros(N_SHAPE)
    shape[SH_TM_RATIO] = tm_ratio
    if kind == EXC_CYCLOIDAL_C:
        phi = cycloidal_c_phase(n_cycles)
        shape[SH_PHI] = phi
        shape[SH_SPAN_RATIO] = n_cycles + 0.5 - phi / math.pi
    elif kind in (EXC_CYCLOIDAL_A, EXC_CYCLOIDAL_B):
        shape[SH_SPAN_RATIO] = 1.0
    return kind, shape


def spectrum_rows(sp: np.ndarray, kind: int, shape: np.ndarray, periods: np.ndarray, amplitudes: np.ndarray,
                  opts: np.ndarray, t_free: float) -> dict[str, np.ndarray]:
    """The chunk function of a spectrum: rows ``amplitudes`` × columns ``periods`` (see :func:`spectrum_kernel`;
    the grid points are handed to numba's threads one at a time, so cheap and costly rows balance).

    Returns:
        {"out": float64 (ny, nx, N_OUT)} — a dict so that chunk stores and executors treat every
        batch function alike.
    """
    sp = np.ascontiguousarray(sp, dtype=np.float64)
    args = (sp, int(kind), np.ascontiguousarray(shape, dtype=np.float64),
            np.ascontiguousarray(periods, dtype=np.float64), np.ascontiguousarray(amplitudes, dtype=np.float64),
            np.ascontiguousarray(opts, dtype=np.float64), float(t_free))
    return {"out": spectrum_kernel(*args, worker_count(len(periods) * len(amplitudes)))}


SOURCE_DIGEST = sources_digest()
"""Identifies the engine that computes spectra (every kernel source, :mod:`rockdesign.kernel_cache`): part
of every chunk fingerprint, so chunks computed by another version of the engine are never resumed."""



def pulse_points(sp: np.ndarray, kind: int, shape: np.ndarray, periods: np.ndarray, amplitudes: np.ndarray,
                 opts: np.ndarray, t_free: float) -> np.ndarray:
    """Scattered pulse analyses (point k: T_p = periods[k] [s], a_p = amplitudes[k] [m/s²]) in parallel.

    The batch function for margins and samples: each point equals the spectrum grid point (and the
    ``simulate`` call) of the same pulse. Returns the (n, N_OUT) outputs.
    """
    args = (np.ascontiguousarray(sp, dtype=np.float64), int(kind), np.ascontiguousarray(shape, dtype=np.float64),
            np.ascontiguousarray(periods, dtype=np.float64), np.ascontiguousarray(amplitudes, dtype=np.float64),
            np.ascontiguousarray(opts, dtype=np.float64), float(t_free))
    return points_kernel(*args, worker_count(len(periods)))


_WARM = False


def warm_up(points: bool = False) -> float:
    """Load (or compile, once per machine) the spectrum kernel; returns the seconds it took.

    Called once per process — by the local executor before the first chunk and on every dask
    worker before chunks are sent — so that no chunk pays the compilation. ``points=True`` also
    loads :func:`points_kernel` (scattered pulses, e.g. margins).
    """
    global _WARM
    t0 = time.perf_counter()
    if not _WARM or (points and _WARM != "points"):
        from ..dynamics.batch import batch_options
        from ..dynamics.model import ModelChoice, system_parameters
        from ..system import block
        sp = system_parameters(block(1.5, 0.15), ModelChoice("block", "exact"))
        kind, shape = pulse_shape("ricker-anti")
        spectrum_rows(sp, kind, shape, np.array([1.0]), np.array([0.0, 5.0]), batch_options(), 0.1)
        _WARM = True
        if points:
            pulse_points(sp, kind, shape, np.array([1.0, 1.0]), np.array([0.0, 5.0]), batch_options(), 0.1)
            _WARM = "points"
    return time.perf_counter() - t0


