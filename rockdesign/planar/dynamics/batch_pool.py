"""Shared batches: the analyses of many design variants run together, one batch-driver call for the jobs
of every variant that is waiting (the design grid, SPEC §15).

The design grid checks each variant in a thread of its own (:mod:`rockdesign.design_space.grid`).  Every
batch a variant's check asks for (:func:`rockdesign.planar.checks.runner.run_jobs`) comes here
(:meth:`BatchPool.run`) and waits until every running variant thread waits too; then the grid's own
thread (:meth:`BatchPool.serve`) runs all waiting batches as one call of the batch driver — jobs of
several systems, :func:`~.batch.run_batch` with ``systems`` — longest predicted job first, and hands each
thread its rows.  A check's own Python work (model selection, criteria) runs between its batches, while
the others wait.

Why: a variant's check asks for batches of a few jobs at a time (a chunk of its suite, one round of a
margin scan); alone, each batch ends with idle threads while its last long job finishes, and each pays
for a parallel region.  Shared, the grid's batches are as many times larger as there are variants
running, so the cores stay busy to the end of each call (0.79× the time of one variant after the other
for a 3 × 3 grid on 2 cores, docs/design.md; more so on a machine with many cores).

Results: a job's result does not depend on the other jobs of its batch (each writes only its own row,
``tests/dynamics/test_batch_threads.py``), so every variant gets exactly what its own check computes, and
its verdict is the check's.  Batches with different integrator options (``opts``) run as separate calls
of the same round.  Python's threads only wait here and do bookkeeping: the numerical work is the batch
driver's (numba's threads), one call at a time.

Written by hand: a thread pool hands out whole tasks, not a barrier that merges the requests of tasks
that are all blocked.
"""
from __future__ import annotations

import threading
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np

from .batch import run_batch


class PoolCancelled(RuntimeError):
    """The pool was cancelled (the grid was interrupted): a waiting variant stops here."""


@dataclass
class _Request:
    sp: np.ndarray
    motions: list
    scales: list
    t_ends: list
    opts: np.ndarray
    costs: list
    result: tuple | None = None
    error: BaseException | None = None


class BatchPool:
    """A barrier that merges the batches of its member threads (see module docstring), served by one owner
    thread.  ``calls`` and ``jobs`` count the batch-driver calls made and the jobs they ran; ``requests`` the
    batches asked for.

    The owner makes the pool for ``members`` pieces of work, runs them in threads (each inside
    :meth:`member`; as many at a time as it likes, the next starting when one ends) and calls :meth:`serve`,
    which runs every round of waiting batches in the owner's thread — numba's parallel regions are always
    opened by that one thread — until every member has ended.  A round runs when every *running* member
    waits, so a member still queued for a thread never holds the others up."""

    def __init__(self, members: int):
        self.calls = 0
        self.jobs = 0
        self.requests = 0
        self._cv = threading.Condition()
        self._unfinished = int(members)
        self._running = 0
        self._pending: list[_Request] = []
        self._cancelled = False

    @contextmanager
    def member(self):
        """Run the ``with`` block as one of the pool's members: :func:`current_pool` is this pool in it, and
        its end (normal or not) releases the others' batches from waiting for this one."""
        with self._cv:
            self._running += 1
        _local.pool = self
        try:
            yield self
        finally:
            _local.pool = None
            with self._cv:
                self._running -= 1
                self._unfinished -= 1
                self._cv.notify_all()

    def cancel(self) -> None:
        """Wake every waiting member with :class:`PoolCancelled` (their batches are not run)."""
        with self._cv:
            self._cancelled = True
            self._cv.notify_all()

    def run(self, sp, motions, scales, t_ends, opts, costs=None) -> tuple[np.ndarray, np.ndarray]:
        """The (summaries, diagnostics) of ``run_batch(sp, motions, scales, t_ends, opts)`` (a member's call),
        computed by the owner in one call with the other members' waiting batches.  ``costs``: predicted
        cost per job (the longest run first; default the end times)."""
        req = _Request(np.ascontiguousarray(sp, dtype=np.float64), list(motions), list(scales),
                       [float(t) for t in t_ends], opts, list(t_ends if costs is None else costs))
        with self._cv:
            self.requests += 1
            self._pending.append(req)
            self._cv.notify_all()
            while req.result is None and req.error is None:
                if self._cancelled:
                    raise PoolCancelled("the design grid was interrupted")
                self._cv.wait()
        if req.error is not None:
            raise req.error
        return req.result

    def serve(self, on_wake=None, poll: float = 0.5) -> None:
        """The owner's loop: run each round of batches once every running member waits, until every member
        has ended.  ``on_wake()`` is called in this thread after every round and whenever a member ends (or
        every ``poll`` seconds), e.g. to report finished variants."""
        while True:
            with self._cv:
                while not self._cancelled and self._unfinished > 0 and not self._ready():
                    if not self._cv.wait(timeout=poll):
                        break
                if self._cancelled:
                    raise PoolCancelled("the design grid was interrupted")
                if self._unfinished <= 0 and not self._pending:
                    break
                ready = self._ready()
                batch, self._pending = (self._pending, []) if ready else ([], self._pending)
            if batch:
                self._run_round(batch)
                with self._cv:
                    self._cv.notify_all()
            if on_wake is not None:
                on_wake()
        if on_wake is not None:
            on_wake()

    def _ready(self) -> bool:
        """Every running member waits here (called holding the lock)."""
        return bool(self._pending) and len(self._pending) >= self._running

    def _run_round(self, batch: list[_Request]) -> None:
        groups: dict[bytes, list[_Request]] = {}
        for req in batch:
            groups.setdefault(np.asarray(req.opts, dtype=np.float64).tobytes(), []).append(req)
        for reqs in groups.values():
            try:
                self._run_group(reqs)
            except BaseException as exc:   # noqa: BLE001 — handed to every thread of the group, raised there
                for req in reqs:
                    req.error = exc

    def _run_group(self, reqs: list[_Request]) -> None:
        rows: dict[bytes, int] = {}
        table = []
        jobs = []                                   # (request, job index, system row)
        for req in reqs:
            key = req.sp.tobytes()
            if key not in rows:
                rows[key] = len(table)
                table.append(req.sp)
            jobs.extend((req, j, rows[key]) for j in range(len(req.motions)))
        order = sorted(range(len(jobs)), key=lambda k: (-jobs[k][0].costs[jobs[k][1]], k))
        ordered = [jobs[k] for k in order]
        summaries, diags = run_batch(np.vstack(table), [r.motions[j] for r, j, _ in ordered],
                                     [r.scales[j] for r, j, _ in ordered], [r.t_ends[j] for r, j, _ in ordered],
                                     reqs[0].opts, systems=[s for _, _, s in ordered])
        out = {id(r): (np.empty((len(r.motions), summaries.shape[1])), np.empty((len(r.motions), diags.shape[1]),
                                                                               dtype=diags.dtype)) for r in reqs}
        for row, (r, j, _) in enumerate(ordered):
            out[id(r)][0][j] = summaries[row]
            out[id(r)][1][j] = diags[row]
        for r in reqs:
            r.result = out[id(r)]
        self.calls += 1
        self.jobs += len(jobs)


_local = threading.local()


def current_pool() -> BatchPool | None:
    """The pool the calling thread is a member of (:meth:`BatchPool.member`), or None."""
    return getattr(_local, "pool", None)


__all__ = ["BatchPool", "PoolCancelled", "current_pool"]
