"""The design chart of a project (``rd.design``; ``rockdesign design`` calls it): plan → grid → files (SPEC §15,
CONTRACT §6.3, docs/design.md).

    import rockdesign as rd
    project = rd.load_project("podium.toml")
    chart = rd.design(project, ["podium.width=0.36m:0.52m:3"], out_dir="podium_design",
                      progress=lambda done, total, cell: print(done, total, cell["verdict"]))
    chart.verdicts, chart.recommended, chart.as_json()      # design.json

The steps, for a caller that does something between them (the command line compiles the kernels, with an
announcement, after every input is validated and before any analysis):

- :func:`plan_design` validates everything and analyses nothing: the variables (units, keys the project
  file takes, two keys that say the same thing), each variant's project, the records of every excitation,
  the options the project's kind has no use for; a grid without one valid variant is an input error;
- :func:`run_design` checks every variant (:func:`~rockdesign.design_space.grid.run_grid`);
- :func:`write_design` writes design.json, design.csv and the report into a folder, all or nothing.

The project is parsed once (the :class:`~rockdesign.project_tables.Project` carries its TOML document).
Errors are :class:`~rockdesign.errors.RockdesignError` whose ``key`` names the parameter (``vary``,
``out_dir``, ``records_dir``, ``executor``); the command line names its options instead.  Nothing here
draws on the terminal: progress goes to the callbacks the caller passes.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import ProjectError, RockdesignError
from ..execution.executor import check_executor, running_on
from ..kinds import kind_of
from ..kinds.base import CheckResult
from ..outdir import DesignFolder
from ..paths import require_path
from ..project_tables import Project
from .grid import PREFER, GridRun, check_exit_code, check_off_grid, read_records, recommended, run_grid
from .recommend import with_tolerance
from .tolerance import Tolerance, tolerances
from .variants import Variable, Variant, parse_vary, refuse_overlaps, variants


@dataclass
class DesignPlan:
    """A validated design grid, nothing analysed: the base project, its variables and variants (each a
    validated project or an INVALID cell's reason), and the records of every excitation, read once."""

    project: Project
    variables: list[Variable]
    variants: list[Variant]
    records: dict
    records_dir: str | None = None
    executor: object | None = None
    every_cell: bool = False
    prefer: str | None = None
    tolerances: dict[str, Tolerance] = field(default_factory=dict)
    """The construction tolerance of each varied key (:mod:`.tolerance`)."""
    notes: list[str] = field(default_factory=list)
    """What of the input this chart does not use ([design.tolerance] entries of keys it does not vary)."""

    @property
    def kind(self):
        return kind_of(self.project)


@dataclass
class DesignResult:
    """A design chart: the base project, the grid's cells, the recommendation and (when a report was asked
    for) the full check of the recommended variant; ``as_json()`` is design.json."""

    project: Project
    grid: GridRun
    recommended: dict | None
    settings: dict
    recommended_check: object | None = None
    """The full check (every stage) of the recommended variant, or None (no variant passes, or no report)."""
    warnings: list[str] = field(default_factory=list)
    out_dir: Path | None = None
    plan: DesignPlan | None = None

    def as_json(self) -> dict:
        from ..report.design_results import design_json, presentation
        data = design_json(self.project, self.grid, self.recommended, settings=self.settings,
                           presentation=presentation(kind_of(self.project)))
        full = self.recommended_check
        if full is not None and data["recommended"] is not None:
            data["recommended"]["check"] = {"verdict": full.verdict, "reason": full.verdict_reason,
                                            "robust": getattr(full, "verdict_robust", None)}
        data["warnings"] = list(self.warnings)
        return data

    @property
    def verdicts(self) -> list[str]:
        """The cells' verdicts, row-major over the variables."""
        return [c["verdict"] for c in self.grid.cells]

    @property
    def exit_code(self) -> int:
        """0 when at least one variant passes, 1 when none does (CONTRACT §6.3)."""
        return check_exit_code(self.grid.cells)


def _project(project) -> Project:
    if isinstance(project, Project):
        return project
    if isinstance(project, (str, os.PathLike)):
        from ..library import load_project
        return load_project(project)
    raise ProjectError("design needs a project", key="project",
                       expected="a Project (rd.load_project or rd.parse_project) or a project file",
                       found=type(project).__name__)


def _vary_list(vary) -> list[str]:
    specs = [vary] if isinstance(vary, str) else list(vary) if isinstance(vary, (list, tuple)) else None
    if specs is None or not all(isinstance(v, str) for v in specs):
        raise RockdesignError("variables must be strings", key="vary",
                              expected="one or two 'TABLE.KEY=FROM:TO:N' strings", found=repr(vary))
    if not 1 <= len(specs) <= 2:
        raise RockdesignError("one or two variables", key="vary", expected="one or two TABLE.KEY=FROM:TO:N",
                              found=f"{len(specs)} given")
    return specs


def plan_design(project, vary, *, records_dir=None, executor=None, every_cell: bool = False,
                prefer: str | None = None, tolerance: dict | None = None) -> DesignPlan:
    """Validate a design grid without analysing anything (see module docstring).

    Args:
        project: a :class:`~rockdesign.project_tables.Project` (or a project file's path, loaded once).
        vary: one or two ``"TABLE.KEY=FROM:TO:N"`` (FROM and TO in the key's units).
        records_dir: folder of PEER AT2 files for suites that name them (planar structures).
        executor: an executor (:mod:`rockdesign.execution.executor`, e.g. a dask cluster; planar structures).
        every_cell: analyse every cell (default: coarse to fine, cells between agreeing neighbours left out).
        prefer: what the recommendation minimises among robust passing variants, ``"material"`` or
            ``"shear"`` (default: the superstructure's shear where there is one, else the material).
        tolerance: ``{KEY: VALUE}``, the construction tolerance of varied keys ("1%", "2 mm"), over the project
            file's ``[design.tolerance]`` and the defaults (:mod:`rockdesign.design_space.tolerance`).

    Raises:
        RockdesignError: naming the parameter (``vary``, ``records_dir``, ``executor``, ``prefer``,
            ``tolerance``) or the project file's key.
    """
    project = _project(project)
    if prefer is not None and prefer not in PREFER:
        raise RockdesignError("unknown preference", key="prefer", expected=" or ".join(PREFER), found=repr(prefer))
    specs = _vary_list(vary)
    kind = kind_of(project)
    if records_dir is not None:
        require_path(records_dir, "records_dir", "a folder of record files")
    kind.check_options(project, records_dir=records_dir, executor=executor)   # a kind's refusal first
    check_executor(executor, text=False)        # rd.design starts an address; a plan holds an executor
    raw = project.raw
    derived = frozenset(kind.quantities(project))     # design quantities: not keys of the project file
    variables = [parse_vary(v, raw, alternatives=kind.key_alternatives, derived=derived) for v in specs]
    refuse_overlaps(variables)
    if tolerance is not None and not isinstance(tolerance, (dict, list, tuple)):
        raise RockdesignError("tolerances must be a mapping", key="tolerance",
                              expected="{KEY: VALUE} or [\"KEY=VALUE\", …], e.g. {\"podium.width\": \"1%\"}",
                              found=repr(tolerance))
    tols, notes = tolerances(variables, tolerance, raw, file=str(project.path))
    if project.excitation_raw is None:
        raise ProjectError("the design chart needs an excitation", file=project.path, key="excitation",
                           expected="an [excitation] table (the default intensity would move with the varied keys)",
                           found="no [excitation] table")
    cells = variants(raw, variables, file=str(project.path))
    records = read_records(cells, str(records_dir) if records_dir else None)
    return DesignPlan(project, variables, cells, records, str(records_dir) if records_dir else None, executor,
                      bool(every_cell), prefer, tols, notes)


def prepare_design(plan: DesignPlan, say=None) -> float:
    """Compile the kernels of the project's check on a first run (announced with ``say``), before any
    analysis; seconds spent (0 when every kernel is cached)."""
    from ..execution import compilation
    return compilation.prepare("design", plan.kind.kernels("check"), say)


def run_design(plan: DesignPlan, *, store=None, progress=None, stage_progress=None, warn=None,
               say=None) -> DesignResult:
    """Check every variant of a :func:`plan_design`, then the tolerance neighbourhood of the recommendation.

    Args:
        store: the folder of stored variants (resumable; None: nothing stored).
        progress: ``progress(done, total, cell)`` as each variant ends.
        stage_progress: ``stage_progress(stage, done, total)`` inside a variant checked alone.
        warn: ``warn(text)`` for a stored variant that cannot be used (analysed again).
        say: ``say(text)`` as the checks of a candidate's tolerance neighbourhood start.
    """
    kind = plan.kind
    grid = run_grid(plan.variants, plan.variables, records_dir=plan.records_dir, executor=plan.executor,
                    store=store, progress=progress, stage_progress=stage_progress, warn=warn, records=plan.records,
                    every_cell=plan.every_cell, seed=getattr(plan.project.analysis, "seed", 0))
    before = grid.analyses_run
    rec = with_tolerance(recommended(grid.cells, kind.design_material, plan.prefer, demand=kind.design_demand),
                         grid.cells, lambda jobs: check_off_grid(grid, jobs, plan.records_dir), plan.variables,
                         plan.tolerances, plan.project.raw, str(plan.project.path), material=kind.design_material,
                         prefer=plan.prefer, say=say, demand=kind.design_demand)
    if grid.checker is not None and grid.checker.shared["variants"]:
        grid.shared_batches = dict(grid.checker.shared)      # the cells' and the neighbours' shared calls
    analysed = sum(1 for c in grid.cells if c.get("analysed", True))
    inference = grid.inference or {}
    settings = {"early_stopping": kind.design_skipped, "verdict_rule": kind.design_rule,
                "executor": "dask" if plan.executor is not None else "local",
                "shared_batches": grid.shared_batches,
                "order": "every cell" if plan.every_cell else "coarse to fine",
                "cells_analysed": analysed, "cells_not_analysed": len(grid.cells) - analysed,
                "cells_inferred": len(grid.cells) - analysed,
                "inference_audit": {"n": inference.get("audited", 0), "agreed": inference.get("agreed", 0),
                                    "cells": inference.get("cells", []),
                                    **({"fallback": inference["fallback"]} if "fallback" in inference else {})},
                "inference_rule": INFERENCE,
                "flip_margin": FLIP,
                "tolerances": {k: t.as_json() for k, t in plan.tolerances.items()},
                "tolerance_analyses": grid.analyses_run - before,
                "robustness": ROBUSTNESS.format(draws=kind.design_draws), "prefer": plan.prefer}
    return DesignResult(plan.project, grid, rec, settings, warnings=list(grid.warnings) + list(plan.notes), plan=plan)


ROBUSTNESS = ("a variant that passes at nominal values is run again under its check's perturbation draws ({draws}), "
              "stopping at the first draw in which the "
              "design-level acceptance rule fails: robust when every draw passes; an ACMR above its requirement by "
              "less than the scans' resolution (margin_precision + 0.1 %) is not robust")
"""How a cell's robustness is decided (design.json ``settings.robustness``)."""


INFERENCE = ("a cell is left unanalysed only between analysed cells (the corners of the coarser box around it) that "
             "agree — all robust PASS or all FAIL — and are far from their flip (flip margin ≥ 1.25, or ≤ 0.8 for a "
             "FAIL); a cell left out that touches a cell of another verdict is analysed; then a seeded tenth of the "
             "cells left out is analysed as an audit, and if one disagrees every cell left out is analysed")
"""How a chart infers cells (design.json ``settings.inference_rule``)."""

FLIP = ("flip_margin: the factor λ on the design intensity at which the verdict changes — the smaller of the "
        "factor at which the count of ground motions unacceptable at or below λ × the design intensity exceeds the "
        "allowance (from each ground motion's first overturning factor) and ACMR / ACMR required; > 1 passes, ≤ 1 "
        "fails")
"""What a cell's flip margin is (design.json ``settings.flip_margin``)."""


FULL_CHECK = ("full check of the recommended design: the stages the grid skipped (sensitivity, perturbation "
              "ensembles, report figures) run as in rockdesign check")
"""What the full check of the recommended design does, and why it takes as long as a check."""


SLOW_ANALYSIS = ("one analysis can take minutes when a record brings the structure close to its uplift level, where "
                 "the engine resolves every impact (a 3D cylinder some 10^5 quasi-impacts of one record pair), and a "
                 "stage ends with its slowest analysis; nothing has stopped (Ctrl-C stops the run, the finished "
                 "variants stay stored)")
"""Why a stage of a design run can be silent for minutes (the command line says it after a while)."""


def recommended_check(result: DesignResult, *, progress=None) -> CheckResult | None:
    """The full check (every stage, as ``rockdesign check``) of the recommended variant: its summary goes into
    the design report, and its verdict must be PASS like its cell's.  None when no variant passes."""
    if result.recommended is None:
        return None
    plan = result.plan
    index = tuple(result.recommended["index"])
    variant = next(v for v in plan.variants if tuple(v.index) == index)
    return kind_of(variant.project).check(variant.project, progress=progress, records_dir=plan.records_dir,
                                          margins=True, executor=None)


def design_folder(out_dir, *, key: str = "out_dir") -> DesignFolder:
    """The output folder of a design chart, validated (a file, a read-only folder or one holding files
    rockdesign did not write is refused before any analysis)."""
    if not isinstance(out_dir, DesignFolder):
        require_path(out_dir, key, "a folder name")
    folder = DesignFolder(out_dir, key=key)
    folder.validate()
    return folder


def write_design(result: DesignResult, folder, *, pdf: bool = True, html: bool = True, say=None) -> Path:
    """Write design.json, design.csv and (``html``/``pdf``) design.html, design.pdf and the figures into
    ``folder`` (a path or a :class:`~rockdesign.outdir.DesignFolder`), all or nothing: files of an earlier
    run that this one does not write (a design.pdf beside a new --no-pdf design.json) are gone afterwards;
    the stored variants stay.  ``say(text)``: what is being written.  Returns the folder."""
    from ..report.design_results import write_design_csv, write_design_json
    folder = folder if isinstance(folder, DesignFolder) else design_folder(folder)
    data = result.as_json()
    with folder.staging() as tmp:
        write_design_json(data, tmp / "design.json")
        write_design_csv(data, tmp / "design.csv")
        if pdf or html:
            from ..report.design_report import write_design_report
            if say is not None:
                say("writing the design report (charts" + (", PDF" if pdf else "") + ")")
            write_design_report(result, data, tmp, pdf=pdf, recommended_check=result.recommended_check)
    result.out_dir = folder.target
    return folder.target


def design(project, vary, *, out_dir=None, records_dir=None, executor=None, pdf: bool = True, html: bool = True,
           full_check: bool | None = None, progress=None, stage_progress=None, warn=None, say=None,
           every_cell: bool = False, prefer: str | None = None, tolerance: dict | None = None) -> DesignResult:
    """The design chart of a project: the check of every variant of one or two keys (SPEC §15, docs/design.md).

    Args:
        project: a :class:`~rockdesign.project_tables.Project` (or a project file's path).
        vary: one or two ``"TABLE.KEY=FROM:TO:N"``, FROM and TO in the key's units
            (``"podium.width=0.36m:0.60m:7"``, ``"podium.columns=6:10:3"``, ``"superstructure.damping=1%:5%:3"``).
        out_dir: the folder of design.json, design.csv, the report and the stored variants (resumable: an
            interrupted run started again re-runs only the variants not yet stored); None: no files, nothing stored.
        records_dir: folder of PEER AT2 files for suites that name them (planar structures).
        executor: a started executor (:mod:`rockdesign.execution.executor`, e.g. a dask cluster; planar), or a
            dask value (``"local:4"``, ``"tcp://host:8786"``), started here and closed when the chart is done.
        pdf, html: write design.pdf / design.html (with ``out_dir``).
        full_check: run the full check of the recommended variant (default: when a report is written).
        progress: ``progress(done, total, cell)`` as each variant ends.
        stage_progress: ``stage_progress(stage, done, total)`` inside a variant checked alone.
        warn: ``warn(text)``: a stored variant that cannot be used (it is analysed again).
        say: ``say(text)``: a long step starting (the full check, the report).
        every_cell: analyse every cell (default: coarse to fine; a cell between agreeing neighbours is left
            unanalysed, ``"analysed": false``, and shows no verdict).
        prefer: ``"material"`` or ``"shear"``: what the recommendation minimises among robust passing variants.
        tolerance: ``{KEY: VALUE}``: the construction tolerance of varied keys ("1%", "2 mm"; default ±1 % of a
            length, ±2 % of another key; the project file's ``[design.tolerance]`` in between).

    Returns:
        A :class:`DesignResult` (``verdicts``, ``recommended``, ``exit_code``, ``as_json()`` = design.json).

    Raises:
        RockdesignError: an input error, before any analysis; its ``key`` names the parameter.
    """
    project = _project(project)
    folder = design_folder(out_dir) if out_dir is not None else None
    kind_of(project).check_options(project, records_dir=records_dir, executor=executor)   # a kind's refusal first
    check_executor(executor)                    # a dask value is checked (and its scheduler reached) here
    if isinstance(executor, str):               # started here and closed when the chart is done
        with running_on(executor) as owned:
            return design(project, vary, out_dir=out_dir, records_dir=records_dir, executor=owned, pdf=pdf,
                          html=html, full_check=full_check, progress=progress, stage_progress=stage_progress,
                          warn=warn, say=say, every_cell=every_cell, prefer=prefer, tolerance=tolerance)
    plan = plan_design(project, vary, records_dir=records_dir, executor=executor, every_cell=every_cell,
                       prefer=prefer, tolerance=tolerance)
    if full_check is None:
        full_check = out_dir is not None and (pdf or html)
    if folder is None:
        result = run_design(plan, progress=progress, stage_progress=stage_progress, warn=warn, say=say)
        if full_check:
            if say is not None and result.recommended is not None:
                say(FULL_CHECK)
            result.recommended_check = recommended_check(result, progress=stage_progress)
        return result
    with folder.locked():
        result = run_design(plan, store=folder.store, progress=progress, stage_progress=stage_progress, warn=warn,
                            say=say)
        if full_check:
            if say is not None and result.recommended is not None:
                say(FULL_CHECK)
            result.recommended_check = recommended_check(result, progress=stage_progress)
        write_design(result, folder, pdf=pdf, html=html, say=say)
    return result


__all__ = ["design", "plan_design", "prepare_design", "run_design", "write_design", "design_folder", "recommended_check",
           "DesignPlan", "DesignResult", "FULL_CHECK", "SLOW_ANALYSIS"]
