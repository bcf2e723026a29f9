"""Many time-history analyses in one call: in parallel over the machine's cores (numba prange, jobs handed
out dynamically), or one after the other in the calling thread when a batch is too small to pay for threads.

A batch is a list of jobs, each with its system (a row of ``sps``, usually one row shared by every job;
several when the design grid runs the analyses of many variants together, :mod:`.shared_batches`) and its
excitation: an excitation kind, a parameter row (pulse amplitude/period, or record scale/dt) and a
slice of one concatenated sample array.  Only the summaries (θ_max, impacts, overturning...) are kept —
what spectra, suites and margins need.  Results are identical to one-by-one :func:`integrate` calls,
whichever driver runs them and in whatever order the threads take the jobs.

Scheduling (docs/engine.md, "Threads"): the parallel driver starts one worker per numba thread and
each worker takes the next job from a shared atomic counter until none is left (:mod:`.scheduling`), so a
thread whose core is busy with another program simply takes fewer jobs.  A batch of fewer than
:data:`SERIAL_BELOW_JOBS` jobs, and every single analysis (:func:`run_history`), runs serially in the
calling thread: a parallel region waits for every thread to be scheduled, which costs a single analysis
up to several times its own time on a loaded machine (benchmarks/bench_threads.py).
"""
from __future__ import annotations

import math

import numba
import numpy as np
from numba import njit, prange

from ...errors import ModelError
from .engine import integrate
from ...execution.scheduling import take, worker_count
from .layout import (METHOD_NAMES, N_DIAG, N_OPTIONS, N_SUMMARY, O_ATOL, O_ENERGY_STOP, O_H_MAX, O_MAX_EVENTS,
                     O_MAX_STEPS, O_METHOD, O_RTOL, O_SCAN, O_STOP_EXCEEDED, O_T_END)

SERIAL_BELOW_JOBS = 2
"""Batches of fewer jobs run serially in the calling thread (:func:`run_packed`).  One job cannot gain from
threads; on an idle machine two already do, while on a loaded one small batches lose to the second
thread's scheduling delay (benchmarks/bench_threads.py, docs/engine.md "Threads"): no larger fixed
count suits both."""


@njit(cache=True)
def _job(j, sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t, ev_k,
         ev_y, summaries, diags, written):
    """Job ``j`` of a batch (the arguments of :func:`_run_batch`): its :func:`integrate` run of the system
    ``sps[systems[j]]``, written into row ``j`` of ``summaries``/``diags``/``written``.  The one loop body of
    both drivers."""
    n = kinds.shape[0]
    o = opts.copy()
    o[O_T_END] = t_ends[j]
    s = samples[offsets[j]:offsets[j] + lengths[j]]
    if n == 1:
        t_o, o_y, e_t, e_k, e_y = t_out, out_y, ev_t, ev_k, ev_y
    else:
        t_o, o_y, e_t, e_k, e_y = (np.zeros(0), np.zeros((0, 4)), np.zeros(0), np.zeros(0, dtype=np.int64),
                                   np.zeros((0, 4)))
    summ, diag, w = integrate(sps[systems[j]], kinds[j], xps[j], s, y0s[j], sides[j], 0.0, o, t_o, o_y, e_t, e_k, e_y)
    written[j] = w
    for k in range(N_SUMMARY):
        summaries[j, k] = summ[k]
    for k in range(N_DIAG):
        diags[j, k] = diag[k]


@njit(cache=True, parallel=True)
def _run_batch(sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t, ev_k,
               ev_y, workers):
    """The jobs in parallel (job ``j`` analyses the system ``sps[systems[j]]``): ``workers`` workers (prange;
    one per numba thread), each taking the next job
    until none is left; a batch of one job also records its history into ``t_out``/``out_y`` and its
    events into ``ev_t``/``ev_k``/``ev_y`` (pass empty arrays otherwise).

    Returns (summaries n × N_SUMMARY, diagnostics n × N_DIAG, output rows written per job), in job order.
    """
    n = kinds.shape[0]
    summaries = np.zeros((n, N_SUMMARY))
    diags = np.zeros((n, N_DIAG), dtype=np.int64)
    written = np.zeros(n, dtype=np.int64)
    counter = np.zeros(1, dtype=np.int64)
    for _ in prange(workers):
        j = take(counter)
        while j < n:
            _job(j, sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t,
                 ev_k, ev_y, summaries, diags, written)
            j = take(counter)
    return summaries, diags, written


def _run_serial(sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t,
                ev_k, ev_y):
    """:func:`_run_batch` one job after the other in the calling thread (no parallel region; the same
    machine code for each job, :func:`_job`)."""
    n = kinds.shape[0]
    summaries = np.zeros((n, N_SUMMARY))
    diags = np.zeros((n, N_DIAG), dtype=np.int64)
    written = np.zeros(n, dtype=np.int64)
    for j in range(n):
        _job(j, sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t, ev_k,
             ev_y, summaries, diags, written)
    return summaries, diags, written


def use_threads(jobs: int) -> bool:
    """True when a batch of ``jobs`` runs on numba's threads, False when serially in the calling thread."""
    return jobs >= SERIAL_BELOW_JOBS and numba.get_num_threads() > 1


def system_rows(sp, n: int, systems=None) -> tuple[np.ndarray, np.ndarray]:
    """(sps, systems) of a batch of ``n`` jobs: ``sp`` one system's parameters (every job's) or a table of
    several systems' rows with ``systems[j]`` the row of job ``j``."""
    sps = np.ascontiguousarray(sp, dtype=np.float64)
    if sps.ndim == 1:
        return sps.reshape(1, -1), np.zeros(n, dtype=np.int64)
    index = np.ascontiguousarray(systems, dtype=np.int64)
    if index.shape != (n,) or (n and (index.min() < 0 or index.max() >= sps.shape[0])):
        raise ValueError("systems: one row index of sps per job")
    return sps, index


def run_packed(sp, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, threads: bool | None = None,
               systems=None):
    """The packed jobs (:func:`pack_motions`), summaries only: (summaries, diagnostics).

    ``sp``: the system of every job, or a table of systems (one row each) with ``systems[j]`` the row of job
    ``j`` (:func:`system_rows`).  ``threads``: run on numba's threads (True), serially in the calling thread
    (False), or by the size of the batch (None, :func:`use_threads`); the results are the same."""
    sides = np.where(y0s[:, 0] >= 0.0, 1.0, -1.0)
    empty = np.zeros(0)
    empty_rows = np.zeros((0, 4))
    sps, index = system_rows(sp, kinds.shape[0], systems)
    args = (sps, index, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, empty, empty_rows, empty,
            np.zeros(0, dtype=np.int64), empty_rows)
    n = kinds.shape[0]
    if use_threads(n) if threads is None else threads:
        summaries, diags, _ = _run_batch(*args, worker_count(n))
    else:
        summaries, diags, _ = _run_serial(*args)
    return summaries, diags


def run_history(sp, kind, xp, samples, y0, side0, opts, t_out, out_y, ev_t, ev_kind, ev_y):
    """One analysis from t = 0 with its history (the arguments of :func:`~.engine.integrate`, t0 = 0, the
    end time in ``opts``); returns (summary, diagnostics, output rows written).

    It runs in the calling thread, as the one job of a serial batch (:func:`_job`, the machine code of
    the parallel driver's jobs): a parallel region would cost more than the analysis on a loaded machine.
    """
    summaries, diags, written = _run_serial(
        np.ascontiguousarray(sp, dtype=np.float64).reshape(1, -1), np.zeros(1, dtype=np.int64),
        np.array([kind], dtype=np.int64), np.ascontiguousarray(xp, dtype=np.float64).reshape(1, -1),
        np.ascontiguousarray(samples, dtype=np.float64), np.zeros(1, dtype=np.int64),
        np.array([samples.shape[0]], dtype=np.int64), np.array([opts[O_T_END]]), opts,
        np.ascontiguousarray(y0, dtype=np.float64).reshape(1, 4), np.array([float(side0)]), t_out, out_y, ev_t,
        ev_kind, ev_y)
    return summaries[0], diags[0], int(written[0])


def batch_options(rtol: float = 1e-10, atol: float = 1e-12, energy_stop: bool = True,
                  stop_at_capacity: bool = False, max_steps: int = 20_000_000, max_events: int = 1_000_000,
                  scan_points: int = 8, method: str = "auto") -> np.ndarray:
    """The ``opts`` array shared by the jobs of a batch (t_end is per job).

    ``method``: ``auto`` (DOP853 for the 2DOF podium at rtol < 5e-8, DP5(4) otherwise — chosen by the
    work-precision data of benchmarks/bench_engine.py), ``dp5`` or ``dop853``.
    """
    codes = {name: code for code, name in METHOD_NAMES.items()}
    if method not in codes:
        raise ModelError("unknown integration method", key="method", expected=" | ".join(codes),
                         found=f"'{method}'")
    opts = np.zeros(N_OPTIONS)
    opts[O_METHOD] = codes[method]
    opts[O_RTOL] = rtol
    opts[O_ATOL] = atol
    opts[O_H_MAX] = math.inf
    opts[O_MAX_STEPS] = max_steps
    opts[O_ENERGY_STOP] = 1.0 if energy_stop else 0.0
    opts[O_STOP_EXCEEDED] = 1.0 if stop_at_capacity else 0.0
    opts[O_SCAN] = scan_points
    opts[O_MAX_EVENTS] = max_events
    return opts


def run_batch(sp: np.ndarray, motions, scales, t_ends, opts: np.ndarray, y0s=None, threads: bool | None = None,
              systems=None):
    """Run ``motions[i]`` scaled by ``scales[i]`` until ``t_ends[i]`` (in parallel unless the batch is small).

    Args:
        sp: system parameters (:func:`rockdesign.planar.dynamics.model.system_parameters`), or a table of several
            systems' parameter rows with ``systems[i]`` the row of job ``i``.
        motions: list of :class:`GroundMotion` (records share their sample arrays; pass the same
            object several times for several scale factors).
        scales: amplitude multipliers per job.
        t_ends: end times [s] per job.
        opts: :func:`batch_options`.
        y0s: optional initial states (n × 4).
        threads: numba's threads (True), the calling thread (False) or by the batch's size (None).

    Returns:
        (summaries n × N_SUMMARY, diagnostics n × N_DIAG) in the order of the jobs.
    """
    n = len(motions)
    kinds, xps, samples, offsets, lengths = pack_motions(motions, scales)
    y0 = np.zeros((n, 4)) if y0s is None else np.ascontiguousarray(y0s, dtype=np.float64)
    return run_packed(sp, kinds, xps, samples, offsets, lengths, np.asarray(t_ends, dtype=np.float64), opts, y0,
                      threads, systems)


def pack_motions(motions, scales) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(kinds, xps, samples, offsets, lengths) of jobs ``motions[i]`` scaled by ``scales[i]``.

    Records shared by several jobs (the same ``GroundMotion`` object) store their samples once.
    """
    n = len(motions)
    kinds = np.array([m.kind for m in motions], dtype=np.int64)
    width = max([m.params.size for m in motions] + [1])
    xps = np.zeros((n, width))
    unique: dict[int, tuple[int, int]] = {}
    chunks = []
    offset = 0
    offsets = np.zeros(n, dtype=np.int64)
    lengths = np.zeros(n, dtype=np.int64)
    for j, (m, f) in enumerate(zip(motions, scales)):
        xps[j, :m.params.size] = m.params
        xps[j, 0] *= f
        key = id(m.samples)
        if key not in unique:
            unique[key] = (offset, m.samples.size)
            chunks.append(m.samples)
            offset += m.samples.size
        offsets[j], lengths[j] = unique[key]
    samples = np.ascontiguousarray(np.concatenate(chunks) if chunks else np.zeros(0), dtype=np.float64)
    return kinds, xps, samples, offsets, lengths
