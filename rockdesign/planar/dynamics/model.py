"""From a typed system to the numba parameter array: which equations, which structure (SPEC §3, §6)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..design.frequencies import frequency_parameter, uplifted_frequency_ratio
from ..design.geometry import rocking_geometry, slenderness_angle
from ..design.quantities import RIGID_SUPERSTRUCTURE_RATIO, coefficient_of_restitution, effective_gamma
from ...errors import ModelError
from ..system import RockingSystem
from .eom import pack_parameters

STRUCTURES = ("auto", "block", "frame", "rigid-superstructure", "podium-2dof")
EQUATIONS = ("exact", "linear")
REST_VELOCITY = 5e-4
"""Default rest threshold |θ̇⁺| [rad/s] below which an impact ends rocking (thesis code, SPEC §3.6)."""
UPLIFT_HYSTERESIS = 1e-9
"""Uplift needs the criterion exceeded by this fraction of g/R (≈ 1e-9 g, SPEC §3.6 chatter guard)."""


@dataclass(frozen=True)
class ModelChoice:
    """The analysed model: structure (how the superstructure is represented) and equations."""

    structure: str      # block | frame | rigid-superstructure | podium-2dof
    equations: str      # exact | linear

    @property
    def label(self) -> str:
        return f"{self.structure}/{self.equations}"


def default_structure(system: RockingSystem, rigid_ratio: float = RIGID_SUPERSTRUCTURE_RATIO) -> tuple[str, str]:
    """(structure, reason): the simplest structural model SPEC §6 allows for ``system``."""
    if system.kind == "column":
        return "block", "solitary column: one rocking body (SDOF)"
    s = system.superstructure
    if s is None:
        return "frame", "no superstructure: rocking frame (SDOF, Eq 3.75)"
    if s.rigid:
        return "rigid-superstructure", "superstructure declared rigid: frame with γ̂ = γ(1+η) (docs/model.md §4)"
    c = system.column
    p = frequency_parameter(math.hypot(c.half_width, c.half_height), c.mass_distribution, system.g)
    ratio = s.omega_s / p
    if ratio >= rigid_ratio:
        return "rigid-superstructure", (f"ω_s/p = {ratio:.3g} ≥ {rigid_ratio:g}: superstructure treated as rigid "
                                        "(Polyakov rule 1; docs/model.md §7: measured −1…−2 % at ω_s/p = 30)")
    return "podium-2dof", (f"ω_s/p = {ratio:.3g} < {rigid_ratio:g}: superstructure flexibility changes the "
                           "overturning acceleration by up to −12 % (docs/model.md §7): 2DOF podium")


def resolve_structure(system: RockingSystem, structure: str, rigid_ratio: float = RIGID_SUPERSTRUCTURE_RATIO) -> str:
    """Validate an explicit structure or resolve ``auto``."""
    if structure == "auto":
        return default_structure(system, rigid_ratio)[0]
    if structure not in STRUCTURES:
        raise ModelError("unknown structural model", key="model", expected=", ".join(STRUCTURES),
                         found=f"'{structure}'")
    ok = {"block": system.kind == "column",
          "frame": system.kind == "podium" and system.superstructure is None,
          "rigid-superstructure": system.kind == "podium" and system.superstructure is not None,
          "podium-2dof": system.has_elastic_superstructure}[structure]
    if not ok:
        raise ModelError(f"structural model '{structure}' does not fit a {system.kind}"
                         + (" with a superstructure" if system.superstructure else ""), key="model",
                         expected="block (column), frame (podium without superstructure), rigid-superstructure or "
                                  "podium-2dof (podium with an elastic superstructure)", found=f"'{structure}'")
    return structure


def analysed_system(system: RockingSystem, structure: str) -> RockingSystem:
    """The system the equations see: the rigid-superstructure model moves m_T onto the cap beam."""
    if structure == "rigid-superstructure":
        return system.with_rigid_superstructure()
    return system


def system_parameters(system: RockingSystem, choice: ModelChoice, *, rest_velocity: float = REST_VELOCITY,
                      overturn_angle: float = math.pi / 2) -> np.ndarray:
    """The ``sp`` array of :mod:`rockdesign.planar.dynamics.eom` for ``system`` analysed with ``choice``."""
    model_sys = analysed_system(system, choice.structure)
    c = system.column
    geo = rocking_geometry(c)
    linear = choice.equations == "linear"
    beta = geo.beta
    two_rho = 0.0
    if c.extension == "curved":
        rho = c.curvature
        # The linear model keeps the wedge angle β of Eq 3.44 (as the thesis's Code B.2): with the
        # linearized β = (α'−α)/(2ρ), Table 3.4's B3/B4 linear values (SPEC §6: B4 1.594) do not
        # reproduce (1.160, 1.586 instead of 1.1557, 1.5945).
        two_rho = 2.0 * rho
    two_dof = choice.structure == "podium-2dof"
    c_r, _ = coefficient_of_restitution(system)
    omega = zeta = 0.0
    eta = 0.0
    gamma = model_sys.gamma
    if two_dof:
        s = system.superstructure
        eta = system.eta
        omega = s.omega_s
        zeta = s.damping
        if s.damping_correction:
            zeta /= uplifted_frequency_ratio(c.mass_distribution, system.gamma, system.eta,
                                             slenderness_angle(c.half_width, c.half_height))
    elif choice.structure == "rigid-superstructure":
        gamma = effective_gamma(system)
    return pack_parameters(dict(
        r=geo.R, alpha=geo.alpha, radius=geo.radius, beta=beta, lam=geo.lam, gamma=gamma, eta=eta,
        g=system.g, omega=omega, zeta=zeta, cr=c_r, linear=1.0 if linear else 0.0, theta_c=geo.theta_c,
        overturn=overturn_angle, rest_v=rest_velocity, two_dof=1.0 if two_dof else 0.0,
        hyst=UPLIFT_HYSTERESIS * system.g / geo.R, two_rho=two_rho))
