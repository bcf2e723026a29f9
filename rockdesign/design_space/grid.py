"""The design grid's runner: the check of every variant, with the work the variants share done once (SPEC §15).

Shared work:

- the records of the excitation are read and scaled once per distinct excitation (every variant of a
  ``pga``/``factor``/``spectrum``/``sdmax``-scaled suite shares them; ``uplift`` scaling depends on the
  variant's uplift acceleration and is keyed on it; a cylinder's record pairs and their SD_max are
  shared by the variants of one ``[excitation]``) and handed to the check's ``records`` hook;
- the kernels compile (or load from the cache) once, in this one process;
- the analyses of all variants run together: each variant's check runs in a thread of its own and its
  batches (a chunk of a suite, a round of a margin scan) wait for the other running variants' to run as
  one call of the numerical driver (:mod:`rockdesign.execution.batch_pool`, the kind's ``grid_batches``) — as many times more jobs per call
  as there are variants running (:func:`at_once`), so the cores stay busy to the end of each call (on a
  dask cluster the variants run one after the other, each on the whole cluster);
- each variant runs the check's own stages through its kind's grid hooks (:mod:`rockdesign.kinds`:
  ``grid_records``, ``grid_check``, ``grid_cell``; planar: :func:`rockdesign.planar.checks.check.run_check`,
  cylinder: :func:`rockdesign.cylinder.check.run_cylinder_check`, both with ``verdict_only``):
  model selection, the design-level suite, the margin scans and the demand — so a cell's verdict is the
  check's verdict of that variant;
- a variant stops once its verdict is decided: when the design-level suite already fails the acceptance
  rule (or an analysis failed) the margin scans and the demand re-runs are skipped — the margins can
  only add failing criteria; the c_r sensitivity, ensembles, report histories, the engine-accuracy
  appendix and a cylinder's planar runs per component (which never change the verdict's word) are
  skipped everywhere.

Every finished variant is stored in ``<out>/variants/<digest>.json`` (:mod:`.store`: the digest of the
variant's project text, the content of its scaled records, the tool version and the kernel sources): a run
interrupted and started again skips them, each placed in the current grid (its index and labels are the
current grid's, never the stored file's); a stored file that cannot be used is analysed again with a warning.
"""
from __future__ import annotations

import math
import threading
from dataclasses import dataclass, field
from ..errors import ProjectError, RockdesignError
from ..kinds import kind_of
from .store import VariantStore, content_digest, tool_digest, variant_digest
from .variants import Variable, Variant, variant_toml


@dataclass
class GridRun:
    """The grid's outcome: ``cells`` (one dict per variant, design.json's ``cells``), the analyses run
    and the lower bound of those saved, how many variants came from a stored earlier run, and
    ``shared_batches`` — the variants checked together, the batches they asked for and the calls of the
    batch driver that ran them (None when no variants ran together)."""

    variables: list[Variable]
    cells: list[dict]
    analyses_run: int = 0
    analyses_saved: int = 0
    resumed: int = 0
    notes: list[str] = field(default_factory=list)
    shared_batches: dict | None = None
    warnings: list[str] = field(default_factory=list)
    """Stored variants that could not be used (analysed again), in the words told to ``warn``."""


NOT_NEEDED = (("no incremental analysis: --no-margins", "not needed: the design-level suite decides"),
              ("intensities below the design level not analysed (--no-margins)",
               "intensities below the design level not analysed (not needed: the design-level suite decides)"))
"""A decided variant's reason: the skipped incremental analysis was not needed (it is not ``--no-margins``)."""


def _cell(kind, variant: Variant, variables, result, analyses: int) -> dict:
    """design.json's cell of a checked variant: the variant's values and the kind's numbers."""
    cell = {**_base_cell(variant, variables), **kind.grid_cell(result, analyses)}
    if cell["decided_at_design_level"]:
        for old, new in NOT_NEEDED:
            cell["reason"] = cell["reason"].replace(old, new)
    return cell


def _base_cell(variant: Variant, variables) -> dict:
    return {"index": list(variant.index),
            "values": {v.key: v.si[k] for v, k in zip(variables, variant.index)},
            "labels": {v.key: v.label(k) for v, k in zip(variables, variant.index)},
            "notes": list(variant.notes)}


EMPTY = dict.fromkeys(("governing", "acmr", "acmr_required", "p_collapse_design", "target_p_collapse", "n_unacceptable",
                       "allowed_unacceptable", "n_ground_motions", "superstructure_shear_p84",
                       "superstructure_drift_p84", "median_theta_max_over_theta_c", "uplift_acceleration",
                       "uplift_shear_coefficient", "theta_c", "column_material", "model"))
"""The check's numbers of a cell that has none (INVALID, ERROR)."""


def at_once() -> int:
    """Variants checked at the same time (a thread each; the next starts when one ends): 4 per core, at
    least 8, at most 64 — enough jobs per shared call to keep the cores busy, few enough that variants
    finish (and are stored for a resumed run) one after another."""
    from ..execution.executor import usable_cores
    return min(64, max(8, 4 * usable_cores()))


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


def run_grid(variant_list: list[Variant], variables, *, records_dir=None, executor=None, store=None,
             progress=None, stage_progress=None, warn=None, records: dict | None = None) -> GridRun:
    """Check every variant (see module docstring); ``progress(done, total, cell)`` as each variant ends,
    ``stage_progress(stage, done, total)`` inside one (the check's stages; not while variants run together);
    ``store``: the folder (or :class:`~.store.VariantStore`) of the per-variant results that makes the run
    resumable (None: nothing stored); ``warn(text)``: a stored variant that cannot be used (it is analysed
    again); ``records``: :func:`read_records` of these variants when already read.

    Variants whose analyses can share batches (:meth:`~rockdesign.kinds.base.StructureKind.grid_batches`)
    are checked together, each in a thread of its own with a pool member as its check's executor, their
    batches merged into shared calls of the kind's driver (:mod:`rockdesign.execution.batch_pool`); on a dask
    cluster (``executor``) one after the other."""
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
    tasks = []                  # (position, variant, kind, records, digest) of the variants to check
    for pos, variant in enumerate(variant_list):
        if variant.project is None:
            cells[pos] = {**_base_cell(variant, variables), **EMPTY, "verdict": "INVALID", "reason": variant.invalid,
                          "decided_at_design_level": False, "n_failed_analyses": 0, "analyses": 0,
                          "analyses_saved": 0}
            continue
        kind = kind_of(variant.project)
        recs, recs_digest = records[records_key(variant)]
        digest = None
        if store is not None:
            digest = variant_digest(kind.name, variant_toml(variant.raw), recs_digest, tool)
            stored = store.load(digest)
            if stored is not None:      # its place is this grid's, not the stored file's
                cells[pos] = {**_base_cell(variant, variables), **stored, "resumed": True}
                run.resumed += 1
                continue
        tasks.append((pos, variant, kind, recs, (store, digest)))

    done = [0]

    def report(pos: int) -> None:
        done[0] += 1
        cell = cells[pos]
        if not cell.get("resumed"):
            run.analyses_run += cell.get("analyses") or 0
            run.analyses_saved += cell.get("analyses_saved") or 0
        if progress is not None:
            progress(done[0], total, cell)

    for pos in range(total):        # invalid and stored variants first
        if cells[pos] is not None:
            report(pos)

    def check(task, stages, runs_on=executor) -> None:
        pos, variant, kind, recs, path = task
        cells[pos] = _check_variant(variant, variables, kind, recs, path, records_dir=records_dir,
                                    executor=runs_on, progress=stages)

    batches = tasks[0][2].grid_batches() if tasks and executor is None else None
    together = [t for t in tasks if t[2] is tasks[0][2]] if batches is not None else []
    if len(together) > 1:
        pool = _check_together(together, lambda task, member: check(task, None, member), report, at_once(),
                               batches)
        run.shared_batches = {"variants": len(together), "batches": pool.requests,
                              "driver_calls": getattr(batches, "calls", pool.rounds),
                              "analyses": getattr(batches, "jobs", None)}
    for task in tasks:
        if cells[task[0]] is None:
            check(task, stage_progress)
            report(task[0])
    run.cells = cells
    return run


def _check_variant(variant, variables, kind, records, path, *, records_dir, executor, progress) -> dict:
    """The cell of one variant's check (stored for a resumed run: ``path`` is (store, digest))."""
    from ..execution.batch_pool import PoolMember
    from ..execution.counting import AnalysisCount
    before = AnalysisCount.total

    def analyses() -> int:     # variants checked together count on their pool member
        return executor.analyses if isinstance(executor, PoolMember) else AnalysisCount.total - before
    try:
        result = kind.grid_check(variant.project, records=records, records_dir=records_dir, executor=executor,
                                 progress=progress)
    except RockdesignError as exc:  # the variant's own model or geometry is impossible
        cell = {**_base_cell(variant, variables), **EMPTY, "reason": str(exc),
                "verdict": "INVALID" if isinstance(exc, ProjectError) else "ERROR",
                "decided_at_design_level": False, "n_failed_analyses": 0,
                "analyses": analyses(), "analyses_saved": 0}
    else:
        cell = _cell(kind, variant, variables, result, analyses())
    store, digest = path
    if store is not None:
        store.save(digest, cell)
    cell["resumed"] = False
    return cell


def _check_together(tasks, check, report, threads: int, batches):
    """Check ``tasks`` in ``threads`` threads (the next task starting as one ends), ``check(task, member)`` with
    a pool member as the check's executor, their analyses in shared batches (``batches(requests)``, the kind's)
    served by this thread; ``report(position)`` here as each one ends.  An error or Ctrl-C cancels the others
    and is raised.  Returns the :class:`~rockdesign.execution.batch_pool.BatchPool` (its counts)."""
    from concurrent.futures import ThreadPoolExecutor

    from ..execution.batch_pool import BatchPool, PoolCancelled
    pool = BatchPool(len(tasks), batches)
    errors: list[BaseException] = []
    finished: list[int] = []
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
            finished.append(task[0])

    def on_wake() -> None:
        with lock:
            ended, finished[:] = list(finished), []
        for pos in ended:
            report(pos)

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


def recommended(cells: list[dict], material: tuple[str, str] = ("column material", "no elastic superstructure demand")
                ) -> dict | None:
    """The recommended design (SPEC §15): among passing cells the lowest 84th-percentile superstructure
    shear coefficient (equal to 3 significant digits: the least column material n·m_C), with its margin;
    None when no cell passes.  Without an elastic superstructure the least material decides (``material``:
    what is least and why, the kind's :attr:`~rockdesign.kinds.base.StructureKind.design_material`)."""
    passing = [c for c in cells if c["verdict"] == "PASS"]
    if not passing:
        return None

    def rank(c):
        shear = c.get("superstructure_shear_p84")
        return (float(f"{shear:.3g}") if shear is not None else math.inf, c.get("column_material") or math.inf)

    best = min(passing, key=rank)
    margin = []
    if best.get("acmr") is not None and best.get("acmr_required"):
        margin.append(f"ACMR {best['acmr']:.3g} ≥ {best['acmr_required']:.3g} required "
                      f"(×{best['acmr'] / best['acmr_required']:.3g})")
    if best.get("n_unacceptable") is not None and best.get("acceptance") != "binomial":
        margin.append(f"{best['n_unacceptable']} of {best['n_ground_motions']} ground motions unacceptable "
                      f"({best['allowed_unacceptable']} allowed)")
    if best.get("acceptance") == "binomial" and best.get("p_overturn_bound") is not None:
        margin.append(f"P(overturn) ≤ {best['p_overturn_bound']:.3g} at 95 % confidence "
                      f"(limit {best['binomial_limit']:.3g})")
    shear = best.get("superstructure_shear_p84")
    mass = best.get("column_material")
    what = material[0] + (f" {mass / 1000:.3g} t" if mass is not None and math.isfinite(mass) else "")
    why = ("the passing variant with the lowest superstructure shear coefficient (84th percentile "
           f"{shear:.3g})" if shear is not None else
           f"the passing variant with the least {what} ({material[1]})")
    return {"values": best["values"], "labels": best["labels"], "index": best["index"],
            "reason": f"{why}; margin: " + "; ".join(margin) if margin else why}


def check_exit_code(cells: list[dict]) -> int:
    """0 when at least one variant passes, 1 when none does (CONTRACT §6.3)."""
    return 0 if any(c["verdict"] == "PASS" for c in cells) else 1


__all__ = ["GridRun", "run_grid", "read_records", "recommended", "check_exit_code"]
