"""The interface every kind of structure supplies (the registry is :mod:`rockdesign.kinds`).

A kind of structure (planar: column, frame, podium; the 3D cylinder) is one object; ``rd.load_project``,
``rd.design_quantities``, ``rd.simulate``, ``rd.check``, ``rd.write_report``, ``rd.spectrum`` and
``rd.design`` ask the registry for the kind once and call it — no other module branches on the kind of a
structure.  The pattern is a design-code base class (concreteproperties' ``DesignCode``): what every kind
shares has a default here; a kind writes the seven methods marked abstract and overrides a default only
where it differs.

A kind must write:

==========================  ===================================================================
``claims(raw)``             does this TOML document describe a structure of this kind?
``parse(raw, file, text)``  the typed :class:`~rockdesign.project_tables.Project` (SI)
``quantities(project)``     the closed-form design quantities, each a :class:`~rockdesign.quantity.Quantity`
``simulation_request``      validate one analysis (a motion string or object) without analysing
``run_simulation``          analyse a request: a result with ``as_json()``, ``write_csv``, ``write_figure``
``check(project, …)``       the design check: a result with ``verdict``, ``records``, ``as_json()``
``report(result)``          the calculation report's parts (:class:`~rockdesign.report.document.ReportParts`)
==========================  ===================================================================
"""
from __future__ import annotations

import abc
import importlib
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Protocol
from dataclasses import dataclass
from pathlib import Path

from ..errors import RockdesignError
from ..outdir import RUN_FILES, OutputFolder
from .options import CliOption

if TYPE_CHECKING:       # the report's modules load jinja2 and matplotlib: not needed to read a project
    from ..report.document import ReportParts


def _shown(value) -> str:
    """A value given to a library function, as an error message quotes it."""
    if isinstance(value, (str, Path)):
        return repr(str(value))
    if isinstance(value, (bool, int, float, list, tuple)):
        return repr(value)
    return getattr(value, "name", None) or type(value).__name__


@dataclass(frozen=True)
class SpectrumOptions:
    """What ``rd.spectrum`` was asked for, handed to the project's kind.

    Attributes:
        given: the options given by name (``pulse``, ``record``, ``x``, ``y``, ``relative`` — a loaded
            :class:`~rockdesign.project_tables.Project` —, ``out_dir``, ``executor``, …); options left at
            None are not in it, so a kind's defaults apply.
        progress: ``progress(stage, done, total)`` as analyses finish (:func:`rockdesign.progress.progress_bars`
            draws it), or None.
        say: ``say(text)`` prints a line (the first-run compilation is announced with it), or None.
    """

    given: Mapping[str, object]
    progress: Callable[[str, int, int], None] | None = None
    say: Callable[[str], object] | None = None

    def accepted(self, names, used_by: str, expected: str) -> dict:
        """The given options, or a :class:`~rockdesign.errors.RockdesignError` naming the first one that is not
        among ``names`` (the kind's options): it is "not used by ``used_by``"."""
        for name, value in self.given.items():
            if name not in names:
                raise RockdesignError(f"not used by {used_by}", key=name, expected=expected,
                                      found=f"{name}={_shown(value)}")
        return dict(self.given)


class SimulationRequest(Protocol):
    """A validated request of one analysis (``rd.simulation_request``; :meth:`StructureKind.simulation_request`):
    the project it analyses; the rest is the kind's (its parsed motion, model and end time)."""

    project: object


class SimulationResult(Protocol):
    """What every kind's one analysis returns (``rd.simulate``; :meth:`StructureKind.run_simulation`)."""

    warnings: list

    @property
    def failed(self) -> bool: ...

    def as_json(self) -> dict: ...

    def write_csv(self, path) -> None: ...

    def write_figure(self, path) -> None: ...

    def summary_rows(self) -> list: ...


class CheckResult(Protocol):
    """What every kind's design check returns (``rd.check``; :meth:`StructureKind.check`): the shared sections of
    results.json (docs/architecture.md "Every check result has the same core sections")."""

    project: object
    verdict: str
    verdict_reason: str
    records: list
    checks: list
    acceptance: dict | None

    def as_json(self) -> dict: ...


class SpectrumResult(Protocol):
    """What every kind's rocking spectrum returns (``rd.spectrum``; :meth:`StructureKind.spectrum`)."""

    out_dir: Path
    title: str

    def as_json(self) -> dict: ...

    def summary_rows(self) -> list: ...


class EnsembleResult(Protocol):
    """What a kind's ensemble run returns (``rd.ensemble``; the kind's ``experiments.run_ensemble``)."""

    def rows(self) -> list: ...

    def as_json(self) -> dict: ...

    def write_csv(self, path) -> None: ...


def unavailable(what: str, kind: str, key: str):
    """The error for a command or option a kind does not offer (exit 2 in the CLI)."""
    return RockdesignError(f"{what} is not available for this kind of structure", key=key,
                           expected=f"a kind of structure that offers {what}", found=kind)


class StructureKind(abc.ABC):
    """One kind of structure: its project parser, design quantities, time-history analysis, check and
    report.  Subclasses set :attr:`name` and :attr:`systems` and write the abstract methods."""

    name: str = ""
    """The kind's name ("planar", "cylinder")."""
    systems: tuple[str, ...] = ()
    """``project.system.kind`` values of this kind's systems ("column", "podium"; "cylinder")."""
    report_files: frozenset[str] = frozenset()
    """Files a check writes into its output folder besides the run files (``ReportParts.files``)."""
    csv_columns: tuple[str, ...] = ("id", "ground_motion")
    """The columns of results.csv, one row per record of results.json (by default the keys every check's records
    have); :func:`rockdesign.report.results.write_results_csv` writes them."""
    csv_units: Mapping[str, str] = {}
    """The SI unit of each column of results.csv that has one (its header reads "pga [m/s^2]")."""
    csv_nested: Mapping[str, tuple[str, str]] = {}
    """Columns of results.csv read from a dict in a record's row: column → (key of the dict, key in it)."""
    key_alternatives: Mapping[str, tuple[str, ...]] = {}
    """Keys of the kind's project tables that say the same thing two ways (CONTRACT §1): a ``--vary`` of one
    replaces the others (listed in design.json's ``notes``); none by default."""
    uses: tuple[str, ...] = ()
    """Modules of other kinds' packages this kind's package imports (a declared dependency between kinds, read by
    tests/architecture/test_front_door.py); none by default."""
    spectrum_options: tuple[str, ...] = ()
    """The options of ``rd.spectrum`` the kind's :meth:`spectrum` takes (``pulse``, ``record``, ``x``, ``out_dir``, …);
    it refuses any other, naming it (:meth:`SpectrumOptions.accepted`)."""
    spectrum_cli: tuple[CliOption, ...] = ()
    """The options of :attr:`spectrum_options` that ``rockdesign spectrum`` offers on the command line, each a
    :class:`~rockdesign.kinds.options.CliOption` (name, value type, help); ``relative``, ``out_dir``, ``executor`` and
    ``figures`` are the command's own.  The command merges the options of every registered kind (one option for a name
    several kinds declare, :func:`~rockdesign.kinds.options.merged_options`); none by default."""
    templates: tuple[str, ...] = ()
    """The commented project templates the kind offers, by name (``rockdesign init NAME``; :meth:`template_text`)."""
    design_material: tuple[str, str] = ("material", "no demand to rank by")
    """The recommended design without a superstructure force to rank by: (what is least, why)."""
    design_demand: str = "demand ("
    """What a cell's ``demand`` is, in the recommendation's words ("the variant with the lowest <design_demand> 0.45)");
    a kind whose cells have a demand (the force the building above is designed for) names it."""
    design_columns: tuple[tuple[str, str, str], ...] = ()
    """The kind's own numbers of a design cell (those :meth:`grid_cell` adds to the shared ones): (cell key, heading
    of the report's variants table, SI unit).  design.json lists them (``columns``), design.csv writes them after
    the shared columns ("theta_c [rad]"; unit "-": dimensionless, "": a count) and the report's table shows those
    with a heading ("": the files only)."""
    design_response: tuple[str, str] = ("response ratio", "the peak response over the capacity")
    """The cell's median response ratio (design.json ``median_theta_max_over_theta_c``, the median of the runs'
    :attr:`~rockdesign.acceptance.outcome.Run.response_ratio`) in the report's words: (its symbol "θ_max/θc", what it
    is, citing the thesis)."""
    design_draws: str = "the perturbation draws of the kind's check"
    """What the design grid's robustness draws of a passing variant vary (:meth:`grid_draws`), in the words of
    design.json ``settings.robustness``."""
    design_plane: Mapping[str, str] | None = None
    """Two of the kind's cell numbers the design report draws against each other, one mark per variant: ``x``,
    ``y`` (cell keys), ``x_label``, ``y_label``, ``caption``; None: no such figure."""
    experiments_module: str | None = None
    """The dotted name of the module of the kind's experiments (thesis Ch. 6–7: ``calibrate``, ``simulated_history``,
    ``run_ensemble``), imported when first used; None when the kind has none (``rd.calibration`` and ``rd.ensemble``
    refuse it)."""
    grid_module: str | None = None
    """The dotted name of the module of the kind's design-grid hooks (``records_key``, ``grid_records``,
    ``grid_check``, ``grid_cell``, ``grid_draws``, ``RULE`` and ``SKIPPED``: what decides a cell's verdict and what
    the grid skips, in the report's words), imported when first used; None when the kind has no design grid."""

    @property
    def experiments(self):
        """The module named by :attr:`experiments_module` (imported on first use: a typo in a project file is
        reported before the engine loads), or None."""
        return importlib.import_module(self.experiments_module) if self.experiments_module else None

    @property
    def grid(self):
        """The module named by :attr:`grid_module` (imported on first use), or None."""
        return importlib.import_module(self.grid_module) if self.grid_module else None

    @property
    def design_rule(self) -> str:
        """What decides the verdict of a design-grid cell (``rockdesign design``: the report's words)."""
        return getattr(self.grid, "RULE", "") if self.grid_module else ""

    @property
    def design_skipped(self) -> str:
        """What the design grid skips of a variant's check (design.json ``settings.early_stopping``)."""
        return getattr(self.grid, "SKIPPED", "") if self.grid_module else ""

    # --- the numerical kernels ---------------------------------------------------------------
    def kernels(self, command: str) -> tuple:
        """The groups of numba kernels (:class:`~rockdesign.execution.compilation.Kernels`, each with its warm-up)
        that ``command`` ("simulate", "check") runs: compiled, and announced, before its work on a first run.
        By default none (kernels then compile on first use)."""
        return ()

    # --- the project file -------------------------------------------------------------------
    @abc.abstractmethod
    def claims(self, raw: dict) -> bool:
        """True when the TOML document ``raw`` describes a structure of this kind."""

    @abc.abstractmethod
    def parse(self, raw: dict, *, file: str, text: str):
        """The validated :class:`~rockdesign.project_tables.Project` (SI; ``[excitation]`` and ``[analysis]``
        typed) or a :class:`~rockdesign.errors.ProjectError`."""

    def template_text(self, name: str) -> str:
        """The commented template project file ``name`` (one of :attr:`templates`); by default the package data
        ``templates/project_<name>.toml``."""
        from ..paths import templates_dir
        return (templates_dir() / f"project_{name}.toml").read_text(encoding="utf-8")

    # --- design quantities ------------------------------------------------------------------
    @abc.abstractmethod
    def quantities(self, project) -> dict:
        """Design quantities: name → :class:`~rockdesign.quantity.Quantity` (SI, thesis equation)."""

    def quantities_title(self, project) -> str:
        """The title of the console table of the quantities."""
        return f"{project.name} — design quantities ({project.system.kind})"

    def quantities_json(self, project) -> dict:
        """The ``quantities --json`` object of CONTRACT §3 (SI values)."""
        return {"quantities": {name: q.as_json() for name, q in self.quantities(project).items()},
                "warnings": list(project.warnings)}

    def write_curve(self, project, path: Path) -> None:
        """``quantities --pushover PATH``: the kind's capacity curve (.csv numbers, .png/.svg/.pdf figure)."""
        raise unavailable("a capacity curve", self.name, "path")

    # --- one time-history analysis ----------------------------------------------------------
    @abc.abstractmethod
    def simulation_request(self, project, motion, *, model: str, t_end, rtol, records_dir):
        """Parse a motion (a string, or the kind's motion object) and validate the whole request without
        analysing or compiling anything: a request object with ``project``."""

    @abc.abstractmethod
    def run_simulation(self, request):
        """Analyse a request: a result with ``response``, ``failed``, ``as_json()``, ``write_csv(path)``,
        ``write_figure(path)``, ``summary_rows()`` and ``warnings``."""

    # --- the design check -------------------------------------------------------------------
    def check_options(self, project, *, records_dir, executor) -> None:
        """Refuse options that do not apply to this kind (errors name the parameter); by default every
        option applies."""

    def prepare_check(self, project, *, records_dir) -> None:
        """Before the analyses: read what can be wrong in the input, so that a first run reports a typo
        before it compiles anything.  By default nothing beyond the project."""

    @abc.abstractmethod
    def check(self, project, *, progress, records_dir, margins: bool, executor):
        """The design check: a result with ``project``, ``verdict``, ``verdict_reason``, ``records``,
        ``checks`` and ``as_json()`` (= results.json)."""

    def output_folder(self, target, *, key: str) -> OutputFolder:
        """The check's output folder (it owns :data:`report_files` besides the run files)."""
        return OutputFolder(target, key=key, owned=RUN_FILES | set(self.report_files))

    # --- the report -------------------------------------------------------------------------
    @abc.abstractmethod
    def report(self, result) -> ReportParts:
        """The parts of the calculation report of a check result (its HTML and figures)."""

    # --- rocking spectra (``rd.spectrum``, ``rockdesign spectrum``) ---------------------------
    def spectrum(self, project, request: SpectrumOptions):
        """The kind's rocking spectrum, its files written into an output folder (planar: a pulse family, thesis
        Ch. 3; the cylinder: one record pair over R and PGA, Figs 5.16–5.17): a result with ``out_dir``,
        ``as_json()`` (= summary.json), ``title`` and ``summary_rows()``.  The kind takes the options of
        ``request`` it uses (:meth:`SpectrumOptions.accepted`) and refuses the others, naming them."""
        raise unavailable("a rocking spectrum", self.name, "project")

    # --- the design grid (rockdesign design, SPEC §15): the kind's ``grid`` module does the work --------
    def _grid(self):
        if self.grid is None:
            raise unavailable("a design grid", self.name, "project")
        return self.grid

    def grid_batches(self, executor=None):
        """``execute(requests) -> results`` when the design grid may check variants of this kind together, their
        batches merged into shared calls (:mod:`rockdesign.execution.batch_pool`; the grid passes each variant's
        check a pool member as its executor), or None (variants one after the other).  ``executor``: a started
        executor (e.g. a dask cluster) the shared calls run on, all variants' work submitted at once; a kind
        that cannot returns None for it."""
        return None

    def grid_records_key(self, project) -> str:
        """Which variants share the records read and scaled by :meth:`grid_records` (equal keys share)."""
        return self._grid().records_key(project)

    def grid_records(self, project, records_dir):
        """The records of the project's excitation, read and scaled once for every variant sharing them."""
        return self._grid().grid_records(project, records_dir)

    def grid_check(self, project, *, records, records_dir, executor, progress):
        """The check of one variant (its verdict is :meth:`check`'s), computing only what the verdict's word
        and the design table need (``verdict_only``) on the shared ``records``."""
        return self._grid().grid_check(project, records=records, records_dir=records_dir, executor=executor,
                                       progress=progress)

    def grid_cell(self, result, analyses: int) -> dict:
        """The check's numbers of a design-grid cell (design.json ``cells``, SI): verdict, reason, governing,
        acceptance numbers, ``decided_at_design_level``, ``analyses`` (run) and ``analyses_saved``, the neutral
        ``material`` [kg] and ``demand`` the recommendation ranks by, ``median_theta_max_over_theta_c`` (the median
        response ratio) and the kind's own numbers (:attr:`design_columns`)."""
        return self._grid().grid_cell(result, analyses)

    def grid_draws(self, result, *, records, executor) -> dict:
        """The perturbation draws of a variant that passes at nominal values (SPEC §15: amplitude ± 0.1 %,
        c_r ± 2 %, rtol ÷ 10, as the check's robustness criteria run them), stopping at the first draw that
        fails: ``{"n": draws run, "failed": 0 | 1, "size": draws planned, "first_failure": words | None,
        "what": what the draws vary, in words}``."""
        return self._grid().grid_draws(result, records=records, executor=executor)
