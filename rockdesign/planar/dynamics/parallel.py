"""Large batches of time-history analyses (record suites, scale factors of margins) on the chunked executor.

:func:`run_motions` is :func:`rockdesign.planar.dynamics.batch.run_batch` cut into chunks of jobs and mapped
over an executor of :mod:`rockdesign.execution.executor` — in this process on all cores, or on
dask.distributed — optionally resumable from chunk files. The sample arrays of the records travel
once (broadcast to the workers); each job carries its excitation code, parameter row and the slice
of the samples it uses. Results are identical to ``run_batch`` bit for bit.
"""
from __future__ import annotations

from typing import Callable, Sequence

import numpy as np

from .batch import pack_motions, run_packed
from ...kernel_cache import sources_digest
from ...execution.executor import ChunkStore, fingerprint, here, run_chunks


def motion_rows(sp: np.ndarray, samples: np.ndarray, opts: np.ndarray, kinds: np.ndarray, xps: np.ndarray,
                offsets: np.ndarray, lengths: np.ndarray, t_ends: np.ndarray, y0s: np.ndarray) -> dict:
    """The chunk function: jobs ``kinds[i], xps[i], samples[offsets[i]:offsets[i]+lengths[i]]`` until
    ``t_ends[i]`` [s] (:func:`~.batch.run_packed`: numba's threads, jobs handed out dynamically). Returns {"summaries": n × N_SUMMARY,
    "diagnostics": n × N_DIAG}."""
    s, d = run_packed(sp, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s)
    return {"summaries": s, "diagnostics": d}


def run_motions(sp: np.ndarray, motions: Sequence, scales, t_ends, opts: np.ndarray, *, y0s=None, executor=None,
                chunk_jobs: int = 64, store_dir=None, resume: bool = True, keep_chunks: bool = False,
                progress: Callable[[int], None] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`~rockdesign.planar.dynamics.batch.run_batch` over the chunked executor.

    Args:
        sp: system parameters; motions, scales, t_ends [s], opts, y0s: as ``run_batch``.
        executor: :class:`~rockdesign.execution.executor.LocalExecutor` (default) or
            :class:`~rockdesign.execution.executor.DaskExecutor`.
        chunk_jobs: jobs per chunk.
        store_dir: chunk folder (resumable), or None; deleted after success unless ``keep_chunks``.
        progress: called with the number of jobs of every finished chunk.

    Returns:
        (summaries n × N_SUMMARY, diagnostics n × N_DIAG) in job order, equal to ``run_batch``'s.
    """
    kinds, xps, samples, offsets, lengths = pack_motions(motions, scales)
    n = kinds.size
    t_ends = np.asarray(t_ends, dtype=np.float64)
    y0 = np.zeros((n, 4)) if y0s is None else np.ascontiguousarray(y0s, dtype=np.float64)
    bounds = [(i, min(i + chunk_jobs, n)) for i in range(0, n, max(1, int(chunk_jobs)))]
    tasks = [(kinds[a:b], xps[a:b], offsets[a:b], lengths[a:b], t_ends[a:b], y0[a:b]) for a, b in bounds]
    store = None
    if store_dir is not None:
        store = ChunkStore(store_dir, fingerprint("motion-rows-1", sources_digest(), sp, samples, opts, kinds, xps,
                                                  offsets, lengths, t_ends, y0, int(chunk_jobs)))

    def on_chunk(i, resumed):
        if progress is not None:
            progress(bounds[i][1] - bounds[i][0])

    run = run_chunks(motion_rows, tasks, common=(np.ascontiguousarray(sp, dtype=np.float64), samples, opts),
                     executor=here(executor), store=store, resume=resume,
                     progress=on_chunk)
    if store is not None and not keep_chunks:
        store.clear()
    if not run.results:
        from .layout import N_DIAG, N_SUMMARY
        return np.zeros((0, N_SUMMARY)), np.zeros((0, N_DIAG), dtype=np.int64)
    return (np.concatenate([r["summaries"] for r in run.results]),
            np.concatenate([r["diagnostics"] for r in run.results]))
