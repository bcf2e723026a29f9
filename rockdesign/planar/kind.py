"""The planar kind of structure: solitary columns, rocking frames and rocking podium buildings
(thesis Ch. 3–4): ``[column]`` or ``[podium]`` projects."""
from __future__ import annotations

from pathlib import Path

from ..errors import RockdesignError
from ..kinds.base import StructureKind
from ..kinds.options import CliOption

# Everything else is imported where it is used: the registry loads the kind without pint (the command line lists
# the kinds' spectrum options from it), and reading and validating a project (``parse``) loads no engine, numba
# kernel, figure or report module, so a mistake in a project file is reported before the engine loads
# (tests/cli/test_startup.py).


class Planar(StructureKind):
    """Columns, frames and podiums: the planar engine, the Polyakov check over record suites."""

    name = "planar"
    systems = ("column", "podium")
    templates = ("podium", "column")
    spectrum_options = ("pulse", "x", "y", "relative", "out_dir", "executor", "model", "structure", "overturn",
                        "t_free", "rtol", "tm_ratio", "chunk_rows", "resume", "keep_chunks", "energy_stop",
                        "stop_at_capacity", "polyakov", "equivalent_at", "figures")
    """The parameters of :func:`~rockdesign.planar.spectra.run.pulse_spectrum` that ``rd.spectrum`` passes on."""
    spectrum_cli = (
        CliOption("pulse", short="p", applies_to="planar structures",
                  help="ricker-anti | ricker-sym | sine | cycloidal-a | cycloidal-b | cycloidal-c"),
        CliOption("x", applies_to="planar structures",
                  help="x axis AXIS:lo:hi:n, AXIS = omega_p/p | omega_p/p_hat | Tp (seconds) (default: omega_p/p from "
                       "0.5 to 12, 801 points)"),
        CliOption("y", applies_to="planar structures",
                  help="y axis AXIS:lo:hi:n, AXIS = ap/up (a_p over g tan α) | ap/g (default: ap/up from 0 to 12, 401 "
                       "points)"),
        CliOption("model", help="Equations: exact | linear | auto (default: auto, the equations of the project's "
                                "analysis table)."),
        CliOption("structure", help="auto | block | frame | rigid-superstructure | podium-2dof (default: the model of "
                                    "the project's analysis table)."),
        CliOption("overturn", help="static (θ_max ≥ θc) | dynamic (|θ| = π/2) (default: the project's analysis "
                                   "overturn)."),
        CliOption("t_free", float, "Free vibration in s after the pulse (default: the project's analysis "
                                   "free_vibration, 10 s)."),
        CliOption("rtol", float, "Relative tolerance (default: project)."),
        CliOption("tm_ratio", float, "Ricker centre t_m/T_p (default: 1.5, thesis Table 3.4)."),
        CliOption("chunk_rows", int, "Grid rows per chunk (default: about 48 chunks, or the interrupted run's)."),
        CliOption("resume", bool, "Reuse the chunks of an interrupted run with identical inputs (default: resume).",
                  negatable=True),
        CliOption("keep_chunks", bool, "Keep the chunk files after success."),
        CliOption("energy_stop", bool, "Stop each analysis once the energy bound proves θ_max final (docs: "
                                       "early_termination.md; default: on).", negatable=True),
        CliOption("stop_at_capacity", bool, "Static criterion: stop each analysis when θ reaches θc (verdict final; "
                                            "θ_max shown as θc)."),
        CliOption("polyakov", bool, "Overlay Polyakov's overturning line (SD_max of the pulse = u_B(θc); default: "
                                    "on).", negatable=True),
        CliOption("equivalent_at", float, "Ordinate(s) y for the equivalent size of Eq 3.65 (repeatable).",
                  metavar="Y", multiple=True),
    )
    """The spectrum's options on the command line (``rockdesign spectrum``; the axes ``x`` and ``y`` are shared with
    other kinds, each kind's help joined)."""

    grid_module = "rockdesign.planar.grid"
    experiments_module = "rockdesign.planar.experiments"

    key_alternatives = {"radius": ("curvature",), "curvature": ("radius",), "height": ("half_height",),
                        "half_height": ("height",), "width": ("slenderness",), "slenderness": ("width",),
                        "period": ("frequency",), "frequency": ("period",)}
    """Keys that say the same thing two ways (CONTRACT §1): a ``--vary`` of one replaces the other."""
    design_demand = "superstructure shear coefficient (84th percentile"
    design_material = ("column material", "no elastic superstructure demand")
    design_columns = (("uplift_acceleration", "", "m/s^2"), ("uplift_shear_coefficient", "tan α", "-"),
                      ("theta_c", "θc", "rad"), ("column_material", "material", "kg"))
    """A planar cell's own numbers (:func:`rockdesign.planar.grid.grid_cell`): the uplift acceleration and its base
    shear coefficient tan α (Eq 3.34), the rotation capacity θc (Eq 3.56) and the columns' mass."""
    design_draws = ("c_r − 2 % and + 2 %, then the ensemble_size runs of the whole suite with the amplitude × "
                    "(1 ± 0.1 %) per record, c_r × (1 ± 2 %) and rtol ÷ 10")
    design_response = ("θ_max/θc", "the peak rotation over the rotation capacity θc (Eq 3.56)")
    design_plane = {"x": "uplift_shear_coefficient", "y": "theta_c",
                    "x_label": "uplift base-shear coefficient tan α [-] (Eq 3.34)",
                    "y_label": "rotation capacity θc [rad] (Eq 3.56)",
                    "caption": "The variants in the plane of the thesis's two curved-base design parameters: the uplift "
                               "base-shear coefficient tan α (Eq 3.34) and the rotation capacity θc (Eq 3.56); one mark "
                               "per analysed variant, and variants that fall on one point (equal tan α and θc) drawn as "
                               "a small block of marks around it."}

    @property
    def csv_columns(self):
        from .checks.results_csv import CSV_COLUMNS
        return CSV_COLUMNS

    @property
    def csv_units(self):
        from .checks.results_csv import CSV_UNITS
        return CSV_UNITS

    @property
    def csv_nested(self):
        from .checks.results_csv import CSV_NESTED
        return CSV_NESTED

    def grid_batches(self, executor=None):
        """Every analysis of the planar check runs through ``run_jobs``, which takes a pool member; on an
        ``executor`` the merged calls run there in chunks."""
        from .dynamics.shared_batches import SharedBatches
        return SharedBatches(executor)

    def kernels(self, command):
        """The rocking engine (``simulate``); with the closed-form linear integrator of the report's accuracy
        statement and the elastic spectrum of Polyakov's rule (``check``)."""
        from ..motions.warm_up import ELASTIC_SPECTRUM
        from .dynamics.warm_up import ENGINE, LINEAR_EXACT
        return {"simulate": (ENGINE,), "check": (ENGINE, LINEAR_EXACT, ELASTIC_SPECTRUM)}.get(command, ())

    def claims(self, raw):
        return True            # the default kind: its parser names what is missing ([column] or [podium])

    def parse(self, raw, *, file, text):
        from .project import parse_planar_project
        return parse_planar_project(raw, file=file, text=text)

    def quantities(self, project):
        from .design.quantities import design_quantities
        return design_quantities(project.system, project.analysis.rigid_superstructure_ratio)

    def write_curve(self, project, path):
        """The pushover curve F_R/(m_C g) against θ through both phases (Fig 3.15, Eqs 3.18/3.48), from
        θ = 0 to θc: a CSV table (``theta_rad, F_R_over_mg, phase``) or, for .png/.svg/.pdf, the report's plot."""
        import numpy as np

        from .checks.figure_data import pushover_data
        path = Path(path)
        suffix = path.suffix.lower()
        if suffix not in (".csv", ".png", ".svg", ".pdf"):
            raise RockdesignError("unknown pushover file type", key="path",
                                  expected=".csv, .png, .svg or .pdf", found=f"'{path.name}'")
        curve = pushover_data(project.system)
        if suffix == ".csv":
            theta, force = curve["theta"], curve["force"]
            phase = np.where((curve["radius"] > 0) & (theta <= curve["beta"]), 1, 2)
            np.savetxt(path, np.column_stack([theta, force, phase]), delimiter=",", fmt=["%.15g", "%.15g", "%d"],
                       header="theta_rad,F_R_over_mg,phase", comments="")
        else:
            from ..plots import save
            from .report.figures import pushover_figure
            save(pushover_figure(curve), path)

    def simulation_request(self, project, motion, *, model, t_end, rtol, records_dir):
        from . import simulation as planar_simulation
        return planar_simulation.simulation_request(project, motion, model=model, t_end=t_end, rtol=rtol,
                                                    records_dir=records_dir)

    def run_simulation(self, request):
        from . import simulation as planar_simulation
        return planar_simulation.run_simulation(request)

    def prepare_check(self, project, *, records_dir):
        """Read the records (an input error in them stops a first run before it compiles)."""
        from .checks import check as planar_check
        planar_check.check_records(project, records_dir)

    def check(self, project, *, progress, records_dir, margins, executor):
        from .checks import check as planar_check
        return planar_check.run_check(project, records_dir=records_dir, margins=margins, progress=progress, executor=executor)

    def report(self, result):
        from ..report.document import ReportParts
        from .report.report import render_html
        return ReportParts(html=lambda: render_html(result))

    def spectrum(self, project, request):
        """The rocking spectrum over a pulse family (thesis Sec 3.3.2; :func:`~rockdesign.planar.spectra.run.pulse_spectrum`)."""
        from .spectra import run as pulse_spectra
        options = request.accepted(self.spectrum_options, "the spectrum of a planar system (pulses)",
                                   "pulse and the pulse spectrum's options (record is for a [cylinder] project)")
        reference = options.get("relative")
        if reference is not None and reference.system.kind not in self.systems:
            raise RockdesignError("a relative spectrum compares two planar systems", key="relative",
                                  expected="a [column] or [podium] project", found=f"a {reference.system.kind}")
        return pulse_spectra.pulse_spectrum(project, **options, progress=request.progress, say=request.say)
