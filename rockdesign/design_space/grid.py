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
- coarse to fine (:mod:`.refine`): a coarse sub-grid first, then the cells where neighbours disagree; a cell
  between agreeing neighbours is left unanalysed (``"analysed": false``, no verdict word) unless
  ``every_cell``.

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
from ..display import verdict_words
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


def not_passing() -> dict:
    """The robustness keys of a cell that does not pass (CONTRACT §7.4: ``robust`` is null unless PASS)."""
    return {"analysed": True, "robust": None, "draws": {"n": 0, "failed": 0}, "robustness": None}


def margin_undecided(cell: dict, precision: float) -> str | None:
    """Why a passing cell's collapse margin cannot be told from its requirement, or None.  The ACMR comes from
    scans that bisect each record's first overturning intensity to ``precision`` (``[analysis]
    margin_precision``); an ACMR above its requirement by less than that resolution (plus the draws'
    ± 0.1 % amplitude) is not a robust PASS — the rule the grid states instead of scanning every draw.  An ACMR
    below its requirement in a passing cell is informative (the acceptance rule is another one) and is left
    alone."""
    acmr, need = cell.get("acmr"), cell.get("acmr_required")
    if acmr is None or not need:
        return None
    from ..acceptance.perturbations import AMPLITUDE_VARIATION
    if need <= acmr < need * (1.0 + precision + AMPLITUDE_VARIATION):   # (below its requirement the margin did not
        # decide the PASS: it informs under another acceptance rule, e.g. the binomial bound)
        return (f"ACMR {acmr:.4g} within the scans' resolution ({100 * precision:g} % + {100 * AMPLITUDE_VARIATION:g} %"
                f") of the {need:.4g} required")
    return None


def robustness(draws: dict | None, near: str | None = None) -> dict:
    """The robustness keys of a passing cell from its perturbation draws (``grid_draws``), or from a margin
    too close to its requirement (``near``; no draws run)."""
    if near is not None:
        return {"robust": False, "draws": {"n": 0, "failed": 0}, "robustness": f"not robust: {near}"}
    n, failed, size = draws["n"], draws["failed"], draws.get("size", draws["n"])
    if size == 0:
        return {"robust": False, "draws": {"n": 0, "failed": 0},
                "robustness": "not robust: no perturbation draws ([analysis] ensemble_size = 0 and no c_r draws)"}
    if failed:
        return {"robust": False, "draws": {"n": n, "failed": failed},
                "robustness": f"not robust: fails in {failed} of {n} draws (stopped at the first that fails, "
                              f"{size} planned; {draws['first_failure']})"}
    return {"robust": True, "draws": {"n": n, "failed": 0},
            "robustness": f"robust: passes in all {n} perturbation draws ("
                          f"{draws.get('what') or 'as the check draws them'})"}


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
             progress=None, stage_progress=None, warn=None, records: dict | None = None,
             every_cell: bool = False) -> GridRun:
    """Check every variant (see module docstring); ``progress(done, total, cell)`` as each variant ends (or
    is left unanalysed), ``stage_progress(stage, done, total)`` inside one (the check's stages; not while
    variants run together); ``store``: the folder (or :class:`~.store.VariantStore`) of the per-variant results
    that makes the run resumable (None: nothing stored); ``warn(text)``: a stored variant that cannot be used
    (it is analysed again); ``records``: :func:`read_records` of these variants when already read;
    ``every_cell``: analyse every cell (default: coarse to fine, :mod:`.refine` — cells between agreeing
    corners are left unanalysed, ``"analysed": false``).

    Variants whose analyses can share batches (:meth:`~rockdesign.kinds.base.StructureKind.grid_batches`)
    are checked together, each in a thread of its own with a pool member as its check's executor, their
    batches merged into shared calls of the kind's driver (:mod:`rockdesign.execution.batch_pool`) — on a dask
    cluster (``executor``) too, each shared call submitted to the cluster at once."""
    from .refine import agreed, levels
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
    tasks = {}                  # position → (position, variant, kind, records, (store, digest)) of variants to check
    for pos, variant in enumerate(variant_list):
        if variant.project is None:
            cells[pos] = {**_base_cell(variant, variables), **EMPTY, "verdict": "INVALID", "reason": variant.invalid,
                          "decided_at_design_level": False, "n_failed_analyses": 0, "analyses": 0,
                          "analyses_saved": 0, **not_passing()}
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
        tasks[pos] = (pos, variant, kind, recs, (store, digest))

    done = [0]

    def report(pos: int) -> None:
        done[0] += 1
        cell = cells[pos]
        if not cell.get("resumed"):
            run.analyses_run += cell.get("analyses") or 0
            run.analyses_saved += cell.get("analyses_saved") or 0
        if progress is not None:
            progress(done[0], total, cell)

    def check(task, stages, runs_on=executor) -> None:
        pos, variant, kind, recs, path = task
        cells[pos] = _check_variant(variant, variables, kind, recs, path, records_dir=records_dir,
                                    executor=runs_on, progress=stages)

    shape = tuple(len(v.values) for v in variables)
    position = {tuple(v.index): k for k, v in enumerate(variant_list)}
    full = bool(shape) and len(position) == total == math.prod(shape)
    order = ([[position[i] for i in lvl] for lvl in levels(shape, every_cell)] if full
             else [list(range(total))])       # a list of variants that is not a whole grid: every one
    known: dict = {}
    reported: set = set()
    shared = {"variants": 0, "batches": 0, "driver_calls": 0, "analyses": 0}
    batches = None
    for level, positions in enumerate(order):
        todo = []
        for pos in positions:
            index = tuple(variant_list[pos].index)
            between = agreed(index, shape, level, known) if cells[pos] is None and full else None
            if between is not None:
                cells[pos] = {**_base_cell(variant_list[pos], variables), **EMPTY, "verdict": None,
                              "reason": f"not analysed: the analysed variants around it are all {between}",
                              "decided_at_design_level": False, "n_failed_analyses": 0, "analyses": 0,
                              "analyses_saved": 0, "analysed": False, "between": between, "robust": None,
                              "draws": {"n": 0, "failed": 0}, "robustness": None, "resumed": False}
            elif cells[pos] is None:
                todo.append(tasks[pos])
        for pos in positions:
            if cells[pos] is not None and pos not in reported:
                reported.add(pos)
                report(pos)
        if todo and batches is None:
            batches = todo[0][2].grid_batches(executor) if executor is not None else todo[0][2].grid_batches()
        together = [t for t in todo if t[2] is todo[0][2]] if batches is not None else []
        if len(together) > 1:
            pool = _check_together(together, lambda task, member: check(task, None, member), report, at_once(),
                                   batches)
            reported.update(t[0] for t in together)
            shared["variants"] += len(together)
            shared["batches"] += pool.requests
            shared["driver_calls"] = getattr(batches, "calls", shared["driver_calls"] + pool.rounds)
            shared["analyses"] = getattr(batches, "jobs", None)
        for task in todo:
            if cells[task[0]] is None:
                check(task, stage_progress)
                reported.add(task[0])
                report(task[0])
        for pos in positions:
            known[tuple(variant_list[pos].index)] = cells[pos]
    run.shared_batches = shared if shared["variants"] else None
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
                "analyses": analyses(), "analyses_saved": 0, **not_passing()}
    else:
        nominal = analyses()
        cell = _cell(kind, variant, variables, result, nominal)
        cell.update(not_passing())
        if cell["verdict"] == "PASS":
            precision = getattr(variant.project.analysis, "margin_precision", 0.0)
            near = margin_undecided(cell, precision)
            draws = None if near else kind.grid_draws(result, records=records, executor=executor)
            cell.update(robustness(draws, near))
            extra = analyses() - nominal
            cell["analyses"] = analyses()
            cell["analyses_saved"] = max(0, cell["analyses_saved"] - extra)
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


PREFER = ("material", "shear")
"""What the recommendation minimises among robust passing variants (``--prefer``)."""


def _rank(prefer: str | None):
    def shear(c):
        x = c.get("superstructure_shear_p84")
        return float(f"{x:.3g}") if x is not None else math.inf

    def mass(c):
        x = c.get("column_material")
        return x if x is not None else math.inf
    if prefer == "material":
        return lambda c: (mass(c), shear(c))
    return lambda c: (shear(c), mass(c))


def _labels(cell: dict) -> str:
    return ", ".join(f"{k} = {v}" for k, v in cell["labels"].items())


def _neighbours(best: dict, cells: list[dict], rank, what: str) -> str:
    """Why ``best`` was chosen over the cells next to it in the grid (one step along each axis)."""
    here = tuple(best["index"])
    parts = []
    for c in cells:
        idx = tuple(c["index"])
        if sum(abs(a - b) for a, b in zip(idx, here)) != 1:
            continue
        changed = [k for k in best["labels"] if c["labels"][k] != best["labels"][k]]
        name = ", ".join(f"{k} = {c['labels'][k]}" for k in changed)
        words = verdict_words(c)
        if c.get("analysed", True) and c.get("verdict") == "PASS" and c.get("robust"):
            words += f", more {what}" if rank(c) > rank(best) else f", {what} not lower"
        parts.append(f"{name}: {words}")
    return "; ".join(parts)


def recommended(cells: list[dict], material: tuple[str, str] = ("column material", "no elastic superstructure demand"),
                prefer: str | None = None) -> dict | None:
    """The recommended design (SPEC §15): a robust PASS whenever one exists — among the analysed passing cells
    that pass all their perturbation draws, the lowest 84th-percentile superstructure shear coefficient (equal
    to 3 significant digits: the least column material n·m_C), or with ``prefer = "material"`` (or without an
    elastic superstructure) the least material (``material``: what is least and why, the kind's
    :attr:`~rockdesign.kinds.base.StructureKind.design_material`); with its margin, its robustness and why it
    was chosen over its neighbours.  Where no cell passes robustly, the best fragile PASS with
    ``"robust": false`` and the fragile candidates named (``fragile_candidates``); None when no cell passes."""
    passing = [c for c in cells if c.get("analysed", True) and c["verdict"] == "PASS"]
    if not passing:
        return None
    robust = [c for c in passing if c.get("robust")]
    rank = _rank(prefer)
    best = min(robust or passing, key=rank)
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
    kind_of_pass = "robust passing" if robust else "passing"
    by_shear = prefer != "material" and shear is not None
    why = (f"the {kind_of_pass} variant with the lowest superstructure shear coefficient (84th percentile "
           f"{shear:.3g})" if by_shear else
           f"the {kind_of_pass} variant with the least {what}"
           + (f" ({material[1]})" if prefer != "material" else " (preferred: material)"))
    reason = f"{why}; margin: " + "; ".join(margin) if margin else why
    reason += "; " + (best.get("robustness") or "robustness not evaluated")
    near = _neighbours(best, cells, rank, "shear" if by_shear else "material")
    if near:
        reason += f"; chosen over its neighbours ({near})"
    out = {"values": best["values"], "labels": best["labels"], "index": best["index"], "reason": reason,
           "robust": bool(best.get("robust")), "prefer": "shear" if by_shear else "material"}
    if not robust:
        fragile = sorted(passing, key=rank)
        out["fragile_candidates"] = [{"labels": c["labels"], "index": c["index"],
                                      "robustness": c.get("robustness")} for c in fragile]
        out["no_robust_pass"] = ("no variant passes robustly: every passing variant fails in some perturbation "
                                 "draw or has its margin at its requirement; fragile candidates: "
                                 + "; ".join(_labels(c) for c in fragile[:5]) + (" …" if len(fragile) > 5 else ""))
    return out


def check_exit_code(cells: list[dict]) -> int:
    """0 when at least one variant passes, 1 when none does (CONTRACT §6.3)."""
    return 0 if any(c.get("analysed", True) and c["verdict"] == "PASS" for c in cells) else 1


__all__ = ["GridRun", "run_grid", "read_records", "recommended", "check_exit_code", "verdict_words", "PREFER"]
