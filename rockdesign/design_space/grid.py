"""The design grid's runner: the check of every variant, with the work the variants share done once (SPEC §15).

Shared work:

- the records of the excitation are read and scaled once per distinct excitation (every variant of a
  ``pga``/``factor``/``spectrum``/``sdmax``-scaled suite shares them; ``uplift`` scaling depends on the
  variant's uplift acceleration and is keyed on it; a cylinder's record pairs and their SD_max are
  shared by the variants of one ``[excitation]``) and handed to the check's ``records`` hook;
- the kernels compile (or load from the cache) once, in this one process;
- the analyses of all variants run together: each variant's check runs in a thread of its own and its
  batches (a chunk of a suite, a round of a margin scan, a perturbation draw) wait for the other running
  variants' to run as one call of the numerical driver (:mod:`rockdesign.execution.batch_pool`, the kind's
  ``grid_batches``) — as many times more jobs per call as there are variants running (:func:`at_once`), so
  the cores stay busy to the end of each call; on a dask cluster each shared call is submitted to the
  cluster in chunks, all at once (the variants run there concurrently);
- each variant runs the check's own stages through its kind's grid hooks (:mod:`rockdesign.kinds`:
  ``grid_records``, ``grid_check``, ``grid_cell``, ``grid_draws``; planar:
  :func:`rockdesign.planar.checks.check.run_check`, cylinder: :func:`rockdesign.cylinder.check.run_cylinder_check`,
  both with ``verdict_only``): model selection, the design-level suite, the margin scans and the demand — so
  a cell's verdict is the check's verdict of that variant;
- a variant stops once its verdict is decided: when the design-level suite already fails the acceptance
  rule (or an analysis failed) the margin scans and the demand re-runs are skipped — the margins can
  only add failing criteria; report histories, the engine-accuracy appendix and a cylinder's planar runs
  per component are skipped everywhere;
- robustness (SPEC §15, CONTRACT §7.4): a variant that passes runs its check's perturbation draws
  (``grid_draws``: c_r ± 2 % and the ensemble's suite runs, the check's seed), stopping at the first draw
  that fails — ``robust`` true when every draw passes, false otherwise or when the ACMR is within the
  scans' resolution of its requirement (:func:`margin_undecided`), null unless PASS;
- every analysed cell carries the distance of its verdict to the flip (:mod:`rockdesign.acceptance.flip`): a
  passing variant's scans stop once the cell's numbers are decided, and a FAIL decided at the design level is
  scanned below it for that distance alone (:class:`~rockdesign.acceptance.scans.ScanNeed`);
- coarse to fine (:mod:`.refine`): a coarse sub-grid first, then the cells where neighbours disagree; a cell
  between agreeing neighbours far from their flip is left unanalysed (``"analysed": false``, no verdict word)
  unless ``every_cell``; no cell left out touches a cell of another verdict, and a seeded sample of them is
  analysed as an audit (``inference_audit``).

Every finished variant is stored in ``<out>/variants/<digest>.json`` (:mod:`.store`: the digest of the
variant's project text, the content of its scaled records, the tool version and the kernel sources): a run
interrupted and started again skips them, each placed in the current grid (its index and labels are the
current grid's, never the stored file's); a stored file that cannot be used is analysed again with a warning.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..display import verdict_words
from ..kinds import kind_of
from .batches import Task, VariantChecker
from .cells import inferred_cell, invalid_cell
from .recommend import PREFER, check_exit_code, recommended
from .store import VariantStore, content_digest, tool_digest, variant_digest
from .variants import Variant, variant_toml


@dataclass
class GridRun:
    """The grid's outcome: ``cells`` (one dict per variant, design.json's ``cells``), the analyses run
    and the lower bound of those saved, how many variants came from a stored earlier run, and
    ``shared_batches`` — the variants checked together, the batches they asked for and the calls of the
    batch driver that ran them (None when no variants ran together); ``inference`` — the cells left out and
    the audit of that inference (None when every cell was analysed or none could be left out)."""

    variables: list
    cells: list[dict]
    analyses_run: int = 0
    analyses_saved: int = 0
    resumed: int = 0
    notes: list[str] = field(default_factory=list)
    shared_batches: dict | None = None
    warnings: list[str] = field(default_factory=list)
    """Stored variants that could not be used (analysed again), in the words told to ``warn``."""
    inference: dict | None = None
    checker: VariantChecker | None = None
    """The checker that ran the cells (the recommendation's neighbourhood runs through it too)."""
    records: dict | None = None
    store: VariantStore | None = None


def records_key(variant: Variant) -> str:
    kind = kind_of(variant.project)
    return f"{kind.name}\n{kind.grid_records_key(variant.project)}"


def read_records(variant_list: list[Variant], records_dir=None, cache: dict | None = None) -> dict[str, tuple]:
    """The records of every distinct excitation of the valid variants, read and scaled once
    (:meth:`~rockdesign.kinds.base.StructureKind.grid_records`): ``{records_key: (records, content digest)}``.
    Input errors in the records (a missing suite file, a record not found) raise here, before any analysis."""
    cache = {} if cache is None else cache
    for variant in variant_list:
        if variant.project is None:
            continue
        key = records_key(variant)
        if key not in cache:
            records = kind_of(variant.project).grid_records(variant.project, records_dir)
            cache[key] = (records, content_digest(records))
    return cache


def task_of(key, variant: Variant, records: dict, store: VariantStore | None, tool: str,
            draws: bool = True) -> tuple[Task, dict | None]:
    """The task of checking ``variant`` (``draws``: with a passing variant's perturbation draws) and its stored
    cell of an earlier run (None: to be checked); a check without draws is stored under another name."""
    kind = kind_of(variant.project)
    recs, recs_digest = records[records_key(variant)]
    digest = None
    if store is not None:
        text = variant_toml(variant.raw) + ("" if draws else "\n# verdict only: no perturbation draws\n")
        digest = variant_digest(kind.name, text, recs_digest, tool)
        stored = store.load(digest)
        if stored is not None:
            return Task(key, variant, kind, recs, store, digest, draws), stored
    return Task(key, variant, kind, recs, store, digest, draws), None


def run_grid(variant_list: list[Variant], variables, *, records_dir=None, executor=None, store=None,
             progress=None, stage_progress=None, warn=None, records: dict | None = None,
             every_cell: bool = False, seed: int = 0) -> GridRun:
    """Check every variant (see module docstring); ``progress(done, total, cell)`` as each variant ends (or
    is left unanalysed), ``stage_progress(stage, done, total)`` inside one (the check's stages; not while
    variants run together); ``store``: the folder (or :class:`~.store.VariantStore`) of the per-variant results
    that makes the run resumable (None: nothing stored); ``warn(text)``: a stored variant that cannot be used
    (it is analysed again); ``records``: :func:`read_records` of these variants when already read;
    ``every_cell``: analyse every cell (default: coarse to fine, :mod:`.refine` — cells between agreeing
    corners far from their flip are left unanalysed, ``"analysed": false``); ``seed``: of the audit's sample.

    Variants whose analyses can share batches (:meth:`~rockdesign.kinds.base.StructureKind.grid_batches`)
    are checked together, each in a thread of its own with a pool member as its check's executor, their
    batches merged into shared calls of the kind's driver (:mod:`rockdesign.execution.batch_pool`) — on a dask
    cluster (``executor``) too, each shared call submitted to the cluster at once."""
    from .refine import agreed, audit_sample, category, levels, unsafe
    run = GridRun(list(variables), [])

    def warned(text: str) -> None:
        run.warnings.append(text)
        if warn is not None:
            warn(text)

    if store is not None and not isinstance(store, VariantStore):
        store = VariantStore(store)
    if store is not None:
        store.warn = warned
    records = read_records(variant_list, records_dir, records)    # input errors stop the grid, before any analysis
    tool = tool_digest() if store is not None else ""
    total = len(variant_list)
    cells: list[dict | None] = [None] * total
    tasks = {}
    for pos, variant in enumerate(variant_list):
        if variant.project is None:
            cells[pos] = invalid_cell(variant, variables)
            continue
        tasks[pos], stored = task_of(pos, variant, records, store, tool)
        if stored is not None:      # its place is this grid's, not the stored file's
            cells[pos] = {**stored, **_place(variant, variables), "resumed": True}
            run.resumed += 1
    checker = VariantChecker(list(variables), records_dir, executor, stage_progress)
    done = [0]
    reported: set = set()

    def report(pos: int) -> None:
        if pos in reported:
            return
        reported.add(pos)
        done[0] += 1
        cell = cells[pos]
        if cell.get("analysed", True) and not cell.get("resumed"):
            run.analyses_run += cell.get("analyses") or 0
            run.analyses_saved += cell.get("analyses_saved") or 0
        if progress is not None:
            progress(done[0], total, cell)

    def analyse(positions) -> None:
        todo = [tasks[p] for p in positions if p in tasks and (cells[p] is None or not cells[p].get("analysed", True))]
        for p in positions:
            if cells[p] is not None and cells[p].get("analysed", True):
                report(p)

        def finished(pos, cell):
            cells[pos] = cell
            report(pos)
        checker.run(todo, finished)

    shape = tuple(len(v.values) for v in variables)
    position = {tuple(v.index): k for k, v in enumerate(variant_list)}
    full = bool(shape) and len(position) == total == math.prod(shape)
    order = ([[position[i] for i in lvl] for lvl in levels(shape, every_cell)] if full
             else [list(range(total))])       # a list of variants that is not a whole grid: every one
    known: dict = {}
    for level, positions in enumerate(order):
        todo = []
        for pos in positions:
            index = tuple(variant_list[pos].index)
            between = agreed(index, shape, level, known) if cells[pos] is None and full else None
            if between is not None:
                cells[pos] = inferred_cell(variant_list[pos], variables, between)
            else:
                todo.append(pos)
        analyse(todo)
        for pos in positions:
            known[tuple(variant_list[pos].index)] = cells[pos]

    def left_out() -> list:
        return [pos for pos in range(total) if not cells[pos].get("analysed", True)]

    if full and left_out():
        while True:                  # never infer across an edge
            edge = [position[i] for i in unsafe(shape, known)]
            if not edge:
                break
            analyse(edge)
            for pos in edge:
                known[tuple(variant_list[pos].index)] = cells[pos]
        inferred = {pos: cells[pos]["between"] for pos in left_out()}
        sample = [position[i] for i in audit_sample([tuple(variant_list[p].index) for p in inferred], seed)]
        analyse(sample)
        agreed_n = 0
        for pos in sample:
            cells[pos]["audit"] = {"between": inferred[pos], "agreed": category(cells[pos]) == inferred[pos]}
            agreed_n += cells[pos]["audit"]["agreed"]
        run.inference = {"cells_inferred": len(inferred) - len(sample), "audited": len(sample), "agreed": agreed_n,
                         "cells": [cells[p]["labels"] for p in sample]}
        if agreed_n < len(sample):   # the inference failed somewhere: nothing is inferred
            rest = left_out()
            analyse(rest)
            run.inference["cells_inferred"] = 0
            run.inference["fallback"] = (f"{len(sample) - agreed_n} of {len(sample)} audited cells disagreed with "
                                         f"their neighbours: the {len(rest)} other cells left out were analysed too")
    for pos in range(total):
        report(pos)
    shared = checker.shared
    run.shared_batches = dict(shared) if shared["variants"] else None
    run.cells = cells
    run.checker, run.records, run.store = checker, records, store
    return run


def check_off_grid(run: GridRun, jobs, records_dir=None) -> dict:
    """The cells of variants off the grid (``jobs``: (name, variant) pairs: tolerance neighbours), checked as the
    grid's cells are — together, stored and resumed likewise — but judged by their check's verdict alone (no
    perturbation draws); their analyses are added to the run's."""
    records = read_records([v for _, v in jobs], records_dir, run.records)
    tool = tool_digest() if run.store is not None else ""
    out, tasks = {}, []
    for name, variant in jobs:
        if variant.project is None:
            out[name] = invalid_cell(variant, run.variables)
            continue
        task, stored = task_of(name, variant, records, run.store, tool, draws=False)
        if stored is not None:
            out[name] = {**stored, **_place(variant, run.variables), "resumed": True}
        else:
            tasks.append(task)
    fresh = run.checker.run(tasks)
    for cell in fresh.values():
        run.analyses_run += cell.get("analyses") or 0
    out.update(fresh)
    return out


def _place(variant: Variant, variables) -> dict:
    """A stored cell's place in this grid (its index and labels are the current grid's)."""
    from .cells import base_cell
    return base_cell(variant, variables)


__all__ = ["GridRun", "run_grid", "read_records", "task_of", "check_off_grid", "recommended", "check_exit_code", "verdict_words",
           "PREFER"]
