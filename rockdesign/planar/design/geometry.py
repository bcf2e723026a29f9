"""Column geometry: slenderness, size, extensions, wedge angle, critical curvature, capacity (SPEC §2).

Pure functions of plain floats (SI: m, rad).  ``Column``-level helpers at the bottom.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .kinematics import centre_kinematics
from ..system import Column


def slenderness_angle(half_width: float, half_height: float) -> float:
    """α = atan(B/H) [rad] (Eq 2.1)."""
    return math.atan2(half_width, half_height)


def half_diagonal(half_width: float, half_height: float) -> float:
    """R = √(B² + H²) [m] (Eq 2.2)."""
    return math.hypot(half_width, half_height)


def wedge_angle(tan_alpha: float, tan_alpha_ext: float, rho: float) -> float:
    """β = asin((tan α' − tan α)/(2ρ)) [rad] (Eq 3.44; valid only if 2ρ ≥ tan α' − tan α, SPEC §8)."""
    x = (tan_alpha_ext - tan_alpha) / (2.0 * rho)
    if x > 1.0 + 1e-12:
        raise ValueError(f"curved extension impossible: 2ρ = {2 * rho:.6g} < tan α' − tan α = "
                         f"{tan_alpha_ext - tan_alpha:.6g} (Eq 3.44)")
    return math.asin(min(x, 1.0))


def wedge_angle_linear(alpha: float, alpha_ext: float, rho: float) -> float:
    """Linearized β = (α' − α)/(2ρ) [rad] (Eq 3.44 to first order)."""
    return (alpha_ext - alpha) / (2.0 * rho)


def critical_curvature(tan_alpha: float, tan_alpha_ext: float) -> float:
    """ρc = ½(1 − tan α/tan α') [-] (Eq 3.55): zero post-uplift stiffness in the rolling phase."""
    return 0.5 * (1.0 - tan_alpha / tan_alpha_ext)


def critical_curvature_linear(alpha: float, alpha_ext: float) -> float:
    """Linearized ρc = ½(1 − α/α') [-] (Eq 3.68)."""
    return 0.5 * (1.0 - alpha / alpha_ext)


def rotation_capacity_curved(tan_alpha: float, tan_alpha_ext: float, rho: float) -> float:
    """θc [rad] of a column with curved extensions: the first zero of F_R (corrected Eq 3.56, atan in
    both branches), in the phase where it lies.

    θc = atan(tan α/(1 − 2ρ)) if that root lies in the rolling phase (θ ≤ β): instability while rolling;
    θc = atan(tan α'/(1 − 2ρ(1 − cos β))) otherwise: instability while rocking.
    Eq 3.56 chooses the branch by ρ ≤ ρc (Eq 3.55), which is exact only for the linearized β of Eq 3.68:
    with the exact β of Eq 3.44, for ρ slightly above ρc the rocking formula falls below β (outside its
    phase) while F_R already vanishes in the rolling phase — e.g. tan α = 0.1875, tan α' = 0.4375,
    ρ = 0.289 (ρc = 0.286): the rocking formula gives 0.434 rad < β = 0.447 rad, the true capacity is the
    rolling root 0.418 rad (docs/model.md §2). The atan is taken on (0, π): 1 − 2ρ < 0 gives θc > π/2.
    """
    theta_rolling = math.atan2(tan_alpha, 1.0 - 2.0 * rho)
    if rho <= critical_curvature(tan_alpha, tan_alpha_ext):
        return theta_rolling          # ρ ≤ ρc: the rolling root is below α' < β (Eq 3.44)
    beta = wedge_angle(tan_alpha, tan_alpha_ext, rho)
    if theta_rolling <= beta:
        return theta_rolling
    return math.atan2(tan_alpha_ext, 1.0 - 2.0 * rho * (1.0 - math.cos(beta)))


@dataclass(frozen=True)
class RockingGeometry:
    """The kinematic parameters the equations of motion use (SPEC §3.1).

    A flat-extended column is a block of size R' = R cos α/cos α' and slenderness α', with
    λ' = λ cos²α'/cos²α so that I_C is unchanged (SPEC §2).
    """

    R: float          # size used in the EOM [m]
    alpha: float      # slenderness angle used in the EOM [rad]
    radius: float     # r [m] (0 unless curved)
    beta: float       # wedge angle [rad] (0 unless curved)
    lam: float        # λ relative to R [-]
    theta_c: float    # rotation capacity θc [rad]


def rocking_geometry(column: Column) -> RockingGeometry:
    """Kinematic parameters (R, α, r, β, λ, θc) of a column for the equations of motion."""
    H, B = column.half_height, column.half_width
    alpha = slenderness_angle(B, H)
    R = half_diagonal(B, H)
    lam = column.mass_distribution
    if column.extension == "flat":
        alpha_e = slenderness_angle(column.half_width_ext, H)
        R_e = R * math.cos(alpha) / math.cos(alpha_e)
        lam_e = lam * math.cos(alpha_e) ** 2 / math.cos(alpha) ** 2
        return RockingGeometry(R_e, alpha_e, 0.0, 0.0, lam_e, alpha_e)
    if column.extension == "curved":
        ta, tae = column.tan_alpha, column.tan_alpha_ext
        rho = column.curvature
        beta = wedge_angle(ta, tae, rho)
        return RockingGeometry(R, alpha, column.radius, beta, lam, rotation_capacity_curved(ta, tae, rho))
    return RockingGeometry(R, alpha, 0.0, 0.0, lam, alpha)


def phase_at(theta: float, geometry: RockingGeometry) -> int:
    """Contact phase at |θ| (1: rolling, |θ| ≤ β; 2: rocking)."""
    return 1 if geometry.radius > 0.0 and abs(theta) <= geometry.beta else 2


def top_displacement_at(theta: float, geometry: RockingGeometry) -> float:
    """Column-top displacement u_B = 2u_C(θ) [m] (Eqs 3.1, 3.46, 3.51, 3.83), θ ≥ 0."""
    u, *_ = centre_kinematics(abs(theta), 1.0, phase_at(theta, geometry), geometry.R, geometry.alpha,
                              geometry.radius, geometry.beta)
    return 2.0 * u


def displacement_capacity(column: Column) -> float:
    """Column-top displacement at θ = θc [m] (SPEC §2): 2B for a block, 2B' for flat extensions."""
    geometry = rocking_geometry(column)
    if column.extension == "none":
        return 2.0 * column.half_width
    if column.extension == "flat":
        return 2.0 * column.half_width_ext
    return top_displacement_at(geometry.theta_c, geometry)
