"""The library API of ``import rockdesign as rd`` (notebooks and scripts; the CLI is a thin layer over it).

    import rockdesign as rd
    project = rd.load_project("podium.toml")            # or rd.parse_project(toml_text, name="podium")
    q = rd.design_quantities(project)                   # q.theta_c.value [rad], q["theta_c"].unit, q.as_json()
    r = rd.simulate(project, "ricker-anti:ap=0.38g,Tp=0.95s")   # r.theta_max [rad], r.t [s], r.theta [rad]
    c = rd.check(project, progress=False)               # c.verdict, c.records, c.fragility, c.as_json()
    rd.write_report(c, "out/")                          # report.pdf/html, results.json/csv

Every result is a typed object whose ``as_json()`` is exactly the JSON of the matching CLI command
(``quantities --json``, ``simulate --json``, ``check --json``).  Errors are
:class:`rockdesign.RockdesignError` subclasses whose ``key`` names the offending parameter of the
function called (``motion``, ``model``, ``t_end``...), not a command-line flag.
"""
from __future__ import annotations

import dataclasses
import functools
import tomllib
from collections.abc import Mapping
from pathlib import Path

from .api import SimulationResult, model_for_project, quantities_json, simulate_project
from .design.quantities import Quantity
from .errors import ProjectError, RockdesignError
from .project import Project, load_project
from .project import parse_project as _parse_raw

__all__ = ["load_project", "parse_project", "design_quantities", "simulate", "check", "write_report",
           "Quantities", "SimulationResponse"]


def _parameter_names(func):
    """Re-key errors raised below with a command-line flag (``--t-end``) to the parameter (``t_end``)."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except RockdesignError as exc:
            if exc.key and exc.key.startswith("-"):
                exc.key = exc.key.split("/")[-1].lstrip("-").replace("-", "_")
                exc.args = (exc.format(),)
            raise

    return wrapper


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
    return _parse_raw(raw, file=name, text=text)


class Quantities(Mapping):
    """The closed-form design quantities of a project (CONTRACT §3 names), by key or attribute.

    Each value is a :class:`~rockdesign.design.quantities.Quantity` with ``value`` in SI units,
    ``unit`` (the unit of ``value``: "m", "rad", "1/s", "m/s^2", "-"...), ``symbol``, ``equation``
    (thesis equation number) and ``formula``.  ``q.theta_c.value`` and ``q["theta_c"].value`` are
    the same number; ``lambda`` (a Python keyword) is reached as ``q["lambda"]``.
    """

    def __init__(self, project: Project):
        from .design.quantities import design_quantities as _compute
        self.project = project
        self._items: dict[str, Quantity] = dict(_compute(project.system, project.analysis.rigid_superstructure_ratio))

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
        return quantities_json(self.project)

    def __repr__(self) -> str:
        body = ", ".join(f"{k}={q.value:.6g} {q.unit}" for k, q in self._items.items())
        return f"Quantities({body})"


def design_quantities(project: Project) -> Quantities:
    """The closed-form design quantities of a project (uplift, θc, ρc, R̂, p, c_r...; thesis Ch. 2–4)."""
    if not isinstance(project, Project):
        raise ProjectError("design_quantities needs a project", key="project",
                           expected="a Project (rd.load_project or rd.parse_project)", found=type(project).__name__)
    return Quantities(project)


@dataclasses.dataclass(frozen=True)
class SimulationResponse(SimulationResult):
    """One time-history analysis of a project: the response and what was analysed.

    Arrays: ``t`` [s], ``theta`` [rad], ``thetadot`` [rad/s], ``u_B`` (column top) [m], ``u_T``
    (superstructure, relative to the ground) [m], ``ground_acceleration`` [m/s²].  Scalars:
    ``theta_max`` [rad], ``theta_max_over_alpha`` [-], ``theta_max_over_theta_c`` [-], ``u_B_max`` [m],
    ``uplift_time`` [s] (None without uplift), ``impacts``, ``overturned``, ``overturn_mode``; every
    other attribute of :class:`rockdesign.dynamics.response.Response` is reached the same way.
    ``as_json()`` is the ``simulate --json`` object.
    """

    @property
    def t(self):
        """Output times [s]."""
        return self.response.t

    @property
    def theta(self):
        """Rotation θ(t) [rad]."""
        return self.response.theta

    @property
    def theta_max(self) -> float:
        """Peak |θ| [rad]."""
        return self.response.theta_max

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.__dict__["response"], name)


@_parameter_names
def simulate(project: Project, motion, *, model: str = "auto", t_end: float | None = None,
             rtol: float | None = None, records_dir: str | Path | None = None) -> SimulationResponse:
    """One nonlinear time-history analysis of a project (thesis Eq 3.12 / 3.46 / 4.13 and the impact maps).

    Args:
        project: a :class:`Project`.
        motion: a motion string (``"ricker-anti:ap=0.38g,Tp=0.95s"``, ``"record:p695-ff/11a,scale=1.5"``,
            ``"free:theta0=0.8alpha"``...) or a :class:`~rockdesign.motions.motion.GroundMotion`.
        model: ``auto`` | ``exact`` | ``linear`` | ``linear-exact``.
        t_end: end time [s] (default: motion duration + the project's free vibration).
        rtol: relative tolerance (default: the project's).
        records_dir: folder of PEER AT2 files for ``file:``/``rsn:`` motions.
    """
    from .motions.motion import GroundMotion
    if isinstance(motion, str):
        result = simulate_project(project, motion, model=model, t_end=t_end, rtol=rtol,
                                  records_dir=str(records_dir) if records_dir else None)
    elif isinstance(motion, GroundMotion):
        from .dynamics.simulate import simulate as _simulate
        eq, structure = model_for_project(project, model)
        a = project.analysis
        response = _simulate(project.system, motion, model=eq, structure=structure, rtol=rtol or a.rtol,
                             atol=a.atol, t_end=t_end if t_end is not None else motion.duration + a.free_vibration,
                             overturn=a.overturn, rest_velocity=a.rest_velocity,
                             rigid_ratio=a.rigid_superstructure_ratio)
        result = SimulationResult(project, motion.name, response)
    else:
        raise RockdesignError("unknown motion", key="motion", expected="a motion string or a GroundMotion",
                              found=type(motion).__name__)
    return SimulationResponse(**{f.name: getattr(result, f.name) for f in dataclasses.fields(result)})


@_parameter_names
def check(project: Project, *, progress: bool = False, records_dir: str | Path | None = None,
          margins: bool = True, executor=None):
    """The design check of a project (the work of ``rockdesign check``): a :class:`CheckResult`.

    Args:
        project: a :class:`Project`, however it was made.
        progress: draw progress bars (rich; works in a terminal and in a notebook).
        records_dir: folder of PEER AT2 files for suites that name them.
        margins: run the incremental overturning-margin analysis.
        executor: a started executor of :mod:`rockdesign.execution.executor` (e.g. a dask cluster).

    Returns:
        CheckResult with ``verdict`` ("PASS" | "FAIL"), ``records`` (one outcome per record: scale,
        PGA [m/s²], SD_max [m], θ_max/α, class...), ``checks``, ``statistics``, ``fragility`` (None
        until computed) and ``as_json()`` = results.json.  For a ``[cylinder]`` project a
        :class:`~rockdesign.checks.cylinder_check.CylinderCheckResult` (``verdict``, ``records``,
        ``checks``, ``summary``, ``histories``, ``as_json()``; docs/cylinder.md); ``records_dir`` and
        ``executor`` do not apply to it.
    """
    from .checks.check import run_check
    from .progress import progress_bars
    if not isinstance(project, Project):
        raise ProjectError("check needs a project", key="project",
                           expected="a Project (rd.load_project or rd.parse_project)", found=type(project).__name__)
    if project.system.kind == "cylinder":     # the 3D cylinder (thesis Ch. 5): a CylinderCheckResult
        from .checks.cylinder_check import cylinder_check
        for key, value in (("records_dir", records_dir), ("executor", executor)):
            if value is not None:
                raise RockdesignError("not used by the check of a cylinder (built-in suites of record pairs, "
                                      "analysed in this process)", key=key, expected="None",
                                      found=type(value).__name__ if key == "executor" else repr(str(value)))
        with progress_bars(disable=not progress) as tick:
            return cylinder_check(project, progress=tick)
    with progress_bars(disable=not progress) as tick:
        return run_check(project, records_dir=str(records_dir) if records_dir else None, margins=margins,
                         progress=tick, executor=executor)


@_parameter_names
def write_report(result, out_dir, *, pdf: bool = True, html: bool = True, pdf_worker=None) -> Path:
    """Write a check's ``report.pdf``, ``report.html``, ``results.json``, ``results.csv`` into ``out_dir``
    (for a cylinder check also the figures ``cylinder_vs_planar.png`` and ``wobbling_period.png``).

    The folder is written all or nothing (a temporary folder beside it is moved into place when
    complete), holds only this run's files afterwards, and is locked against concurrent runs (see
    :mod:`rockdesign.outdir`).  ``out_dir`` may also be a locked :class:`~rockdesign.outdir.OutputFolder`.
    ``pdf_worker``: a started :class:`rockdesign.report.pdf_worker.PdfWorker` (``PdfWorker.start()``,
    ``close()`` it afterwards) writes a planar check's PDF in a second process, as ``rockdesign check``
    does; the files are the same without it.

    Returns:
        The output folder.
    """
    from .checks.cylinder_check import CylinderCheckResult
    from .outdir import OutputFolder
    from .report.results import write_results_csv, write_results_json
    if isinstance(result, CylinderCheckResult):
        from .report.cylinder_report import write_cylinder_folder
        return write_cylinder_folder(result, out_dir, pdf=pdf, html=html)
    folder = out_dir if isinstance(out_dir, OutputFolder) else OutputFolder(out_dir, key="out_dir")
    data = result.as_json()
    with folder.staging() as tmp:
        write_results_json(data, tmp / "results.json")
        write_results_csv(data, tmp / "results.csv")
        if pdf or html:
            from .report.render import write_report as _render
            _render(result, tmp, pdf=pdf, html=html, pdf_worker=pdf_worker)
    return folder.target
