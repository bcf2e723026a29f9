"""Checking many variants at once (SPEC §15): each variant's check in a thread of its own, their batches merged
into shared calls of the kind's driver (:mod:`rockdesign.execution.batch_pool`), or one after the other where the
kind cannot share batches.  The grid's cells (:mod:`.grid`) and the recommendation's tolerance neighbourhood
(:mod:`.recommend`) run through the same :class:`VariantChecker`, so a neighbour is checked exactly as a cell is.
"""
from __future__ import annotations

import threading
from dataclasses import dataclass, field

from ..errors import ProjectError, RockdesignError
from .cells import EMPTY, base_cell, checked_cell, margin_undecided, not_passing, robustness


def at_once() -> int:
    """Variants checked at the same time (a thread each; the next starts when one ends): 4 per core, at
    least 8, at most 64 — enough jobs per shared call to keep the cores busy, few enough that variants
    finish (and are stored for a resumed run) one after another."""
    from ..execution.executor import usable_cores
    return min(64, max(8, 4 * usable_cores()))


@dataclass
class Task:
    """One variant to check: its key (a grid position or a neighbour's name), the variant, its kind, its shared
    records and where its cell is stored (``store``, ``digest``; None: not stored)."""

    key: object
    variant: object
    kind: object
    records: object
    store: object = None
    digest: str | None = None
    draws: bool = True
    """Run a passing variant's perturbation draws (a grid cell); a tolerance neighbour is judged by its check's
    verdict alone."""


@dataclass
class VariantChecker:
    """Checks lists of :class:`Task` (:meth:`run`), sharing batches between the variants of one call where the
    kind allows (:meth:`~rockdesign.kinds.base.StructureKind.grid_batches`), and counts the shared work
    (``shared``: variants checked together, the batches they asked for, the driver calls that ran them)."""

    variables: list
    records_dir: str | None = None
    executor: object = None
    stage_progress: object = None
    shared: dict = field(default_factory=lambda: {"variants": 0, "batches": 0, "driver_calls": 0, "analyses": 0})
    batches: object = None

    def run(self, tasks: list[Task], done=None) -> dict:
        """Check ``tasks``: ``{task.key: cell}``; ``done(key, cell)`` as each one ends."""
        cells: dict = {}

        def finish(task: Task, cell: dict) -> None:
            cells[task.key] = cell
            if done is not None:
                done(task.key, cell)

        if not tasks:
            return cells
        if self.batches is None:
            kind = tasks[0].kind
            self.batches = kind.grid_batches(self.executor) if self.executor is not None else kind.grid_batches()
        together = [t for t in tasks if t.kind is tasks[0].kind] if self.batches is not None else []
        if len(together) > 1:
            results: dict = {}
            pool = _check_together(together, lambda task, member: results.__setitem__(
                task.key, self.check(task, None, member)), lambda task: finish(task, results[task.key]), at_once(),
                self.batches)
            self.shared["variants"] += len(together)
            self.shared["batches"] += pool.requests
            self.shared["driver_calls"] = getattr(self.batches, "calls", self.shared["driver_calls"] + pool.rounds)
            self.shared["analyses"] = getattr(self.batches, "jobs", None)
        for task in tasks:
            if task.key not in cells:
                finish(task, self.check(task, self.stage_progress, self.executor))
        return cells

    def check(self, task: Task, progress, executor) -> dict:
        """The cell of one variant's check (stored for a resumed run when the task has a store)."""
        from ..execution.executor import here
        executor = here(executor)    # None: this process; the executor counts the analyses
        before = executor.analyses
        variant, kind = task.variant, task.kind

        def analyses() -> int:     # counted on the executor the check ran through (a pool member: this variant's)
            return executor.analyses - before
        try:
            result = kind.grid_check(variant.project, records=task.records, records_dir=self.records_dir,
                                     executor=executor, progress=progress)
        except RockdesignError as exc:  # the variant's own model or geometry is impossible
            cell = {**base_cell(variant, self.variables), **EMPTY, "reason": str(exc),
                    "verdict": "INVALID" if isinstance(exc, ProjectError) else "ERROR",
                    "decided_at_design_level": False, "n_failed_analyses": 0,
                    "analyses": analyses(), "analyses_saved": 0, **not_passing()}
        else:
            nominal = analyses()
            cell = checked_cell(kind, variant, self.variables, result, nominal)
            cell.update(not_passing())
            if cell["verdict"] == "PASS" and not task.draws:
                cell.update(robust=None, robustness="not evaluated: a tolerance neighbour is judged by its check's "
                                                    "verdict (no perturbation draws)")
            elif cell["verdict"] == "PASS":
                precision = getattr(variant.project.analysis, "margin_precision", 0.0)
                near = margin_undecided(cell, precision)
                draws = None if near else kind.grid_draws(result, records=task.records, executor=executor)
                cell.update(robustness(draws, near))
                extra = analyses() - nominal
                cell["analyses"] = analyses()
                cell["analyses_saved"] = max(0, cell["analyses_saved"] - extra)
        if task.store is not None:
            task.store.save(task.digest, cell)
        cell["resumed"] = False
        return cell


def _check_together(tasks, check, report, threads: int, batches):
    """Check ``tasks`` in ``threads`` threads (the next task starting as one ends), ``check(task, member)`` with
    a pool member as the check's executor, their analyses in shared batches (``batches(requests)``, the kind's)
    served by this thread; ``report(task)`` here as each one ends.  An error or Ctrl-C cancels the others
    and is raised.  Returns the :class:`~rockdesign.execution.batch_pool.BatchPool` (its counts)."""
    from concurrent.futures import ThreadPoolExecutor

    from ..execution.batch_pool import BatchPool, PoolCancelled
    pool = BatchPool(len(tasks), batches)
    errors: list[BaseException] = []
    finished: list = []
    lock = threading.Lock()

    def body(task) -> None:
        try:
            with pool.member() as member:
                check(task, member)
        except PoolCancelled:
            return
        except BaseException as exc:    # noqa: BLE001 — raised again in the grid's thread
            errors.append(exc)
            pool.cancel()
            return
        with lock:
            finished.append(task)

    def on_wake() -> None:
        with lock:
            ended, finished[:] = list(finished), []
        for task in ended:
            report(task)

    workers = max(1, min(threads, len(tasks)))
    with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="variant") as pool_threads:
        for task in tasks:
            pool_threads.submit(body, task)
        try:
            pool.serve(on_wake)
        except PoolCancelled:
            pass                        # a variant failed and cancelled the rest: its error is raised below
        except BaseException:
            pool.cancel()               # Ctrl-C: the variants stop at their next batch
            raise
    on_wake()
    if errors:
        raise errors[0]
    return pool


__all__ = ["VariantChecker", "Task", "at_once"]
