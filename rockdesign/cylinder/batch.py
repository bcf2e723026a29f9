"""The cylinder's 3D analyses in batches (thesis Ch. 5): each stage of the check — the design-level suite, every
round of the incremental scans, the perturbation ensemble — hands a list of independent analyses to one
:class:`PairRunner`, which runs them in this process or on an executor (the shared executor protocol of
:mod:`rockdesign.execution.executor`: ``start``, ``map``, ``close``, ``describe``; ``rockdesign check --dask``).

An analysis depends only on its own pair, tolerances and the cylinder, so a batch gives the same runs wherever
and in whatever order its analyses run (tests/cylinder/test_cylinder_executor.py compares them).
"""
from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Sequence

from ..execution.executor import chunk_size, here, one_core, slots_of
from .engine import STATUS, simulate_cylinder
from .kernel import ST_COMPLETED, ST_OVERTURNED

COMPLETED = (STATUS[ST_COMPLETED], STATUS[ST_OVERTURNED])
"""Statuses of a cylinder analysis that ran to a conclusion."""
SLOW_RUN_SECONDS = 1.0
"""A 3D analysis longer than this (≈ 100 × a 30-s pair's) is noted on the console with its reason."""


@dataclasses.dataclass(frozen=True)
class PairRun:
    """The 3D response to one pair in the terms the criteria read (:class:`~rockdesign.acceptance.criteria.CheckContext`).

    ``status`` is "completed" for an analysis that ran to a conclusion (overturned or not:
    ``overturned`` says which) and the engine's status otherwise; ``engine_status`` is the engine's own
    word (results.json ``status``).  ``response_ratio`` is θ_max/θ_ot (θ_ot: the 3D overturning tilt; the
    acceptance code's :class:`rockdesign.acceptance.outcome.Run`)."""

    theta_max_over_alpha: float
    response_ratio: float
    overturned: bool
    overturn_mode: str
    quasi_impacts: int
    uplift_time: float | None
    engine_status: str
    min_contact_force_over_weight: float | None = None

    @property
    def status(self) -> str:
        return "completed" if self.engine_status in COMPLETED else self.engine_status

    @property
    def failed(self) -> bool:
        """True when the 3D analysis did not run to a conclusion (step size collapsed, step limit)."""
        return self.engine_status not in COMPLETED


def run_pair(cyl, a, pair, rtol: float | None = None, atol: float | None = None) -> tuple[PairRun, float, str]:
    """One 3D analysis of the scaled ``pair`` (Eqs 5.1–5.41 through :func:`~rockdesign.cylinder.engine.simulate_cylinder`)
    at the project's tolerances or ``rtol``/``atol``: the run, its wall time [s] and why it cost what it did.
    Module-level and free of callbacks, so an executor's worker can run it."""
    t0 = time.perf_counter()
    r = simulate_cylinder(cyl, pair, free_vibration=a.free_vibration, rtol=rtol or a.rtol, atol=atol or a.atol,
                          rest_velocity=a.rest_velocity)
    seconds = time.perf_counter() - t0
    run = PairRun(r.theta_max / cyl.alpha, r.theta_max / cyl.theta_overturn, r.overturned, r.overturn_mode,
                  r.quasi_impacts, r.uplift_time, r.status, r.min_contact_force_over_weight if cyl.damped else None)
    return run, seconds, r.cost_reason() if seconds > SLOW_RUN_SECONDS else ""


@one_core       # its 3D integration releases the GIL: in this process the analyses run in threads, one per core
def run_pairs(cyl, a, jobs) -> list[tuple[PairRun, float, str]]:
    """:func:`run_pair` of each job ``(pair, rtol, atol)`` of a chunk, in order (one task of an executor)."""
    return [run_pair(cyl, a, *job) for job in jobs]


def analyses_per_task(n: int, executor) -> int:
    """3D analyses per task when ``n`` go to ``executor``: one analysis runs on one core, so one per task on a
    single slot (this process: its threads take the next analysis as they finish one, and the progress moves with
    each), a few chunks per slot elsewhere (:func:`~rockdesign.execution.executor.chunk_size`)."""
    return 1 if slots_of(executor) == 1 else chunk_size(n, executor)


Job = tuple
"""One analysis of a batch: ``(pair, rtol, atol)`` (a tolerance None: the project's)."""


class PairRunner:
    """Runs batches of independent 3D analyses of one cylinder: ``runner(jobs, done) -> [PairRun]`` in job order.

    Args:
        cyl, a: the cylinder and the project's ``[analysis]``.
        executor: None (this process: one analysis per core at a time, in threads) or an executor object
            (:func:`rockdesign.execution.executor.is_executor`): the batch's analyses are mapped over it.
        note: ``note(pair name, text)`` for an analysis slower than :data:`SLOW_RUN_SECONDS`.

    Every analysis is counted on the executor it ran through (``executor.count``; read ``executor.analyses``)."""

    def __init__(self, cyl, a, *, executor=None, note: Callable[[str, str], None] | None = None):
        self.cyl, self.a, self.note = cyl, a, note
        self.executor = here(executor)

    def count(self, n: int) -> None:
        """Count ``n`` analyses run here beside the batches (e.g. the planar runs along a pair's components)."""
        self.executor.count(n)

    def __call__(self, jobs: Sequence[Job], done: Callable[[int], None] | None = None) -> list[PairRun]:
        """The runs of ``jobs`` in their order; ``done(k)`` after each k-th analysis ends (in completion order)."""
        jobs = [tuple(j) + (None,) * (3 - len(j)) for j in jobs]
        out: list = [None] * len(jobs)
        if not jobs:
            return out
        size = analyses_per_task(len(jobs), self.executor)
        first = list(range(0, len(jobs), size))
        self.executor.start()
        finished = self.executor.map(run_pairs, (self.cyl, self.a),
                                     {c: (jobs[start:start + size],) for c, start in enumerate(first)})
        count = 0
        for c, results in finished:
            self.executor.count(len(results))
            for k, (run, seconds, reason) in enumerate(results, start=first[c]):
                out[k] = run
                count += 1
                if self.note is not None and reason:
                    self.note(jobs[k][0].name, f"{seconds:.1f} s, {reason}")
                if done is not None:
                    done(count)
        return out


@one_core       # a task of the design grid's shared rounds: one member's 3D analyses (they release the GIL)
def run_tasks(tasks) -> list:
    """``func(*common, *args)`` of each ``(func, common, args)`` of ``tasks``, in order (one task of an executor)."""
    return [func(*common, *args) for func, common, args in tasks]


class SharedPairs:
    """``execute(calls) -> [{index: result}, …]`` for the design grid's pool (:mod:`rockdesign.execution.batch_pool`):
    the cylinder variants of a grid checked together, every task of every member's call of a round in one map over
    ``executor`` (None: this process, one analysis per core in threads), so a round with few analyses of one
    variant (a scan's) shares the cores with the others'.  A task's result does not depend on the others, so each
    variant gets what its own check computes.  ``calls`` and ``jobs`` count the rounds run and their tasks (one 3D
    analysis each: a member's runner hands out one analysis per task)."""

    def __init__(self, executor=None):
        self.executor = here(executor)
        self.calls = 0
        self.jobs = 0

    def __call__(self, calls) -> list[dict]:
        owners = [(c, i) for c, call in enumerate(calls) for i in call.tasks]
        flat = [(calls[c].func, calls[c].common, calls[c].tasks[i]) for c, i in owners]
        results: list[dict] = [{} for _ in calls]
        if flat:
            size = analyses_per_task(len(flat), self.executor)
            first = list(range(0, len(flat), size))
            for k, rows in self.executor.map(run_tasks, (), {k: (flat[a:a + size],) for k, a in enumerate(first)}):
                for (c, i), row in zip(owners[first[k]:first[k] + size], rows):
                    results[c][i] = row
        self.calls += 1
        self.jobs += len(flat)
        return results
