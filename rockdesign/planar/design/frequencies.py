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


def _s(x: float) -> str:
    """A number inside a substituted formula (5 significant digits, as in the design quantities)."""
    return f"{x:.5g}"


def frequency_parameter_derivation(system) -> tuple[float, str, str, str]:
    """(p̂ [1/s], equation, formula, substituted): the frequency parameter of the system as modelled —
    Eq 3.13 block, Eq 3.76 frame (flat extensions: Eq 3.38 with R', λ'), Eq 3.74/3.94 at the critical
    curvature, Eq 4.32 podium with an elastic superstructure.  Value and substituted numbers come from
    the same inputs in the same branch.
    """
    from .equivalence import at_critical_curvature, effective_gamma
    from .geometry import rocking_geometry, slenderness_angle
    c = system.column
    g = system.g
    geo = rocking_geometry(c)
    R, lam = geo.R, geo.lam
    alpha = slenderness_angle(c.half_width, c.half_height)
    ratio = 1.0
    if at_critical_curvature(system):
        ratio = alpha / slenderness_angle(c.half_width_ext, c.half_height)
    if system.has_elastic_superstructure:
        gamma, eta = system.gamma, system.eta
        sub = (f"√({_s(g)}/{_s(R)} · (1+2·{_s(gamma)}+2·{_s(gamma)}·{_s(eta)})/(1+{_s(lam)}+4·{_s(gamma)}) · "
               f"{_s(ratio)})")
        return podium_frequency_parameter(R, lam, gamma, eta, g, ratio), "Eq 4.32", \
            "p̂ = √(g/R · (1+2γ+2γη)/(1+λ+4γ) · α/α')", sub
    g_hat = effective_gamma(system)
    if ratio != 1.0:
        alpha_e = alpha / ratio
        sub = (f"√((1+2·{_s(g_hat)})/(1+{_s(lam)}+4·{_s(g_hat)}) · {_s(g)}/{_s(R)} · "
               f"{_s(alpha)}/{_s(slenderness_angle(c.half_width_ext, c.half_height))})")
        return critical_rolling_frequency_parameter(R, lam, g_hat, alpha, alpha_e, g), \
            "Eq 3.94" if g_hat > 0 else "Eq 3.74", "p̂ = √((1+2γ̂)/(1+λ+4γ̂) · g/R · α/α')", sub
    if c.extension == "flat":
        formula = "p̂ = √((1+2γ̂)/(1+λ'+4γ̂) · g/R'), R' = R cos α/cos α', λ' = λ cos²α'/cos²α"
        eq = "Eq 3.38 (R', λ'; frames Eq 3.76)"
    else:
        formula = "p̂ = √((1+2γ̂)/(1+λ+4γ̂) · g/R)"
        eq = "Eq 3.76" if g_hat > 0 else "Eq 3.13"
    formula += ", γ̂ = γ(1+η)" if system.superstructure is not None else ""
    sub = f"√((1+2·{_s(g_hat)})/(1+{_s(lam)}+4·{_s(g_hat)}) · {_s(g)}/{_s(R)})"
    return frame_frequency_parameter(R, lam, g_hat, g), eq, formula, sub
