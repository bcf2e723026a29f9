"""The planar kind's shared batches: a round of batches of many design variants run as one call of the batch
driver (:func:`~.batch.run_batch` with ``systems``), longest predicted job first; each batch gets its own rows
back (:class:`rockdesign.execution.batch_pool.BatchPool` serves the rounds).  A variant's check maps
:func:`batch_rows` over its executor (the executor protocol); on a pool member those calls come here and are
merged, any other call runs as given.  Batches with other integrator options (``opts``) run as separate calls of
the same round.  On an executor (a dask cluster) the merged jobs of a round go to the cluster in chunks, all at
once: the variants run concurrently there."""
from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from .batch import run_batch
from ...execution.batch_pool import SharedCall, run_call


def balanced_order(costs, threads: int) -> list[int]:
    """The order to hand a batch's jobs to the batch driver's threads: longest predicted ``costs`` first
    (ties in job order).  The threads take the next job as they finish one (:mod:`rockdesign.execution.scheduling`),
    so the batch ends at most one short job after its work is shared out — longest-processing-time-first
    list scheduling, within 4/3 of the best split.  One thread keeps the jobs' own order."""
    n = len(costs)
    if threads < 2 or n < 2:
        return list(range(n))
    return sorted(range(n), key=lambda k: (-costs[k], k))


def batch_rows(sp: np.ndarray, opts: np.ndarray, motions, scales, t_ends, costs) -> tuple[np.ndarray, np.ndarray]:
    """One system's batch of jobs (``motions[i]`` × ``scales[i]`` until ``t_ends[i]`` [s]): :func:`~.batch.run_batch`
    with the longest predicted ``costs`` first (:func:`balanced_order`); (summaries, diagnostics) in job order.
    The function a planar check maps over its executor; :class:`SharedBatches` merges the calls of many checks."""
    order = balanced_order(list(costs), numba.get_num_threads())
    summaries, diags = run_batch(sp, [motions[k] for k in order], [scales[k] for k in order],
                                 [t_ends[k] for k in order], opts)
    s, d = np.empty_like(summaries), np.empty_like(diags)
    s[order], d[order] = summaries, diags
    return s, d


@dataclass
class BatchRequest:
    """One check's batch: a system's parameter row ``sp``, its jobs (motion, scale, end time [s]), the
    integrator options and the predicted cost of each job (the longest runs first)."""

    sp: np.ndarray
    motions: list
    scales: list
    t_ends: list
    opts: np.ndarray
    costs: list

    @classmethod
    def of(cls, common: tuple, args: tuple) -> "BatchRequest":
        """The request of one task of a :func:`batch_rows` call: ``common`` = (sp, opts), ``args`` = (motions,
        scales, t_ends, costs)."""
        sp, opts = common
        motions, scales, t_ends, costs = args
        return cls(sp, list(motions), list(scales), list(t_ends), opts, list(costs))


class SharedBatches:
    """``execute(requests) -> [(summaries, diagnostics), …]`` for a :class:`~rockdesign.execution.batch_pool.BatchPool`;
    ``calls`` and ``jobs`` count the batch-driver calls and the jobs they ran.  ``executor``: a started
    executor of :mod:`rockdesign.execution.executor` (e.g. a dask cluster) that runs each call in chunks
    (:func:`shared_rows`), or None (in this process)."""

    def __init__(self, executor=None):
        self.calls = 0
        self.jobs = 0
        self.executor = executor

    def __call__(self, calls: list[SharedCall]) -> list[dict]:
        """The results of a round of members' calls (``{task index: result}`` each): the tasks of every
        :func:`batch_rows` call merged (:meth:`requests`), any other call run as given."""
        results: list[dict] = [{} for _ in calls]
        owners, requests = [], []
        for c, call in enumerate(calls):
            if call.func is batch_rows:
                for i, args in call.tasks.items():
                    owners.append((c, i))
                    requests.append(BatchRequest.of(call.common, args))
            else:
                results[c] = run_call(call)
        for (c, i), rows in zip(owners, self.requests(requests)):
            results[c][i] = rows
        return results

    def requests(self, requests: list[BatchRequest]) -> list[tuple[np.ndarray, np.ndarray]]:
        """(summaries, diagnostics) of each request, in order, from as few driver calls as their options allow."""
        if not requests:
            return []
        groups: dict[bytes, list[int]] = {}
        for k, req in enumerate(requests):
            groups.setdefault(np.asarray(req.opts, dtype=np.float64).tobytes(), []).append(k)
        results: list = [None] * len(requests)
        for indices in groups.values():
            for k, result in zip(indices, self._group([requests[k] for k in indices])):
                results[k] = result
        return results

    def _group(self, reqs: list[BatchRequest]) -> list[tuple[np.ndarray, np.ndarray]]:
        rows: dict[bytes, int] = {}
        table = []
        jobs = []                                   # (request index, job index, system row)
        for i, req in enumerate(reqs):
            key = np.ascontiguousarray(req.sp, dtype=np.float64).tobytes()
            if key not in rows:
                rows[key] = len(table)
                table.append(np.ascontiguousarray(req.sp, dtype=np.float64))
            jobs.extend((i, j, rows[key]) for j in range(len(req.motions)))
        order = sorted(range(len(jobs)), key=lambda k: (-reqs[jobs[k][0]].costs[jobs[k][1]], k))
        ordered = [jobs[k] for k in order]
        summaries, diags = self._run(np.vstack(table), [reqs[i].motions[j] for i, j, _ in ordered],
                                     [reqs[i].scales[j] for i, j, _ in ordered],
                                     [float(reqs[i].t_ends[j]) for i, j, _ in ordered], reqs[0].opts,
                                     [s for _, _, s in ordered])
        out = [(np.empty((len(r.motions), summaries.shape[1])), np.empty((len(r.motions), diags.shape[1]),
                                                                         dtype=diags.dtype)) for r in reqs]
        for row, (i, j, _) in enumerate(ordered):
            out[i][0][j] = summaries[row]
            out[i][1][j] = diags[row]
        self.calls += 1
        self.jobs += len(jobs)
        return out

    def _run(self, table, motions, scales, t_ends, opts, systems):
        if self.executor is None:
            return run_batch(table, motions, scales, t_ends, opts, systems=systems)
        from ...execution.executor import chunk_size, run_chunks
        n = len(motions)
        size = chunk_size(n, self.executor)
        tasks = [(motions[a:a + size], scales[a:a + size], t_ends[a:a + size], systems[a:a + size])
                 for a in range(0, n, size)]
        run = run_chunks(shared_rows, tasks, common=(table, np.asarray(opts)), executor=self.executor)
        return (np.concatenate([r["summaries"] for r in run.results]),
                np.concatenate([r["diagnostics"] for r in run.results]))


def shared_rows(table, opts, motions, scales, t_ends, systems) -> dict:
    """The chunk function of a shared call on an executor: ``run_batch`` of the jobs ``motions[i]`` ×
    ``scales[i]`` until ``t_ends[i]`` [s] on the system row ``table[systems[i]]``; {"summaries", "diagnostics"}."""
    s, d = run_batch(table, motions, scales, t_ends, opts, systems=systems)
    return {"summaries": s, "diagnostics": d}
