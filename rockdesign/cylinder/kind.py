"""The cylinder kind of structure: the 3D rocking and wobbling cylinder (thesis Ch. 5): ``[cylinder]``
projects."""
from __future__ import annotations

from pathlib import Path

from ..errors import RockdesignError
from ..kinds.base import StructureKind
from ..kinds.options import CliOption

# Everything else is imported where it is used: the registry loads the kind without pint (the command line lists
# the kinds' spectrum options from it), and reading and validating a project (``claims``, ``parse``) loads no
# engine, numba kernel, figure or report module, so a mistake in a project file is reported before the engine
# loads (tests/cli/test_startup.py).


class Cylinder(StructureKind):
    """The 3D cylinder: its engine, the check over suites of record pairs against a planar analysis."""

    name = "cylinder"
    systems = ("cylinder",)
    templates = ("cylinder",)
    uses = ("rockdesign.planar.dynamics.simulate", "rockdesign.planar.system", "rockdesign.planar.dynamics.warm_up")
    """The planar rocking body of the same p and α along each component (thesis Ch. 5): the check compares with it
    through the planar engine's public simulate, whose kernels its first run compiles with the planar warm-up."""
    spectrum_options = ("record", "x", "y", "relative", "out_dir", "figures", "executor")
    """The parameters of :func:`~rockdesign.cylinder.spectrum_run.record_pair_spectrum` that ``rd.spectrum`` passes on."""
    spectrum_cli = (
        CliOption("record", applies_to="cylinders", help="the record pair, e.g. p695-ff/11 (axes R:lo:hi:n and "
                                                          "pga/up:lo:hi:n; thesis Figs 5.16-5.17)."),
        CliOption("x", applies_to="cylinders", help="R in m (default: R:0.5:30:60)."),
        CliOption("y", applies_to="cylinders", help="pga/up (default: pga/up:1:6:51)."),
    )
    """The spectrum's options on the command line (``rockdesign spectrum``): the record pair and the two axes (their
    help joined with the other kinds')."""
    design_material = ("material: the cylinder's mass", "a free-standing cylinder carries no superstructure")
    design_columns = (("n_incremental_unacceptable", "incremental unacceptable", ""), ("p_overturn", "", "-"),
                      ("median_theta_max_over_alpha", "", "-"), ("uplift_acceleration", "", "m/s^2"),
                      ("uplift_shear_coefficient", "tan α", "-"), ("theta_c", "", "rad"), ("alpha", "", "rad"),
                      ("theta_overturn", "θ_ot", "rad"), ("column_material", "material", "kg"))
    """A cylinder cell's own numbers (:func:`rockdesign.cylinder.grid.grid_cell`): the pairs overturning up to the
    design level, the fraction overturning at it, the median θ_max/α, the uplift acceleration g·tan α, α, the
    overturning tilt θ_ot (Sec 5.5.1) and the mass; ``theta_c`` is empty (Eq 3.56 is the planar column's)."""
    design_draws = ("the ensemble_size runs of the whole suite with each pair's amplitude × (1 ± 0.1 %) and the "
                    "tolerances ÷ 10; no c_r: the cylinder's impacts follow from its geometry, thesis Sec 5.5.1")
    design_response = ("θ_max/θ_ot", "the peak tilt over the tilt θ_ot = overturn_tilt·α at which the cylinder counts "
                                     "as overturned (thesis Sec 5.5.1)")
    key_alternatives = {"height": ("half_height",), "half_height": ("height",), "diameter": ("slenderness",),
                        "slenderness": ("diameter",), "mass": ("density",), "density": ("mass",)}

    @property
    def report_files(self):
        from .report import FIGURE_FILES
        return frozenset(FIGURE_FILES)

    @property
    def csv_columns(self):
        from .check import CSV_COLUMNS
        return tuple(CSV_COLUMNS)

    csv_units = {"scale": "-", "resultant_pga": "m/s^2", "theta_max_over_alpha": "-", "uplift_time": "s",
                 "planar_theta_max_over_alpha": "-", "polyakov_ratio_x": "-", "polyakov_ratio_y": "-",
                 "min_contact_force_over_weight": "-", "ensemble_overturn_fraction": "-"}
    """The units of the results.csv columns (the others are counts, ids or words)."""

    grid_module = "rockdesign.cylinder.grid"

    def grid_batches(self, executor=None):
        """The design grid checks the cylinder's variants together: each round's 3D analyses of every variant in one
        map over ``executor`` (None: this process's threads; :class:`~rockdesign.cylinder.batch.SharedPairs`)."""
        from .batch import SharedPairs
        return SharedPairs(executor)

    def kernels(self, command):
        """The cylinder's integrator (``simulate``); with the planar engine of the planar components and the
        elastic spectrum of their SD_max (``check``)."""
        from ..motions.warm_up import ELASTIC_SPECTRUM
        from ..planar.dynamics.warm_up import ENGINE
        from .warm_up import INTEGRATOR
        return {"simulate": (INTEGRATOR,), "check": (INTEGRATOR, ENGINE, ELASTIC_SPECTRUM)}.get(command, ())

    def claims(self, raw):
        from .project import claims
        return claims(raw)

    def parse(self, raw, *, file, text):
        from .project import parse_cylinder_project
        return parse_cylinder_project(raw, file=file, text=text)

    def quantities(self, project):
        from .quantities import cylinder_quantities
        return cylinder_quantities(project.system)

    def quantities_title(self, project):
        return f"{project.name} — design quantities (cylinder, {project.system.contact} contact)"

    def write_curve(self, project, path):
        """The wobbling-period curve (Fig 5.2): CSV (theta_over_alpha, Tw_p, T_housner_p) or a figure."""
        import numpy as np

        from .quantities import wobbling_curve
        path = Path(path)
        if path.suffix.lower() not in (".csv", ".png", ".svg", ".pdf"):
            raise RockdesignError("unknown file type", key="path", expected=".csv, .png, .svg or .pdf",
                                  found=f"'{path.name}'")
        ratio, tw, th = wobbling_curve(project.system)
        if path.suffix.lower() == ".csv":
            np.savetxt(path, np.column_stack([ratio, tw, th]), delimiter=",", fmt="%.12g",
                       header="theta_over_alpha,Tw_p,T_housner_p", comments="")
        else:
            from ..plots import save
            from .figures import wobbling_figure
            curve = {"theta_over_alpha": ratio, "Tw_p": tw, "T_housner_p": th}
            save(wobbling_figure(curve, project.system.tan_alpha), path)

    def simulation_request(self, project, motion, *, model, t_end, rtol, records_dir):
        from . import simulation as cylinder_simulation
        return cylinder_simulation.simulation_request(project, motion, model=model, t_end=t_end, rtol=rtol,
                                                      records_dir=records_dir)

    def run_simulation(self, request):
        from . import simulation as cylinder_simulation
        return cylinder_simulation.run_simulation(request)

    def check_options(self, project, *, records_dir, executor):
        """The cylinder's suites of record pairs are built in: ``records_dir`` is refused; an ``executor`` runs its
        3D analyses (:class:`~rockdesign.cylinder.batch.PairRunner`)."""
        if records_dir is not None:
            raise RockdesignError("not used by the check of a cylinder (built-in suites of record pairs)",
                                  key="records_dir", expected="None",
                                  found=repr(str(records_dir)) if isinstance(records_dir, (str, Path))
                                  else type(records_dir).__name__)

    def check(self, project, *, progress, records_dir, margins, executor):
        from . import check as cylinder_check
        return cylinder_check.cylinder_check(project, progress=progress, margins=margins, executor=executor)

    def report(self, result):
        from .report import cylinder_report_parts
        return cylinder_report_parts(result)

    def spectrum(self, project, request):
        """The rocking spectrum of one record pair over R and PGA (Figs 5.16–5.17;
        :func:`~rockdesign.cylinder.spectrum_run.record_pair_spectrum`)."""
        from . import spectrum_run as cylinder_spectra
        options = request.accepted(self.spectrum_options, "the spectrum of a cylinder (a record pair on R × pga "
                                   "axes)", "record, x R:…, y pga/up:…, relative, out_dir, figures and executor")
        reference = options.get("relative")
        if reference is not None and reference.system.kind not in self.systems:
            raise RockdesignError("a relative cylinder spectrum needs a second cylinder", key="relative",
                                  expected="a [cylinder] project", found=f"a {reference.system.kind}")
        return cylinder_spectra.record_pair_spectrum(project, **options, progress=request.progress, say=request.say)
