"""Frequency parameters, rocking period and the uplifted superstructure frequency (SPEC §2).

SI: lengths m, frequencies rad/s, g m/s².
"""
from __future__ import annotations

import math


def frequency_parameter(R: float, lam: float, g: float) -> float:
    """p = √(g/(R(1+λ))) [rad/s] (Eq 3.13)."""
    return math.sqrt(g / (R * (1.0 + lam)))


def frame_frequency_parameter(R: float, lam: float, gamma: float, g: float) -> float:
    """p̂ = √((1+2γ)/(1+λ+4γ) · g/R) [rad/s] of a rocking frame (Eq 3.76; γ = 0 gives Eq 3.13)."""
    return math.sqrt((1.0 + 2.0 * gamma) / (1.0 + lam + 4.0 * gamma) * g / R)


def critical_rolling_frequency_parameter(R: float, lam: float, gamma: float, alpha: float,
                                         alpha_ext: float, g: float) -> float:
    """p̂ of a (frame of) curved column(s) at ρ = ρc: p̂² = p²(1+2γ)(1+λ)/(1+λ+4γ)·α/α' (Eqs 3.74, 3.94)."""
    return frame_frequency_parameter(R, lam, gamma, g) * math.sqrt(alpha / alpha_ext)


def podium_frequency_parameter(R: float, lam: float, gamma: float, eta: float, g: float,
                               alpha_ratio: float = 1.0) -> float:
    """p̂ of a podium with an elastic superstructure: p̂² = g/R·(1+2γ+2γη)/(1+λ+4γ)·α/α' (Eq 4.32)."""
    return math.sqrt(g / R * (1.0 + 2.0 * gamma + 2.0 * gamma * eta) / (1.0 + lam + 4.0 * gamma) * alpha_ratio)


def rocking_period(p: float, alpha: float, theta0: float) -> float:
    """Linearized free-rocking period T_R = (4/p) acosh(1/(1 − θ0/α)) [s] (Eq 2.8), 0 < θ0 < α."""
    if not 0.0 < theta0 < alpha:
        raise ValueError("rocking period needs 0 < θ0 < α")
    return 4.0 / p * math.acosh(1.0 / (1.0 - theta0 / alpha))


def uplifted_frequency_ratio(lam: float, gamma: float, eta: float, alpha: float) -> float:
    """S_r = ω_su/ω_s = √((1+λ+4γ(1+η))/(1+λ+4γ(1+η sin²α))) [-] (Eq 4.25; γ → ∞ gives Eq 4.26)."""
    if math.isinf(gamma):
        return math.sqrt((1.0 + eta) / (1.0 + eta * math.sin(alpha) ** 2))
    return math.sqrt((1.0 + lam + 4.0 * gamma * (1.0 + eta))
                     / (1.0 + lam + 4.0 * gamma * (1.0 + eta * math.sin(alpha) ** 2)))


def uplifted_damping(zeta_s: float, S_r: float) -> float:
    """Uplifted superstructure damping ζ_su = S_r ζ_s [-] (Eq 4.27)."""
    return S_r * zeta_s
