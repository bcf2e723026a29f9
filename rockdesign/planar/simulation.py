"""``simulate`` of a planar structure (column, frame, podium): request, analysis, result.

A request is parsed and validated in full (:func:`simulation_request`) before anything is analysed
or compiled, so bad input is reported at once, also on a first run; :func:`run_simulation` analyses
it (thesis Eq 3.12 / 3.46 / 4.13 and the impact maps).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..display import format_value
from ..errors import RockdesignError
from .dynamics.layout import COMPLETED_STATUSES, STATUS_NAMES
from .dynamics.response import Response
from .dynamics.simulate import check_request, simulate
from ..motions.measures import plausibility_warnings
from ..motions.motion import GroundMotion
from .design.quantities import design_quantities
from ..motions.parse import MotionSpec, SystemScales, parse_motion
from ..plots import save
from ..project_tables import Project
from .report.history import time_history_figure

COMPLETED = tuple(STATUS_NAMES[code] for code in COMPLETED_STATUSES)
"""Engine statuses of an analysis that ran to a conclusion (docs/engine.md)."""


@dataclass(frozen=True)
class SimulationResult:
    """One time-history analysis of a planar project: the response and what was analysed.

    Arrays: ``t`` [s], ``theta`` [rad], ``thetadot`` [rad/s], ``u_B`` (column top) [m], ``u_T``
    (superstructure, relative to the ground) [m], ``ground_acceleration`` [m/s²].  Scalars:
    ``theta_max`` [rad], ``theta_max_over_alpha`` [-], ``theta_max_over_theta_c`` [-], ``u_B_max`` [m],
    ``uplift_time`` [s] (None without uplift), ``impacts``, ``overturned``, ``overturn_mode``; every
    other attribute of :class:`rockdesign.planar.dynamics.response.Response` is reached the same way.
    ``as_json()`` is the ``simulate --json`` object.
    """

    project: Project
    motion_text: str
    response: Response
    motion_parameters: dict | None = None     # resolved pulse parameters (SI): a_p [m/s²], T_p [s], t_m/t_0 [s]
    motion_warnings: tuple[str, ...] = ()
    motion_record: dict | None = None         # a record as applied: pga [m/s²] (after scale), scale on the raw record

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

    @property
    def warnings(self) -> list[str]:
        return list(self.project.warnings) + list(self.motion_warnings)

    @property
    def failed(self) -> bool:
        """True when the engine did not run the analysis to a conclusion: θ_max is then not a result."""
        return self.response.status not in COMPLETED

    def as_json(self) -> dict:
        out = self.response.as_json()
        out["motion"] = self.motion_text
        if self.motion_parameters:
            out["motion_parameters"] = dict(self.motion_parameters)
        out["project"] = self.project.name
        out["warnings"] = self.warnings
        return out

    def write_csv(self, path) -> None:
        """Time history as CSV: t [s], ag [m/s²], theta [rad], thetadot [rad/s], u_B, u_T, u_T−u_B [m]; a 2DOF
        podium adds ``a_T_abs`` (the superstructure's absolute acceleration −f_s [m/s²], SPEC §13) and ``drift``
        (u_T − u_B [m]) — the column names of CONTRACT §6.2."""
        r = self.response
        columns = [r.t, r.ground_acceleration, r.theta, r.thetadot, r.u_B, r.u_T, r.u_rel]
        header = "t_s,ground_acceleration_m_s2,theta_rad,thetadot_rad_s,u_B_m,u_T_m,u_T_minus_u_B_m"
        if r.a_T_abs is not None:
            columns += [r.a_T_abs, r.u_rel]
            header += ",a_T_abs,drift"
        data = np.column_stack(columns)
        np.savetxt(path, data, delimiter=",", header=header, comments="", fmt="%.10g")

    def write_figure(self, path) -> None:
        """The time-history figure (ground acceleration, θ/α, drifts) as png/svg/pdf."""
        save(time_history_figure(self.response, self.project.system.g, f"{self.project.name} — {self.motion_text}"),
             path)

    def summary_rows(self) -> list[tuple[str, str, str]]:
        """(quantity, value, unit) rows of the console summary of ``simulate``."""
        r = self.response
        rows = [
            ("model", model_label(r.model, self.project.system), ""),
            ("θ_max", format_value(r.theta_max), "rad"),
            ("θ_max/α", format_value(r.theta_max_over_alpha), "-"),
            ("θ_max/θc", format_value(r.theta_max_over_theta_c), "-"),
            ("u_B,max (column top)", format_value(r.u_B_max), "m"),
            ("u_B,max / capacity", format_value(r.u_B_max_over_capacity), "-"),
            ("first uplift", "none" if r.uplift_time is None else format_value(r.uplift_time), "s"),
            ("time uplifted", format_value(r.time_uplifted), "s"),
            ("impacts", str(r.impacts), ""),
            ("overturn mode", r.overturn_mode, ""),
            (f"overturned ({r.overturn_criterion} criterion)", "YES" if r.overturned else "no", ""),
            ("analysed until", format_value(r.t_end), "s"),
            ("solver", f"{r.diagnostics['steps']} steps, {r.diagnostics['rejected_steps']} rejected, "
                       f"{r.diagnostics['function_evaluations']} evaluations, {r.diagnostics['events']} events — "
                       f"{r.status}", ""),
        ]
        if r.drift_max:
            rows.insert(5, ("max |u_T − u_B| (sampled)", format_value(r.drift_max), "m"))
        at = next(i for i, row in enumerate(rows) if row[0] == "u_B,max / capacity") + 1
        rows[at:at] = demand_rows(r, self.project.system.g)
        params = self.motion_parameters
        if params:
            g = self.project.system.g
            extra = [("pulse amplitude a_p", f"{format_value(params['a_p'])} ({params['a_p'] / g:.4g} g)", "m/s^2"),
                     ("pulse period T_p", format_value(params["T_p"]), "s")]
            if "t_m" in params:
                extra.append(("wavelet centre t_m", format_value(params["t_m"]), "s"))
            rows[1:1] = extra
        record = self.motion_record
        if record:
            g = self.project.system.g
            rows[1:1] = [("record PGA as applied", f"{format_value(record['pga'])} ({record['pga'] / g:.4g} g)",
                          "m/s^2"),
                         ("scale (× the record as read)", format_value(record["scale"]), "-")]
        return rows


def model_for_project(project: Project, model: str = "auto") -> tuple[str, str]:
    """(model, structure) for ``simulate`` from ``model`` and the project's [analysis].

    ``auto`` follows ``[analysis] equations`` (auto → exact) and ``[analysis] model`` (auto → the
    simplest adequate structure of SPEC §6).
    """
    a = project.analysis
    if model == "auto":
        model = "linear" if a.equations == "linear" else "exact"
    return model, a.model


@dataclass(frozen=True)
class SimulationRequest:
    """A parsed and validated planar ``simulate`` request (:func:`simulation_request`); nothing has run yet."""

    project: Project
    motion_text: str
    spec: MotionSpec              # the parsed motion and its initial state
    model: str                    # exact | linear | linear-exact
    structure: str                # the resolved structural model (SPEC §6)
    rtol: float
    t_end: float                  # [s]


def simulation_request(project: Project, motion, *, model: str = "auto", t_end: float | None = None,
                       rtol: float | None = None, records_dir: str | None = None) -> SimulationRequest:
    """Parse a CONTRACT §2 motion string (or take a :class:`~rockdesign.motions.motion.GroundMotion`) and
    validate everything :func:`run_simulation` needs, without analysing (or compiling) anything."""
    system = project.system
    if isinstance(motion, GroundMotion):
        if records_dir is not None:
            raise RockdesignError("records_dir applies to a motion string", key="records_dir", expected="None",
                                  found=repr(str(records_dir)))
        spec, text = MotionSpec(motion, text=motion.name), motion.name
    elif isinstance(motion, str):
        if records_dir is None and project.excitation is not None and project.excitation.records_dir is not None:
            records_dir = str(project.excitation.records_dir)
        spec, text = parse_motion(motion, system_scales(system), records_dir=records_dir), motion
    else:
        raise RockdesignError("unknown motion", key="motion", expected="a motion string or a GroundMotion",
                              found=type(motion).__name__)
    eq, structure = model_for_project(project, model)
    a = project.analysis
    structure, t_end = check_request(system, spec.motion, model=eq, structure=structure,
                                     t_end=t_end if t_end is not None else spec.motion.duration + a.free_vibration,
                                     overturn=a.overturn, rigid_ratio=a.rigid_superstructure_ratio)
    return SimulationRequest(project, text, spec, eq, structure, rtol or a.rtol, t_end)


def run_simulation(request: SimulationRequest) -> SimulationResult:
    """Analyse a validated request (:func:`simulation_request`)."""
    project, spec = request.project, request.spec
    a = project.analysis
    response = simulate(project.system, spec.motion, model=request.model, structure=request.structure,
                        rtol=request.rtol, atol=a.atol, t_end=request.t_end, theta0=spec.theta0,
                        thetadot0=spec.thetadot0, overturn=a.overturn, rest_velocity=a.rest_velocity,
                        rigid_ratio=a.rigid_superstructure_ratio)
    m = spec.motion
    params = ({k: float(m.meta[k]) for k in ("a_p", "T_p", "t_m", "t_0") if k in m.meta}
              if not m.is_record and "a_p" in m.meta else None)
    record = {"pga": float(m.pga), "scale": float(m.meta.get("scale", 1.0))} if m.is_record else None
    return SimulationResult(project, request.motion_text, response, params,
                            tuple(plausibility_warnings(m, project.system.g)), record)


def system_scales(system) -> SystemScales:
    """The reference values of relative units for ``system`` (α, g tan α, p, p̂, g)."""
    q = design_quantities(system)
    p_hat = q["p_hat"].value if "p_hat" in q else q["p"].value
    return SystemScales(q["alpha"].value, q["uplift_acceleration"].value, q["p"].value, p_hat, system.g)


def model_label(model: str, system) -> str:
    """The analysed model as a reader names it: ``block/exact`` of a column on curved feet is
    "block/exact (column on curved extensions, exact equations)"."""
    structure, _, equations = model.partition("/")
    if structure == "block":
        ext = getattr(system.column, "extension", "none")
        what = {"curved": "column on curved extensions", "flat": "column on flat extensions"}.get(ext, "flat-based column")
    else:
        what = {"frame": "frame of columns under a cap beam", "rigid-superstructure": "frame with a rigid superstructure",
                "podium-2dof": "podium with an elastic superstructure (2DOF)"}.get(structure, structure)
    eq = {"exact": "exact equations", "linear": "linearized equations",
          "linear-exact": "linearized equations, closed-form solution"}.get(equations, equations)
    return f"{model} ({what}, {eq})" if equations else f"{model} ({what})"


def demand_rows(r, g: float) -> list[tuple[str, str, str]]:
    """Rows of the superstructure demand of a simulate response (2DOF podium: peak absolute acceleration of
    the superstructure, the fixed-base reference and their ratio; rigid masses: the cap beam), SPEC §13."""
    rows = []
    until = " (until overturning)" if r.overturned else ""
    if r.superstructure_acceleration_max is not None:
        a = r.superstructure_acceleration_max
        rows.append(("superstructure max |a_T| (abs.)" + until, f"{format_value(a)} ({a / g:.4g} g)", "m/s²"))
        if r.fixed_base_acceleration_max:
            f = r.fixed_base_acceleration_max
            rows.append(("same on a fixed base", f"{format_value(f)} ({f / g:.4g} g)", "m/s²"))
            rows.append(("force ratio rocking / fixed base", format_value(a / f), "-"))
    elif r.cap_acceleration_max is not None:
        rows.append(("cap beam max |a| between impacts" + until, format_value(r.cap_acceleration_max), "m/s²"))
        rows.append(("cap beam max velocity jump (impact)", format_value(r.cap_velocity_jump_max), "m/s"))
    return rows
