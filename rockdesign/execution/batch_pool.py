"""Shared batches: the analyses of many checks running in threads, merged into one call of the numerical
driver while every one of them waits (the design grid, SPEC §15).

The design grid checks each variant in a thread of its own (:mod:`rockdesign.design_space.grid`) and passes
each one a :class:`PoolMember` as the executor of its check.  Every batch a variant's check asks for comes to
:meth:`PoolMember.map` (the executor protocol every kind accepts) and waits until every running member waits too; then the grid's own thread
(:meth:`BatchPool.serve`) hands all waiting batches to the kind's ``execute(requests)`` (the planar kind:
one call of its batch driver over the jobs of every variant, :mod:`rockdesign.planar.dynamics.shared_batches`)
and gives each member its own rows back.  A check's own Python work (model selection, criteria) runs between
its batches, while the others wait.  numba's parallel regions are always opened by the one serving thread.

Why: a variant's check asks for batches of a few jobs at a time (a chunk of its suite, one round of a
margin scan); alone, each batch ends with idle threads while its last long job finishes, and each pays
for a parallel region.  Shared, the grid's batches are as many times larger as there are variants
running (docs/design.md).  A job's result does not depend on the other jobs of its batch, so every variant
gets exactly what its own check computes.

Written by hand: a thread pool hands out whole tasks, not a barrier that merges the requests of tasks that
are all blocked.  The member is passed down as an argument (the check's ``executor``): nothing is kept per
thread.
"""
from __future__ import annotations

import threading
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Callable, Iterator

from .counting import Counted


class PoolCancelled(RuntimeError):
    """The pool was cancelled (the grid was interrupted): a waiting member stops here."""


class _Waiting:
    __slots__ = ("request", "result", "error", "done")

    def __init__(self, request):
        self.request, self.result, self.error, self.done = request, None, None, False


@dataclass(frozen=True)
class SharedCall:
    """What a member asks the pool for: ``func(*common, *args)`` for every ``args`` of ``tasks`` (``{index: args}``),
    one :meth:`PoolMember.map` call.  The pool's ``execute`` may merge the calls of a kind's batch function into
    one call of its driver, and runs any other call as given (:func:`run_call`)."""

    func: Callable
    common: tuple
    tasks: dict


def run_call(call: SharedCall) -> dict:
    """``{index: func(*common, *args)}`` of a :class:`SharedCall`, in this thread, task after task."""
    return {i: call.func(*call.common, *args) for i, args in call.tasks.items()}


class PoolMember(Counted):
    """One member's door to the pool: the executor a variant's check runs its batches through (the executor
    protocol, :data:`~rockdesign.execution.executor.EXECUTOR_METHODS`).  ``map`` hands the batch to the pool as
    one :class:`SharedCall` and waits for its round; ``analyses`` counts the analyses the member's check ran
    (the design grid's per-variant count)."""

    slots = 1
    """A member's batch runs in this process, in the pool owner's thread (the kind's driver uses the cores)."""

    def __init__(self, pool: "BatchPool"):
        self.pool = pool

    def start(self) -> None:
        """Nothing to start: the pool's owner serves the rounds."""

    def close(self) -> None:
        """Nothing to close: the member ends with its ``with`` block (:meth:`BatchPool.member`)."""

    def describe(self) -> dict:
        """What the executor is (for results and logs)."""
        return {"executor": "shared batches"}

    def map(self, func, common: tuple, tasks: dict) -> Iterator[tuple[int, object]]:
        """Yield ``(index, func(*common, *tasks[index]))`` for every task, computed in one round of the pool together
        with the other members' waiting batches."""
        results = self.pool._run(SharedCall(func, tuple(common), dict(tasks)))
        for i in tasks:
            yield i, results[i]


class BatchPool:
    """A barrier that merges the requests of its members (see module docstring), served by one owner thread.

    ``execute(requests) -> results`` runs a round of requests (:class:`SharedCall`; one result per request, in
    order: ``{index: result}``; an exception goes to every member of the round).  ``rounds`` and ``requests`` count the rounds served and the requests
    asked for; ``execute`` may keep its own counts (driver calls, jobs).

    The owner makes the pool for ``members`` pieces of work, runs them in threads (each inside :meth:`member`;
    as many at a time as it likes, the next starting when one ends) and calls :meth:`serve` until every member
    has ended.  A round runs when every *running* member waits, so a member still queued for a thread never
    holds the others up."""

    def __init__(self, members: int, execute: Callable[[list], list]):
        self.execute = execute
        self.rounds = 0
        self.requests = 0
        self._cv = threading.Condition()
        self._unfinished = int(members)
        self._running = 0
        self._pending: list[_Waiting] = []
        self._cancelled = False

    @contextmanager
    def member(self):
        """Run the ``with`` block as one of the pool's members; it yields the :class:`PoolMember` to pass down
        as the check's executor.  Its end (normal or not) releases the others from waiting for it."""
        with self._cv:
            self._running += 1
        try:
            yield PoolMember(self)
        finally:
            with self._cv:
                self._running -= 1
                self._unfinished -= 1
                self._cv.notify_all()

    def cancel(self) -> None:
        """Wake every waiting member with :class:`PoolCancelled` (their requests are not run)."""
        with self._cv:
            self._cancelled = True
            self._cv.notify_all()

    def _run(self, request):
        waiting = _Waiting(request)
        with self._cv:
            self.requests += 1
            self._pending.append(waiting)
            self._cv.notify_all()
            while not waiting.done:
                if self._cancelled:
                    raise PoolCancelled("the design grid was interrupted")
                self._cv.wait()
        if waiting.error is not None:
            raise waiting.error
        return waiting.result

    def serve(self, on_wake=None, poll: float = 0.5) -> None:
        """The owner's loop: run each round of requests once every running member waits, until every member
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

    def _run_round(self, batch: list[_Waiting]) -> None:
        try:
            results = self.execute([w.request for w in batch])
        except BaseException as exc:   # noqa: BLE001 — handed to every member of the round, raised there
            for w in batch:
                w.error, w.done = exc, True
        else:
            for w, result in zip(batch, results):
                w.result, w.done = result, True
        self.rounds += 1


__all__ = ["BatchPool", "PoolCancelled", "PoolMember", "SharedCall", "run_call"]
