"""Closed-form quantities the reference integrator needs, computed from SPEC §2 alone.

Deliberately independent of ``rockdesign.planar.design`` and ``rockdesign.planar.dynamics``: the reference
implementation must not share code with the engine it checks.  Every function takes plain numbers
(SI, radians); :func:`model_parameters` collects them for one :class:`~rockdesign.planar.system.RockingSystem`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from rockdesign.planar.system import RockingSystem

RESTITUTION_RULES = ("theory", "measured", "thesis-eq-3.39")


def frequency_parameter(R: float, lam: float, g: float = 9.81) -> float:
    """p = √(g/(R(1+λ))) [1/s] of a solitary block of size R [m] (Eq 3.13)."""
    return math.sqrt(g / (R * (1.0 + lam)))


def frame_frequency_parameter(R: float, lam: float, gamma: float, g: float = 9.81) -> float:
    """p̂ = √((1+2γ)/(1+λ+4γ) · g/R) [1/s] of a rocking frame (Eq 3.76)."""
    return math.sqrt((1.0 + 2.0 * gamma) / (1.0 + lam + 4.0 * gamma) * g / R)


def wedge_angle(tan_alpha: float, tan_alpha_ext: float, rho: float, linear: bool = False) -> float:
    """β [rad] separating rolling from rocking (Eq 3.44; linearized (α'−α)/(2ρ)).

    Raises ValueError when 2ρ < tan α' − tan α (the extension cannot be a circular arc tangent to
    the flat base; the printed validity condition of Eq 3.44 is reversed, SPEC §8).
    """
    if linear:
        return (math.atan(tan_alpha_ext) - math.atan(tan_alpha)) / (2.0 * rho)
    x = (tan_alpha_ext - tan_alpha) / (2.0 * rho)
    if x > 1.0:
        raise ValueError(f"curved extension impossible: 2ρ = {2 * rho:.6g} < tan α' − tan α = "
                         f"{tan_alpha_ext - tan_alpha:.6g} (Eq 3.44)")
    return math.asin(x)


def critical_curvature(tan_alpha: float, tan_alpha_ext: float) -> float:
    """ρc = ½(1 − tan α/tan α') (Eq 3.55)."""
    return 0.5 * (1.0 - tan_alpha / tan_alpha_ext)


def rotation_capacity(tan_alpha: float, tan_alpha_ext: float, rho: float, extension: str) -> float:
    """θc [rad]: tilt at which the static restoring force vanishes (corrected Eq 3.56, SPEC §2).

    ``extension`` is ``"none"`` (θc = α), ``"flat"`` (θc = α') or ``"curved"`` (the first zero of F_R, in
    the phase where it lies: docs/model.md §2).
    """
    if extension == "none":
        return math.atan(tan_alpha)
    if extension == "flat":
        return math.atan(tan_alpha_ext)
    if rho <= critical_curvature(tan_alpha, tan_alpha_ext):
        return math.atan(tan_alpha / (1.0 - 2.0 * rho))
    beta = wedge_angle(tan_alpha, tan_alpha_ext, rho)
    rolling_root = math.atan2(tan_alpha, 1.0 - 2.0 * rho)   # N = 0 of Eq 3.48 (phase I)
    if rolling_root <= beta:      # just above ρc with the exact β: F_R vanishes before the rocking phase
        return rolling_root
    return math.atan(tan_alpha_ext / (1.0 - 2.0 * rho * (1.0 - math.cos(beta))))


def housner_restitution(sin2_alpha: float, lam: float, gamma_hat: float = 0.0) -> float:
    """c_r = (1 − 2 sin²α (1+4γ̂)/(1+λ+4γ̂))² (Eq 3.14 for γ̂ = 0, Eq 3.80 frame, Eq 4.20 podium
    with γ̂ = γ(1+η))."""
    return (1.0 - 2.0 * sin2_alpha * (1.0 + 4.0 * gamma_hat) / (1.0 + lam + 4.0 * gamma_hat)) ** 2


def restitution_coefficient(system: RockingSystem, rule: str | float | None = None) -> float:
    """Coefficient of restitution c_r = (θ̇⁺/θ̇⁻)² of ``system`` (SPEC §2).

    Args:
        system: the rocking system.
        rule: None (use ``system.restitution`` if given, else ``system.restitution_rule``),
            ``"theory"`` (CoAM: Eqs 3.14/3.80/4.20 with α; flat extensions CoAM about pivots 2B'
            apart, (1 − 2 sin²α'(1+4γ̂)/(1+λ'+4γ̂))²), ``"thesis-eq-3.39"`` (the printed flat
            extension formula with sin²α, reproduces Table 3.4) or a number (imposed c_r).
    """
    if rule is None:
        if system.restitution is not None:
            return float(system.restitution)
        rule = system.restitution_rule
    if not isinstance(rule, str):
        return float(rule)
    if rule == "measured":
        raise ValueError("restitution_rule 'measured' needs system.restitution (a measured c_r)")
    if rule not in RESTITUTION_RULES:
        raise ValueError(f"unknown restitution rule {rule!r}; expected one of {RESTITUTION_RULES}")
    col = system.column
    alpha = math.atan(col.tan_alpha)
    gamma_hat = (system.cap_beam_mass + _superstructure_mass(system)) / (system.n_columns * col.mass)
    lam = col.mass_distribution
    if col.extension != "flat":
        return housner_restitution(math.sin(alpha) ** 2, lam, gamma_hat)
    alpha_ext = math.atan(col.tan_alpha_ext)
    lam_ext = lam * math.cos(alpha_ext) ** 2 / math.cos(alpha) ** 2
    sin_used = math.sin(alpha) if rule == "thesis-eq-3.39" else math.sin(alpha_ext)
    return housner_restitution(sin_used ** 2, lam_ext, gamma_hat)


def _superstructure_mass(system: RockingSystem) -> float:
    return 0.0 if system.superstructure is None else system.superstructure.mass


@dataclass(frozen=True)
class ModelParameters:
    """Everything the reference equations of motion need, in SI units and radians.

    Attributes:
        R: size R = √(B²+H²) of the column [m] (the R of the generic equation, SPEC §3.1).
        lam: λ = I_C/(m_C R²).
        alpha, alpha_ext: α = atan(B/H), α' = atan(B'/H) [rad] (α' = α without extensions).
        extension: ``"none"``, ``"flat"`` or ``"curved"``.
        R_kin, alpha_kin: size and angle of the rocking kinematics (R', α' for flat extensions).
        radius, rho, beta: r [m], ρ = r/(2H), β [rad] (curved extensions; linearized β if ``linear``).
        gamma: γ = m_B/(N m_C); gamma_eta: γη = m_T/(N m_C) of an elastic superstructure (else 0).
        omega_s: ω_s [rad/s] of an elastic superstructure (0 without); zeta: damping ratio used in
            the equations (ζ_s/S_r with the damping correction, SPEC §2).
        g: gravity [m/s²]; linear: first-order equations (SPEC §3.2); c_r: restitution.
        uplift_angle: α used in the uplift criterion (α' for flat extensions).
        theta_c: capacity θc [rad] (exact, Eq 3.56, used for the "exceeded" flag in both modes).
    """

    R: float
    lam: float
    alpha: float
    alpha_ext: float
    extension: str
    R_kin: float
    alpha_kin: float
    radius: float
    rho: float
    beta: float
    gamma: float
    gamma_eta: float
    omega_s: float
    zeta: float
    g: float
    linear: bool
    c_r: float
    uplift_angle: float
    theta_c: float

    @property
    def elastic(self) -> bool:
        """True for a podium with an elastic superstructure (2DOF after uplift)."""
        return self.gamma_eta > 0.0

    @property
    def curved(self) -> bool:
        return self.extension == "curved"


def model_parameters(system: RockingSystem, linear: bool = False,
                     restitution: str | float | None = None,
                     linear_beta: str = "linearized") -> ModelParameters:
    """Collect the parameters of ``system`` for the reference equations (SPEC §1–§2).

    ``linear_beta`` chooses β of a linearized curved base: ``"linearized"`` (α'−α)/(2ρ) as SPEC §3.2
    prescribes, or ``"exact"`` asin((tan α' − tan α)/(2ρ)) as the thesis code (Code B.2) and the
    linear values in the notes of cases.json tab3.4_B3ec/B4ec use.

    A rigid superstructure (ω_s = inf) must already be folded into the cap beam
    (``system.with_rigid_superstructure()``, SPEC §3.3).
    """
    col = system.column
    H, B = col.half_height, col.half_width
    R = math.hypot(B, H)
    alpha = math.atan(col.tan_alpha)
    ext = col.extension
    if ext not in ("none", "flat", "curved"):
        raise ValueError(f"unknown extension {ext!r}")
    alpha_ext = math.atan(col.tan_alpha_ext) if ext != "none" else alpha
    R_kin, alpha_kin = R, alpha
    if ext == "flat":
        R_kin, alpha_kin = H / math.cos(alpha_ext), alpha_ext
    radius = rho = beta = 0.0
    if ext == "curved":
        radius = col.radius
        rho = radius / (2.0 * H)
        if linear_beta not in ("linearized", "exact"):
            raise ValueError(f"linear_beta must be 'linearized' or 'exact', not {linear_beta!r}")
        beta = wedge_angle(col.tan_alpha, col.tan_alpha_ext, rho, linear=linear and linear_beta == "linearized")
    n_mc = system.n_columns * col.mass
    gamma = system.cap_beam_mass / n_mc
    sup = system.superstructure
    gamma_eta = omega_s = zeta = 0.0
    if sup is not None:
        if sup.rigid:
            raise ValueError("rigid superstructure: use system.with_rigid_superstructure() (SPEC §3.3)")
        gamma_eta = sup.mass / n_mc
        omega_s = sup.omega_s
        zeta = sup.damping
        if sup.damping_correction and zeta != 0.0:
            zeta /= uplifted_frequency_ratio(col, gamma, gamma_eta)
    return ModelParameters(
        R=R, lam=col.mass_distribution, alpha=alpha, alpha_ext=alpha_ext, extension=ext,
        R_kin=R_kin, alpha_kin=alpha_kin, radius=radius, rho=rho, beta=beta, gamma=gamma,
        gamma_eta=gamma_eta, omega_s=omega_s, zeta=zeta, g=system.g, linear=linear,
        c_r=restitution_coefficient(system, restitution),
        uplift_angle=alpha_ext if ext == "flat" else alpha,
        theta_c=rotation_capacity(col.tan_alpha, col.tan_alpha_ext, rho, ext))


def uplifted_frequency_ratio(column, gamma: float, gamma_eta: float) -> float:
    """S_r of Eq 4.25 for ``column`` with γ and γη = m_T/(N m_C); flat extensions use α', λ'."""
    alpha = math.atan(column.tan_alpha)
    lam = column.mass_distribution
    if column.extension == "flat":
        alpha_ext = math.atan(column.tan_alpha_ext)
        lam = lam * math.cos(alpha_ext) ** 2 / math.cos(alpha) ** 2
        alpha = alpha_ext
    s2 = math.sin(alpha) ** 2
    return math.sqrt((1.0 + lam + 4.0 * gamma + 4.0 * gamma_eta) / (1.0 + lam + 4.0 * gamma + 4.0 * gamma_eta * s2))


def uplift_thresholds(params: ModelParameters, shear: float = 0.0) -> tuple[float, float]:
    """Ground accelerations (lower, upper) [m/s²] at which the body uplifts from rest (Eq 4.7).

    Uplift to θ > 0 when ü_g ≤ lower, to θ < 0 when ü_g ≥ upper, with
    lower = −A + k(−A + f), upper = A + k(A + f), A = g tan α (g α when linearized; α' for flat
    extensions), k = 2γη/(2γ+1) and f = ω_s² u_T + 2ζ_s ω_s u̇_T = ``shear`` (the superstructure base
    shear per unit top mass; 0 without an elastic superstructure, giving ∓g tan α).
    """
    angle = params.uplift_angle
    A = params.g * (angle if params.linear else math.tan(angle))
    if params.gamma_eta == 0.0:
        return -A, A
    k = 2.0 * params.gamma_eta / (2.0 * params.gamma + 1.0)
    return -A + k * (-A + shear), A + k * (A + shear)
