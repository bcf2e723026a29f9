"""``simulate`` of a cylinder (thesis Ch. 5): request, analysis, result.

As for a planar structure, a request is parsed and validated in full (:func:`simulation_request`)
before anything is analysed or compiled; :func:`run_simulation` integrates it (Eqs 5.22–5.31).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .engine import SPIN_TILT_MIN, STATUS, CylinderResponse, simulate_cylinder
from .kernel import ST_COMPLETED, ST_OVERTURNED
from .figures import cylinder_history_figure
from .quantities import frequency_parameter
from ..display import format_value
from ..errors import ModelError, RockdesignError
from .pairs import MotionPair, PairSpec, parse_pair
from ..plots import save
from ..project_tables import Project

CYLINDER_MODELS = ("auto", "undamped", "damped")
COMPLETED = (STATUS[ST_COMPLETED], STATUS[ST_OVERTURNED])
"""Statuses of a cylinder analysis that ran to a conclusion (the others: step size collapsed, step limit)."""


@dataclass(frozen=True)
class CylinderSimulation:
    """A cylinder project's response to one motion: ``response`` (:class:`CylinderResponse`: ``t`` [s],
    ``theta`` [rad], ``phi`` [rad], ``theta_max`` [rad], ``quasi_impacts``...; reached as attributes of
    the result too) and the record pair analysed.  ``as_json()`` is the ``simulate --json`` object."""

    project: Project
    motion_text: str
    response: CylinderResponse
    pair: MotionPair | None = None

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.__dict__["response"], name)

    @property
    def warnings(self) -> list[str]:
        return list(self.project.warnings)

    @property
    def failed(self) -> bool:
        """True when the integration did not run to a conclusion (step size collapsed, step limit)."""
        return self.response.status not in COMPLETED

    def as_json(self) -> dict:
        out = self.response.as_json()
        out.update(motion=self.motion_text, project=self.project.name, warnings=self.warnings)
        return out

    def write_csv(self, path) -> None:
        """CSV: t [s], ü_gx, ü_gy [m/s²], θ [rad], θ̇ [rad/s], φ [rad], φ̇ [rad/s] (, w_T [m]), N/(mg) [-]."""
        r = self.response
        cols = [r.t, r.ground_x, r.ground_y, r.theta, r.thetadot, r.phi, r.phidot]
        header = "t_s,ground_x_m_s2,ground_y_m_s2,theta_rad,thetadot_rad_s,phi_rad,phidot_rad_s"
        if r.damped:
            cols.append(r.w_T)
            header += ",w_T_m"
        cols.append(r.contact_force)
        header += ",contact_force_over_weight"
        np.savetxt(path, np.column_stack(cols), delimiter=",", header=header, comments="", fmt="%.12g")

    def write_figure(self, path) -> None:
        """θ(t) and the plan-view orbit (Figs 5.9–5.15) as png/svg/pdf."""
        save(cylinder_history_figure(self.response, self.project.system.g,
                                     f"{self.project.name} — {self.motion_text}", self.pair), path)

    @property
    def summary_caption(self) -> str:
        """The caption under the console summary: what the spin rate φ̇ means and where it is reported."""
        return (f"φ̇ near θ = 0 is the contact point whirling round the rim (quasi-impact, unbounded as θ → 0), "
                f"not a rotation of the body: it is reported where θ ≥ {SPIN_TILT_MIN:g}α")

    def summary_rows(self) -> list[tuple[str, str, str]]:
        """(quantity, value, unit) rows of the console summary of ``simulate``."""
        r = self.response
        j = r.as_json()
        rows = [("model", j["model"], "")]
        pair = self.pair
        if pair is not None and pair.is_record:
            pga = pair.resultant_pga
            g = self.project.system.g
            rows += [("resultant PGA as applied", f"{format_value(pga)} ({pga / g:.4g} g)", "m/s^2"),
                     ("scale (× the records as read)", format_value(pair.scale), "-")]
        spin = r.spin_max()
        rows += [("θ_max", format_value(r.theta_max), "rad"),
                ("θ_max/α", format_value(r.theta_max / r.alpha), "-"),
                ("first uplift", "none" if r.uplift_time is None else format_value(r.uplift_time), "s"),
                ("quasi-impacts", str(r.quasi_impacts), ""),
                (f"max |φ̇| where θ ≥ {SPIN_TILT_MIN:g}α", "—" if spin is None else format_value(spin), "rad/s"),
                ("φ at the end", format_value(j["phi_end"]), "rad"),
                (f"overturned (θ ≥ θ_ot = {r.theta_overturn:.4g} rad)", "YES" if r.overturned else "no", ""),
                ("analysed until", format_value(float(r.t[-1])), "s")]
        if r.damped:
            rows.append(("min contact force N/(m g)", format_value(r.min_contact_force_over_weight), "-"))
        s = r.solver
        rows.append(("solver", f"{s['steps']} steps, {s['rejected_steps']} rejected, {s['rhs_evaluations']} "
                               f"evaluations — {r.status}", ""))
        return rows


@dataclass(frozen=True)
class CylinderRequest:
    """A parsed and validated cylinder ``simulate`` request; nothing has run yet."""

    project: Project
    motion_text: str
    spec: PairSpec
    cylinder: object              # the project's Cylinder, with the contact of ``model``
    rtol: float
    t_end: float | None           # [s] (None: the pair's duration + free vibration)


def _cylinder_for(project: Project, model: str):
    if model not in CYLINDER_MODELS:
        raise ModelError("model does not apply to a cylinder", key="model", expected=" | ".join(CYLINDER_MODELS),
                         found=f"'{model}'")
    cyl = project.system
    if model != "auto":
        cyl = replace(cyl, contact="spring-dashpot" if model == "damped" else "rigid")
    return cyl


def simulation_request(project: Project, motion, *, model: str = "auto", t_end: float | None = None,
                       rtol: float | None = None, records_dir: str | None = None) -> CylinderRequest:
    """Parse a bidirectional motion string (``record:p695-ff/1,resultant_pga=0.3g``, a pulse with
    ``direction=``, ``free:theta0=…``) and check the model, without analysing anything.

    ``model``: ``auto`` (the project's contact), ``undamped`` (rigid contact) or ``damped``
    (spring–dashpot with the project's ω_n, ζ)."""
    cyl = _cylinder_for(project, model)
    if isinstance(motion, MotionPair):
        if records_dir is not None:
            raise RockdesignError("records_dir applies to a motion string", key="records_dir", expected="None",
                                  found=repr(str(records_dir)))
        return CylinderRequest(project, motion.name, PairSpec(motion), cyl, rtol or project.analysis.rtol, t_end)
    if not isinstance(motion, str):
        raise RockdesignError("a cylinder is driven by a pair of components", key="motion",
                              expected="a motion string or a MotionPair (rockdesign.cylinder.pairs)",
                              found=type(motion).__name__)
    if records_dir is None and project.excitation is not None:
        records_dir = project.excitation.records_dir
    spec = parse_pair(motion, gravity=cyl.g, alpha=cyl.alpha, uplift_acceleration=cyl.g * cyl.tan_alpha,
                      p=frequency_parameter(cyl.R, cyl.alpha, cyl.g), records_dir=records_dir)
    return CylinderRequest(project, motion, spec, cyl, rtol or project.analysis.rtol, t_end)


def run_simulation(request: CylinderRequest) -> CylinderSimulation:
    """Integrate a validated request (:func:`simulation_request`)."""
    a, spec = request.project.analysis, request.spec
    response = simulate_cylinder(request.cylinder, spec.pair, t_end=request.t_end, free_vibration=a.free_vibration,
                                 theta0=spec.theta0, thetadot0=spec.thetadot0, phi0=spec.phi0, phidot0=spec.phidot0,
                                 rtol=request.rtol, atol=a.atol, rest_velocity=a.rest_velocity,
                                 output_dt=0.0 if spec.pair.is_record else 0.01)
    return CylinderSimulation(request.project, request.motion_text, response, spec.pair)
