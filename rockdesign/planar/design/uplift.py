"""Uplift: ground acceleration and force that start rocking (SPEC §2, Eqs 2.17, 3.34, 3.78, 4.7)."""
from __future__ import annotations

import math


def uplift_acceleration(tan_alpha: float, g: float) -> float:
    """ü_g,up = g tan α [m/s²] (Eq 3.34); use tan α' for flat extensions."""
    return g * tan_alpha


def uplift_acceleration_linear(alpha: float, g: float) -> float:
    """Linearized ü_g,up = g α [m/s²] (Eq 2.17)."""
    return g * alpha


def uplift_force(n_columns: int, column_mass: float, gamma: float, tan_alpha: float, g: float) -> float:
    """Static horizontal uplift force F_up = (1+2γ) N m_C g tan α [N] (Eq 3.78)."""
    return (1.0 + 2.0 * gamma) * n_columns * column_mass * g * tan_alpha


def podium_uplift_factor(gamma: float, eta: float) -> float:
    """k = 2γη/(2γ+1) [-] of the podium uplift criterion (Eq 4.7)."""
    return 2.0 * gamma * eta / (2.0 * gamma + 1.0)


def podium_uplift_thresholds(tan_alpha: float, g: float, gamma: float, eta: float, omega_s: float,
                             zeta_s: float, u_T: float, u_T_dot: float) -> tuple[float, float]:
    """Ground accelerations [m/s²] that uplift a podium with an elastic superstructure (Eq 4.7).

    Uplift to θ > 0 when ü_g ≤ first value, to θ < 0 when ü_g ≥ second value:
    −g tan α + k(−g tan α + f) and g tan α + k(g tan α + f), with k = 2γη/(2γ+1) and
    f = ω_s² u_T + 2ζ_s ω_s u̇_T (u_T relative to the ground).  A rigid superstructure gives ∓g tan α.
    """
    k = podium_uplift_factor(gamma, eta)
    f = omega_s ** 2 * u_T + 2.0 * zeta_s * omega_s * u_T_dot
    up = g * tan_alpha
    return -up + k * (-up + f), up + k * (up + f)
