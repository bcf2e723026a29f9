"""The library API a user calls from a notebook; the CLI is a thin layer over it.

    >>> from rockdesign.api import load_project, design_quantities
    >>> proj = load_project("examples/podium_flat.toml")
    >>> design_quantities(proj.system)["theta_c"].value
"""
from __future__ import annotations

from .design.quantities import design_quantities
from .project import Project, load_project

__all__ = ["load_project", "design_quantities", "quantities_json", "quantities_table"]


def quantities_json(project: Project) -> dict:
    """The ``quantities --json`` object of CONTRACT §3 (SI values)."""
    if project.system.kind == "cylinder":                   # the 3D cylinder (thesis Ch. 5)
        from .cylinder.commands import quantities_json as cylinder_json
        return cylinder_json(project)
    q = design_quantities(project.system, project.analysis.rigid_superstructure_ratio)
    return {"quantities": {name: x.as_json() for name, x in q.items()}, "warnings": list(project.warnings)}


def write_pushover(system, path) -> None:
    """The pushover curve F_R/(m_C g) against θ through both phases (Fig 3.15, Eqs 3.18/3.48), from θ = 0
    to θc: a CSV table (``theta_rad, F_R_over_mg, phase``) or, for .png/.svg/.pdf, the report's plot."""
    from pathlib import Path

    import numpy as np

    from .design.geometry import rocking_geometry
    from .design.pushover import pushover_curve
    from .errors import RockdesignError
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".csv":
        geo = rocking_geometry(system.column)
        theta, force = pushover_curve(geo)
        phase = np.where((geo.radius > 0) & (theta <= geo.beta), 1, 2)
        np.savetxt(path, np.column_stack([theta, force, phase]), delimiter=",", fmt=["%.15g", "%.15g", "%d"],
                   header="theta_rad,F_R_over_mg,phase", comments="")
    elif suffix in (".png", ".svg", ".pdf"):
        from .report.figures import pushover_figure
        from .plots import save
        save(pushover_figure(system), path)
    else:
        raise RockdesignError("unknown pushover file type", key="--pushover", expected=".csv, .png, .svg or .pdf",
                              found=f"'{path.name}'")


def quantities_table(project: Project, console, units: str | None = None) -> None:
    """Print the design quantities of a project as a table."""
    from .display import quantities_table as _table
    _table(design_quantities(project.system, project.analysis.rigid_superstructure_ratio), console, units, project.system.g,
           f"{project.name} — design quantities ({project.system.kind})", project.warnings)


# --- time-history analysis -------------------------------------------------------------------
from dataclasses import dataclass  # noqa: E402

from .dynamics.response import Response  # noqa: E402
from .dynamics.simulate import simulate  # noqa: E402
from .motions.parse import MotionSpec  # noqa: E402


@dataclass(frozen=True)
class SimulationResult:
    """A project's response to one motion string, with what was analysed."""

    project: Project
    motion_text: str
    response: Response
    motion_parameters: dict | None = None     # resolved pulse parameters (SI): a_p [m/s²], T_p [s], t_m/t_0 [s]
    motion_warnings: tuple[str, ...] = ()

    @property
    def warnings(self) -> list[str]:
        return list(self.project.warnings) + list(self.motion_warnings)

    def as_json(self) -> dict:
        out = self.response.as_json()
        out["motion"] = self.motion_text
        if self.motion_parameters:
            out["motion_parameters"] = dict(self.motion_parameters)
        out["project"] = self.project.name
        out["warnings"] = self.warnings
        return out


def model_for_project(project: Project, model: str = "auto") -> tuple[str, str]:
    """(model, structure) for ``simulate`` from the CLI ``--model`` and the project's [analysis].

    ``auto`` follows ``[analysis] equations`` (auto → exact) and ``[analysis] model`` (auto → the
    simplest adequate structure of SPEC §6).
    """
    a = project.analysis
    structure = a.model
    if model == "auto":
        model = "linear" if a.equations == "linear" else "exact"
    return model, structure


@dataclass(frozen=True)
class SimulationRequest:
    """A parsed and validated ``simulate`` request (:func:`simulation_request`); nothing has run yet."""

    project: Project
    motion_text: str
    spec: "MotionSpec"            # the parsed motion and its initial state
    model: str                    # exact | linear | linear-exact
    structure: str                # the resolved structural model (SPEC §6)
    rtol: float
    t_end: float                  # [s]


def simulation_request(project: Project, motion: str, *, model: str = "auto", t_end: float | None = None,
                       rtol: float | None = None, records_dir: str | None = None) -> SimulationRequest:
    """Parse a CONTRACT §2 motion string and validate everything :func:`run_simulation` needs, without
    analysing (or compiling) anything: bad input is reported at once, also on a first run."""
    if project.system.kind == "cylinder":
        from .errors import RockdesignError
        raise RockdesignError("a cylinder project is simulated by rockdesign.cylinder.commands.simulate_project",
                              key="project", expected="a planar system", found="a cylinder")
    from .dynamics.simulate import check_request
    from .motions.parse import parse_motion, system_scales
    system = project.system
    if records_dir is None and project.excitation_raw and "records_dir" in project.excitation_raw:
        records_dir = str(project.excitation_raw["records_dir"])
    spec = parse_motion(motion, system_scales(system), records_dir=records_dir)
    eq, structure = model_for_project(project, model)
    a = project.analysis
    structure, t_end = check_request(system, spec.motion, model=eq, structure=structure,
                                     t_end=t_end if t_end is not None else spec.motion.duration + a.free_vibration,
                                     overturn=a.overturn, rigid_ratio=a.rigid_superstructure_ratio)
    return SimulationRequest(project, motion, spec, eq, structure, rtol or a.rtol, t_end)


def run_simulation(request: SimulationRequest) -> SimulationResult:
    """Analyse a validated request (:func:`simulation_request`)."""
    project, spec = request.project, request.spec
    a = project.analysis
    response = simulate(project.system, spec.motion, model=request.model, structure=request.structure,
                        rtol=request.rtol, atol=a.atol, t_end=request.t_end, theta0=spec.theta0,
                        thetadot0=spec.thetadot0, overturn=a.overturn, rest_velocity=a.rest_velocity,
                        rigid_ratio=a.rigid_superstructure_ratio)
    from .motions.measures import plausibility_warnings
    m = spec.motion
    params = ({k: float(m.meta[k]) for k in ("a_p", "T_p", "t_m", "t_0") if k in m.meta}
              if not m.is_record and "a_p" in m.meta else None)
    return SimulationResult(project, request.motion_text, response, params,
                            tuple(plausibility_warnings(m, project.system.g)))


def simulate_project(project: Project, motion: str, *, model: str = "auto", t_end: float | None = None,
                     rtol: float | None = None, records_dir: str | None = None) -> SimulationResult:
    """Run ``simulate`` for a project and a CONTRACT §2 motion string."""
    if project.system.kind == "cylinder":                   # the 3D cylinder (thesis Ch. 5)
        from .cylinder.commands import simulate_project as simulate_cylinder_project
        return simulate_cylinder_project(project, motion, model=model, t_end=t_end, rtol=rtol, records_dir=records_dir)
    return run_simulation(simulation_request(project, motion, model=model, t_end=t_end, rtol=rtol,
                                             records_dir=records_dir))


def write_history_csv(response: Response, path) -> None:
    """Time history as CSV: t [s], ag [m/s²], theta [rad], thetadot [rad/s], u_B, u_T, u_T−u_B [m]; a 2DOF
    podium adds ``a_T_abs`` (the superstructure's absolute acceleration −f_s [m/s²], SPEC §13) and ``drift``
    (u_T − u_B [m]) — the column names of CONTRACT §6.2."""
    import numpy as np
    columns = [response.t, response.ground_acceleration, response.theta, response.thetadot, response.u_B,
               response.u_T, response.u_rel]
    header = "t_s,ground_acceleration_m_s2,theta_rad,thetadot_rad_s,u_B_m,u_T_m,u_T_minus_u_B_m"
    if response.a_T_abs is not None:
        columns += [response.a_T_abs, response.u_rel]
        header += ",a_T_abs,drift"
    data = np.column_stack(columns)
    np.savetxt(path, data, delimiter=",", header=header, comments="", fmt="%.10g")
