"""The interface every kind of structure supplies (the registry is :mod:`rockdesign.kinds`).

A kind of structure (planar: column, frame, podium; the 3D cylinder) is one object with these
methods; ``rd.load_project``, ``rd.design_quantities``, ``rd.simulate``, ``rd.check`` and
``rd.write_report`` ask the registry for the kind once and call it — no other module branches on the
kind of a structure.  The pattern is scipy's ``METHODS`` table of ``solve_ivp``: one entry per
method, one call site.
"""
from __future__ import annotations

import abc
from pathlib import Path

from ..outdir import RUN_FILES, OutputFolder


class StructureKind(abc.ABC):
    """One kind of structure: its project parser, design quantities, time-history analysis, check and
    report.  Subclasses set the class attributes and implement every abstract method."""

    name: str = ""
    """The kind's name ("planar", "cylinder")."""
    systems: tuple[str, ...] = ()
    """``project.system.kind`` values of this kind's systems ("column", "podium"; "cylinder")."""
    simulate_kernels: str = "simulate"
    """The first-run compilation command (:mod:`rockdesign.execution.compilation`) of ``simulate``."""
    check_kernels: str = "check"
    """The first-run compilation command of ``check``."""
    spectrum_excitation: str = "pulse"
    """What the kind's rocking spectrum runs over: "pulse" (planar: a pulse family, thesis Ch. 3) or
    "record pair" (cylinder: one record pair over R and PGA, Figs 5.16–5.17)."""
    report_files: frozenset[str] = frozenset()
    """Files a check writes into its output folder besides :data:`~rockdesign.outdir.RUN_FILES`."""
    design_rule: str = ""
    """What decides the verdict of a design-grid cell (``rockdesign design``: the report's words)."""
    design_skipped: str = ""
    """What the design grid skips of a variant's check (design.json ``settings.early_stopping``)."""
    design_material: tuple[str, str] = ("column material", "no elastic superstructure demand")
    """The recommended design without a superstructure force to rank by: (what is least, why)."""
    grid_shared_batches: bool = False
    """Whether the design grid may check variants of this kind together, their analyses merged into shared
    batches (:mod:`rockdesign.planar.dynamics.batch_pool`; the analyses run through
    :func:`rockdesign.planar.checks.runner.run_jobs`)."""
    key_alternatives: dict[str, tuple[str, ...]] | None = None
    """Keys of the kind's project tables that say the same thing two ways: a ``--vary`` of one replaces the
    others (None: :data:`rockdesign.design_space.variants.ALTERNATIVES`)."""

    # --- the project file -------------------------------------------------------------------
    @abc.abstractmethod
    def claims(self, raw: dict) -> bool:
        """True when the TOML document ``raw`` describes a structure of this kind."""

    @abc.abstractmethod
    def parse(self, raw: dict, *, file: str, text: str):
        """The validated :class:`~rockdesign.project_tables.Project` (SI; ``[excitation]`` and ``[analysis]``
        typed) or a :class:`~rockdesign.errors.ProjectError`."""

    # --- design quantities ------------------------------------------------------------------
    @abc.abstractmethod
    def quantities(self, project) -> dict:
        """Design quantities: name → :class:`~rockdesign.design.quantities.Quantity` (SI, thesis equation)."""

    @abc.abstractmethod
    def quantities_title(self, project) -> str:
        """The title of the console table of the quantities."""

    def quantities_json(self, project) -> dict:
        """The ``quantities --json`` object of CONTRACT §3 (SI values)."""
        return {"quantities": {name: q.as_json() for name, q in self.quantities(project).items()},
                "warnings": list(project.warnings)}

    @abc.abstractmethod
    def write_curve(self, project, path: Path) -> None:
        """``quantities --pushover PATH``: the kind's capacity curve (.csv numbers, .png/.svg/.pdf figure)."""

    # --- one time-history analysis ----------------------------------------------------------
    @abc.abstractmethod
    def simulation_request(self, project, motion: str, *, model: str, t_end, rtol, records_dir):
        """Parse a motion string and validate the whole request without analysing or compiling anything."""

    @abc.abstractmethod
    def run_simulation(self, request):
        """Analyse a request: a result with ``response``, ``failed``, ``as_json()``, ``write_csv(path)``,
        ``write_figure(path)``, ``summary_rows()`` and ``warnings``."""

    @abc.abstractmethod
    def simulate_motion(self, project, motion, *, model: str, t_end, rtol):
        """One analysis under a motion object (a GroundMotion for a planar structure, a MotionPair for a
        cylinder); the same result type as :meth:`run_simulation`."""

    # --- the design check -------------------------------------------------------------------
    @abc.abstractmethod
    def check_options(self, project, *, records_dir, executor, keys: dict[str, str]) -> None:
        """Refuse options that do not apply to this kind (``keys`` maps option → the name to quote)."""

    @abc.abstractmethod
    def prepare_check(self, project, *, records_dir, say, report: bool, pdf_in_process: bool) -> None:
        """Before the analyses: read what can be wrong in the input and compile the kernels on a first run
        (announced with ``say``)."""

    @abc.abstractmethod
    def check(self, project, *, progress, records_dir, margins: bool, executor):
        """The design check: a result with ``project``, ``verdict``, ``verdict_reason``, ``records``,
        ``checks`` and ``as_json()`` (= results.json)."""

    def output_folder(self, target, *, key: str) -> OutputFolder:
        """The check's output folder (it owns :data:`report_files` besides the run files)."""
        return OutputFolder(target, key=key, owned=RUN_FILES | set(self.report_files))

    @abc.abstractmethod
    def write_report(self, result, folder: Path, *, pdf: bool, html: bool, pdf_worker) -> None:
        """results.json, results.csv, the figures and report.pdf/html of a check into ``folder`` (staging)."""

    # --- the design grid (rockdesign design, SPEC §15): the kind's ``grid`` module does the work --------
    grid = None
    """The module of the kind's design-grid hooks (``records_key``, ``grid_records``, ``grid_check``,
    ``grid_cell``): :mod:`rockdesign.planar.grid`, :mod:`rockdesign.cylinder.grid`."""

    def grid_records_key(self, project) -> str:
        """Which variants share the records read and scaled by :meth:`grid_records` (equal keys share)."""
        return self.grid.records_key(project)

    def grid_records(self, project, records_dir):
        """The records of the project's excitation, read and scaled once for every variant sharing them."""
        return self.grid.grid_records(project, records_dir)

    def grid_check(self, project, *, records, records_dir, executor, progress):
        """The check of one variant (its verdict is :meth:`check`'s), computing only what the verdict's word
        and the design table need (``verdict_only``) on the shared ``records``."""
        return self.grid.grid_check(project, records=records, records_dir=records_dir, executor=executor,
                                    progress=progress)

    def grid_cell(self, result, analyses: int) -> dict:
        """The check's numbers of a design-grid cell (design.json ``cells``, SI): verdict, reason, governing,
        acceptance numbers, ``decided_at_design_level``, ``analyses`` (run) and ``analyses_saved``."""
        return self.grid.grid_cell(result, analyses)
