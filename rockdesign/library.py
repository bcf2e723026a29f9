"""The library API of ``import rockdesign as rd`` (notebooks and scripts; the CLI is a thin layer over it).

    import rockdesign as rd
    project = rd.load_project("podium.toml")            # or rd.parse_project(toml_text, name="podium")
    q = rd.design_quantities(project)                   # q.theta_c.value [rad], q["theta_c"].unit, q.as_json()
    r = rd.simulate(project, "ricker-anti:ap=0.38g,Tp=0.95s")   # r.theta_max [rad], r.t [s], r.theta [rad]
    c = rd.check(project, progress=False)               # c.verdict, c.records, c.fragility, c.as_json()
    rd.write_report(c, "out/")                          # report.pdf/html, results.json/csv
    s = rd.spectrum(project, pulse="sine", out_dir="spec/")   # s.spectrum.theta_max_over_alpha, s.as_json()

Every kind of structure — planar (column, frame, podium) and the 3D cylinder — goes through these
same functions: each asks the registry (:mod:`rockdesign.kinds`) once for the project's kind and
calls it.  Every result is a typed object whose ``as_json()`` is exactly the JSON of the matching CLI
command (``quantities --json``, ``simulate --json``, ``check --json``, ``spectrum --json``).  Errors are
:class:`rockdesign.RockdesignError` subclasses whose ``key`` names the offending parameter of the
function called (``motion``, ``model``, ``t_end``...), not a command-line flag.

The second group of functions (:func:`simulation_request`, :func:`run_simulation`,
:func:`check_options`, :func:`prepare_check`, :func:`run_check`, :func:`check_output_folder`,
:func:`write_capacity_curve`, :func:`compile_kernels`) are the steps the commands take one by one
(validate everything, compile on a first run, analyse, write); their errors name parameters too, which the
command line shows as its options.

The other commands have their functions beside these (``rd.records_list`` … ``rd.records_scale_model``,
``rd.calibration``, ``rd.validation``, ``rd.ensemble``, ``rd.benchmark``, ``rd.design``; docs/api.md).
"""
from __future__ import annotations

import tomllib
from collections.abc import Mapping
from pathlib import Path

from .execution import compilation
from .errors import ProjectError, RockdesignError
from .execution.executor import check_executor, running_on
from .kinds import kind_of, parse_document
from .kinds.base import CheckResult, SimulationRequest, SimulationResult, SpectrumOptions, SpectrumResult
from .outdir import OutputFolder
from .paths import require_path
from .progress import progress_bars
from .project_tables import Project, read_document
from .quantity import Quantity
from .report.document import write_document
from .report.results import json_text, write_results_csv, write_results_json  # noqa: F401 (json_text: the CLI)

__all__ = ["load_project", "parse_project", "design_quantities", "simulate", "check", "write_report", "spectrum",
           "Quantities"]

def _require_project(project, function: str) -> None:
    if not isinstance(project, Project):
        raise ProjectError(f"{function} needs a project", key="project",
                           expected="a Project (rd.load_project or rd.parse_project)", found=type(project).__name__)


KEYED_BY_MOTION = ("record id",)
"""Keys of the record loader that a motion string's errors report as the parameter ``motion``."""


# --- the project ---------------------------------------------------------------------------------
def load_project(path: str | Path) -> Project:
    """Read and validate a project file (CONTRACT §1) of any kind of structure into a :class:`Project` (SI).

    Everything is validated here, once — ``[excitation]`` and ``[analysis]`` included, parsed into the
    typed ``project.excitation`` and ``project.analysis`` — so every command refuses the same input.
    """
    require_path(path, "path", "a project file name")
    try:
        raw, text = read_document(path)
    except ProjectError as exc:
        if exc.key is None:          # the file itself (not found, unreadable, not TOML): the parameter path
            exc.key = "path"
            exc.args = (exc.format(),)
        raise
    return parse_document(raw, file=str(path), text=text)


def parse_project(toml_text: str, name: str = "<string>") -> Project:
    """A project from TOML text (the content of a project file; no file needed).

    Args:
        toml_text: the project file's text (CONTRACT §1 keys, quantities as strings with units).
        name: what error messages and ``results.json`` (``project.file``) call the source.

    Raises:
        ProjectError: invalid TOML or project content (names ``name``, the key and what was expected).
    """
    if not isinstance(toml_text, str):
        raise ProjectError("project text must be a string", key="toml_text", expected="TOML text",
                           found=type(toml_text).__name__)
    text = toml_text.lstrip("\ufeff")
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ProjectError(f"invalid TOML ({exc})", file=name) from None
    return parse_document(raw, file=name, text=text)


# --- design quantities ---------------------------------------------------------------------------
class Quantities(Mapping):
    """The closed-form design quantities of a project (CONTRACT §3 names), by key or attribute.

    Each value is a :class:`~rockdesign.planar.design.quantities.Quantity` with ``value`` in SI units,
    ``unit`` (the unit of ``value``: "m", "rad", "1/s", "m/s^2", "-"...), ``symbol``, ``equation``
    (thesis equation number) and ``formula``.  ``q.theta_c.value`` and ``q["theta_c"].value`` are
    the same number; ``lambda`` (a Python keyword) is reached as ``q["lambda"]``.
    """

    def __init__(self, project: Project):
        kind = kind_of(project)
        self.project = project
        self.title = kind.quantities_title(project)
        self._items: dict[str, Quantity] = dict(kind.quantities(project))
        self._json = kind.quantities_json(project)

    def __getitem__(self, name: str) -> Quantity:
        return self._items[name]

    def __iter__(self):
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __getattr__(self, name: str) -> Quantity:
        items = self.__dict__.get("_items", {})
        if name in items:
            return items[name]
        raise AttributeError(f"no design quantity '{name}' for this system (available: {', '.join(items)})")

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self._items))

    def as_json(self) -> dict:
        """The ``quantities --json`` object: ``{"quantities": {NAME: {"value", "unit", "equation"}}, "warnings"}``."""
        return self._json

    def __repr__(self) -> str:
        body = ", ".join(f"{k}={q.value:.6g} {q.unit}" for k, q in self._items.items())
        return f"Quantities({body})"


def design_quantities(project: Project) -> Quantities:
    """The closed-form design quantities of a project (uplift, θc, ρc, R̂, p, c_r...; thesis Ch. 2–5)."""
    _require_project(project, "design_quantities")
    return Quantities(project)


def write_capacity_curve(project: Project, path) -> None:
    """``quantities --pushover PATH``: the pushover curve of a planar structure (Fig 3.15), the wobbling
    period of a cylinder (Fig 5.2); .csv for the numbers, .png/.svg/.pdf for the figure."""
    kind_of(project).write_curve(project, path)


# --- one time-history analysis -------------------------------------------------------------------
def simulation_request(project: Project, motion, *, model: str = "auto", t_end: float | None = None,
                       rtol: float | None = None, records_dir: str | Path | None = None) -> SimulationRequest:
    """Parse a CONTRACT §2 motion string (or take a motion object) and validate the whole request, analysing
    (and compiling) nothing: bad input is reported at once, also on a first run."""
    _require_project(project, "simulate")
    if records_dir is not None:
        require_path(records_dir, "records_dir", "a folder of record files")
    try:
        return kind_of(project).simulation_request(project, motion, model=model, t_end=t_end, rtol=rtol,
                                                   records_dir=str(records_dir) if records_dir else None)
    except RockdesignError as exc:
        if exc.key is None or exc.key in KEYED_BY_MOTION:    # the record a motion names: the caller's ``motion``
            exc.key = "motion"
            exc.args = (exc.format(),)
        raise


def run_simulation(request: SimulationRequest, *, say=None) -> SimulationResult:
    """Analyse a validated request (:func:`simulation_request`).  With ``say`` (a print function) the
    kernels are compiled first on a first run, and that is announced."""
    kind = kind_of(request.project)
    if say is not None:
        compilation.prepare("simulate", kind.kernels("simulate"), say)
    return kind.run_simulation(request)


def simulate(project: Project, motion, *, model: str = "auto", t_end: float | None = None,
             rtol: float | None = None, records_dir: str | Path | None = None) -> SimulationResult:
    """One nonlinear time-history analysis of a project (thesis Eq 3.12 / 3.46 / 4.13; Eqs 5.22–5.31 for
    a cylinder).

    Args:
        project: a :class:`Project`.
        motion: a motion string (``"ricker-anti:ap=0.38g,Tp=0.95s"``, ``"record:p695-ff/11a,scale=1.5"``,
            ``"free:theta0=0.8alpha"``; for a cylinder ``"record:p695-ff/1,resultant_pga=0.3g"``...) or a
            motion object (:class:`~rockdesign.motions.motion.GroundMotion`; a
            :class:`~rockdesign.cylinder.pairs.MotionPair` for a cylinder).
        model: ``auto`` | ``exact`` | ``linear`` | ``linear-exact`` (cylinder: ``auto`` | ``undamped`` | ``damped``).
        t_end: end time [s] (default: motion duration + the project's free vibration).
        rtol: relative tolerance (default: the project's).
        records_dir: folder of PEER AT2 files for ``file:``/``rsn:`` motions.

    Returns:
        A :class:`SimulationResponse` (planar) or :class:`CylinderSimulation`; ``as_json()`` is
        ``simulate --json``.
    """
    return run_simulation(simulation_request(project, motion, model=model, t_end=t_end, rtol=rtol,
                                             records_dir=records_dir))


# --- the design check ----------------------------------------------------------------------------
def check_options(project: Project, *, records_dir=None, executor=None) -> None:
    """Refuse ``records_dir`` / ``executor`` where the project's kind has no use for them, and arguments of the
    wrong type; a dask value (``"local:4"``, ``"tcp://host:8786"``) is checked, and a scheduler must answer."""
    _require_project(project, "check")
    if records_dir is not None:
        require_path(records_dir, "records_dir", "a folder of record files")
    kind_of(project).check_options(project, records_dir=records_dir, executor=executor)   # a kind's refusal first
    check_executor(executor)


def prepare_check(project: Project, *, records_dir=None, say=None) -> None:
    """Before the analyses of ``check``, on a first run: stop on input errors that only reading the records
    shows, then compile the kernels (announced with ``say``)."""
    kind = kind_of(project)
    kernels = kind.kernels("check")
    if not compilation.missing(kernels):
        return
    kind.prepare_check(project, records_dir=str(records_dir) if records_dir else None)
    compilation.prepare("check", kernels, say)


def run_check(project: Project, *, progress: bool = False, records_dir=None, margins: bool = True,
              executor=None) -> CheckResult:
    """The design check (see :func:`check`); ``executor`` may also be a ``--dask`` value ("local:N" or a
    scheduler address), started and closed here."""
    kind = kind_of(project)
    check_executor(executor, reach=False)
    with running_on(executor) as on, progress_bars(disable=not progress) as tick:
        return kind.check(project, progress=tick, records_dir=str(records_dir) if records_dir else None,
                          margins=margins, executor=on)


def check(project: Project, *, progress: bool = False, records_dir: str | Path | None = None,
          margins: bool = True, executor=None) -> CheckResult:
    """The design check of a project (the work of ``rockdesign check``), for every kind of structure.

    Args:
        project: a :class:`Project`, however it was made.
        progress: draw progress bars (rich; works in a terminal and in a notebook).
        records_dir: folder of PEER AT2 files for suites that name them (planar structures).
        margins: run the incremental overturning-margin analysis.
        executor: a started executor of :mod:`rockdesign.execution.executor` (e.g. a dask cluster;
            planar structures).

    Returns:
        A check result: ``verdict`` ("PASS" | "FAIL"), ``verdict_reason``, ``records`` (one outcome per
        record, or per record pair of a cylinder), ``checks``, ``statistics`` and ``as_json()`` =
        results.json (the same sections for every kind; docs/model.md, docs/cylinder.md).
    """
    check_options(project, records_dir=records_dir, executor=executor)
    return run_check(project, progress=progress, records_dir=records_dir, margins=margins, executor=executor)


def check_output_folder(project: Project, target, *, key: str = "out_dir") -> OutputFolder:
    """The output folder of a project's check (validated; owns the files the kind writes there)."""
    if not isinstance(target, OutputFolder):
        require_path(target, key, "a folder name")
    return kind_of(project).output_folder(target, key=key)


def write_report(result, out_dir, *, pdf: bool = True, html: bool = True) -> Path:
    """Write a check's ``report.pdf``, ``report.html``, ``results.json``, ``results.csv`` (and its
    figures) into ``out_dir``.

    The folder is written all or nothing (a temporary folder beside it is moved into place when
    complete), holds only this run's files afterwards, and is locked against concurrent runs (see
    :mod:`rockdesign.outdir`).  ``out_dir`` may also be a locked :class:`~rockdesign.outdir.OutputFolder`.

    Returns:
        The output folder.
    """
    kind = kind_of(result)
    if not isinstance(out_dir, OutputFolder):
        require_path(out_dir, "out_dir", "a folder name")
    folder = out_dir if isinstance(out_dir, OutputFolder) else kind.output_folder(out_dir, key="out_dir")
    data = result.as_json()
    with folder.staging() as tmp:
        write_results_json(data, tmp / "results.json")
        write_results_csv(data, tmp / "results.csv", columns=kind.csv_columns, units=kind.csv_units,
                          nested=kind.csv_nested)
        write_document(kind.report(result), tmp, pdf=pdf, html=html)
    return folder.target


# --- rocking spectra ------------------------------------------------------------------------------
def spectrum(project: Project, *, progress=False, say=None, **options) -> SpectrumResult:
    """The rocking spectrum of a project, written into ``out_dir`` (the work of ``rockdesign spectrum``;
    docs/spectra.md, docs/cylinder.md).

    The project's kind runs it (:meth:`~rockdesign.kinds.base.StructureKind.spectrum`) with the options given by
    name: each kind declares the options its spectrum takes (``spectrum_options``) and refuses any other, naming
    it (:meth:`~rockdesign.kinds.base.SpectrumOptions.accepted`); an option given as None is left at the kind's
    default.  docs/api.md lists the options of the built-in kinds (the pulse family of a planar structure, the record
    pair of a cylinder); ``rockdesign.kinds.kind_of(project).spectrum_options`` names those of a project's kind.

    Args:
        project: a :class:`Project`.
        progress: True draws progress bars (rich; a terminal or a notebook), or a function
            ``progress(stage, done, total)``.
        say: a print function announcing a first-run compilation.
        **options: the kind's options.  Read here for every kind: ``relative`` — a reference project of the same
            kind (a :class:`Project` or its file): the relative spectrum; ``out_dir`` — the output folder
            (default ``<project file stem>-spectrum-<pulse or pair>``); ``executor`` — a dask value ``"local:N"``
            or a scheduler address (started and closed by the spectrum), or a started executor of
            :mod:`rockdesign.execution.executor`, for a kind whose spectrum takes one; ``figures`` — write the
            figures (default True).

    Returns:
        The kind's spectrum: ``out_dir``, ``as_json()`` (= summary.json), ``spectrum`` (arrays over the grid),
        ``reference``, ``title`` and ``summary_rows()``.  A planar run interrupted by Ctrl-C raises
        KeyboardInterrupt saying how many chunks were kept: the same call resumes from them.
    """
    _require_project(project, "spectrum")
    given = {name: value for name, value in options.items() if value is not None}
    if "out_dir" in given:
        require_path(given["out_dir"], "out_dir", "a folder name")
    check_executor(given.get("executor"), reach=False)   # a dask value is reached when the spectrum starts it
    relative = given.get("relative")
    if isinstance(relative, (str, Path)):
        given["relative"] = load_project(relative)
    elif relative is not None and not isinstance(relative, Project):
        raise ProjectError("a relative spectrum needs a reference project", key="relative",
                           expected="a Project or a project file", found=type(relative).__name__)
    kind = kind_of(project)
    if progress is True:
        with progress_bars() as tick:
            return kind.spectrum(project, SpectrumOptions(given, progress=tick, say=say))
    return kind.spectrum(project, SpectrumOptions(given, progress=progress or None, say=say))


def compile_kernels(project: Project, command: str = "check", say=None) -> float:
    """Compile the kernels ``command`` ("simulate", "check") needs for ``project``'s kind on a first run
    (:mod:`rockdesign.execution.compilation`), announcing it with ``say``; seconds spent (0 when they were
    compiled before)."""
    return compilation.prepare(command, kind_of(project).kernels(command), say)
