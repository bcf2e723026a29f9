"""The planar kind of structure: solitary columns, rocking frames and rocking podium buildings
(thesis Ch. 3–4): ``[column]`` or ``[podium]`` projects."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .checks import check as planar_check
from .design.geometry import rocking_geometry
from .design.pushover import pushover_curve
from .design.quantities import design_quantities
from ..execution import compilation
from ..errors import RockdesignError
from ..plots import save
from .project import parse_planar_project
from .report.figures import pushover_figure
from ..report import render
from .report.report import write_planar_report
from ..report.results import write_results_csv, write_results_json
from . import grid as planar_grid, simulation as planar_simulation
from ..kinds.base import StructureKind


class Planar(StructureKind):
    """Columns, frames and podiums: the planar engine, the Polyakov check over record suites."""

    name = "planar"
    systems = ("column", "podium")
    simulate_kernels = "simulate"
    check_kernels = "check"
    grid = planar_grid
    design_rule = planar_grid.RULE
    design_skipped = planar_grid.SKIPPED
    grid_shared_batches = True       # every analysis of its check runs through run_jobs

    def claims(self, raw):
        return True            # the default kind: its parser names what is missing ([column] or [podium])

    def parse(self, raw, *, file, text):
        return parse_planar_project(raw, file=file, text=text)

    def quantities(self, project):
        return design_quantities(project.system, project.analysis.rigid_superstructure_ratio)

    def quantities_title(self, project):
        return f"{project.name} — design quantities ({project.system.kind})"

    def write_curve(self, project, path):
        """The pushover curve F_R/(m_C g) against θ through both phases (Fig 3.15, Eqs 3.18/3.48), from
        θ = 0 to θc: a CSV table (``theta_rad, F_R_over_mg, phase``) or, for .png/.svg/.pdf, the report's plot."""
        path = Path(path)
        suffix = path.suffix.lower()
        if suffix == ".csv":
            geo = rocking_geometry(project.system.column)
            theta, force = pushover_curve(geo)
            phase = np.where((geo.radius > 0) & (theta <= geo.beta), 1, 2)
            np.savetxt(path, np.column_stack([theta, force, phase]), delimiter=",", fmt=["%.15g", "%.15g", "%d"],
                       header="theta_rad,F_R_over_mg,phase", comments="")
        elif suffix in (".png", ".svg", ".pdf"):
            save(pushover_figure(project.system), path)
        else:
            raise RockdesignError("unknown pushover file type", key="--pushover",
                                  expected=".csv, .png, .svg or .pdf", found=f"'{path.name}'")

    def simulation_request(self, project, motion, *, model, t_end, rtol, records_dir):
        return planar_simulation.simulation_request(project, motion, model=model, t_end=t_end, rtol=rtol,
                                                    records_dir=records_dir)

    def run_simulation(self, request):
        return planar_simulation.run_simulation(request)

    def simulate_motion(self, project, motion, *, model, t_end, rtol):
        return planar_simulation.simulate_motion(project, motion, model=model, t_end=t_end, rtol=rtol)

    def check_options(self, project, *, records_dir, executor, keys):
        """Every option of the check applies to a planar structure."""

    def prepare_check(self, project, *, records_dir, say, report, pdf_in_process):
        if compilation.missing_kernels(self.check_kernels):   # a first run: an input error in the records stops it first
            planar_check.check_records(project, records_dir)
        # the engine finishes compiling in a helper while the check reads its records (run_check waits)
        compilation.prepare(self.check_kernels, say, background=True)
        if compilation.compilation_pending() and report:      # this process would wait: load the report's libraries
            render.warm_up(pdf=pdf_in_process)

    def check(self, project, *, progress, records_dir, margins, executor):
        return planar_check.run_check(project, records_dir=records_dir, margins=margins, progress=progress, executor=executor)

    def write_report(self, result, folder, *, pdf, html, pdf_worker):
        data = result.as_json()
        write_results_json(data, folder / "results.json")
        write_results_csv(data, folder / "results.csv")
        if pdf or html:
            write_planar_report(result, folder, pdf=pdf, html=html, pdf_worker=pdf_worker)
