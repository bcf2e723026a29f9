"""The library face of the cylinder: ``quantities`` and ``simulate`` for a ``[cylinder]`` project (the
console tables that print them live in rockdesign.cli.cylinder)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from .engine import CylinderResponse, simulate_cylinder
from .quantities import cylinder_quantities, frequency_parameter, quantities_json  # noqa: F401 (re-exported)

CYLINDER_MODELS = ("auto", "undamped", "damped")


def write_wobbling(project, path) -> None:
    """The wobbling-period curve (Fig 5.2): CSV (theta_over_alpha, Tw_p, T_housner_p) or a figure."""
    from pathlib import Path

    from ..errors import RockdesignError
    from .figures import wobbling_figure
    from .quantities import wobbling_curve
    path = Path(path)
    if path.suffix.lower() == ".csv":
        ratio, tw, th = wobbling_curve(project.system)
        np.savetxt(path, np.column_stack([ratio, tw, th]), delimiter=",", fmt="%.12g",
                   header="theta_over_alpha,Tw_p,T_housner_p", comments="")
    elif path.suffix.lower() in (".png", ".svg", ".pdf"):
        from ..plots import save
        save(wobbling_figure(project.system), path)
    else:
        raise RockdesignError("unknown file type", key="--pushover", expected=".csv, .png, .svg or .pdf",
                              found=f"'{path.name}'")


@dataclass(frozen=True)
class CylinderSimulation:
    """A cylinder project's response to one motion string."""

    project: object
    motion_text: str
    response: CylinderResponse
    pair: object = None

    def as_json(self) -> dict:
        out = self.response.as_json()
        out.update(motion=self.motion_text, project=self.project.name, warnings=list(self.project.warnings))
        return out


def simulate_project(project, motion: str, *, model: str = "auto", t_end: float | None = None,
                     rtol: float | None = None, records_dir: str | None = None,
                     before_analysis=None) -> CylinderSimulation:
    """``simulate`` for a cylinder: parse the bidirectional motion string, integrate, return the result.

    ``model``: ``auto`` (the project's contact), ``undamped`` (rigid contact) or ``damped``
    (spring–dashpot with the project's ω_n, ζ).  ``before_analysis()`` is called once the input is
    checked (the CLI compiles the kernels there on a first run)."""
    from dataclasses import replace

    from ..motions.pairs import parse_pair
    cyl = project.system
    if model not in CYLINDER_MODELS:
        raise ModelError("model does not apply to a cylinder", key="--model", expected=" | ".join(CYLINDER_MODELS),
                         found=f"'{model}'")
    if model != "auto":
        cyl = replace(cyl, contact="spring-dashpot" if model == "damped" else "rigid")
    if records_dir is None and project.excitation_raw and "records_dir" in project.excitation_raw:
        records_dir = str(project.excitation_raw["records_dir"])
    spec = parse_pair(motion, gravity=cyl.g, alpha=cyl.alpha, uplift_acceleration=cyl.g * cyl.tan_alpha,
                      p=frequency_parameter(cyl.R, cyl.alpha, cyl.g), records_dir=records_dir)
    a = project.analysis
    if before_analysis is not None:
        before_analysis()
    response = simulate_cylinder(cyl, spec.pair, t_end=t_end, free_vibration=a.free_vibration,
                                 theta0=spec.theta0, thetadot0=spec.thetadot0, phi0=spec.phi0, phidot0=spec.phidot0,
                                 rtol=rtol or a.rtol, atol=a.atol, rest_velocity=a.rest_velocity,
                                 output_dt=0.0 if spec.pair.is_record else 0.01)
    return CylinderSimulation(project, motion, response, spec.pair)


def write_history_csv(response: CylinderResponse, path) -> None:
    """CSV: t [s], ü_gx, ü_gy [m/s²], θ [rad], θ̇ [rad/s], φ [rad], φ̇ [rad/s] (, w_T [m]), N/(mg) [-]."""
    cols = [response.t, response.ground_x, response.ground_y, response.theta, response.thetadot, response.phi,
            response.phidot]
    header = "t_s,ground_x_m_s2,ground_y_m_s2,theta_rad,thetadot_rad_s,phi_rad,phidot_rad_s"
    if response.damped:
        cols.append(response.w_T)
        header += ",w_T_m"
    cols.append(response.contact_force)
    header += ",contact_force_over_weight"
    np.savetxt(path, np.column_stack(cols), delimiter=",", header=header, comments="", fmt="%.12g")
