"""Coefficient of restitution c_r = (θ̇⁺/θ̇⁻)² from conservation of angular momentum (SPEC §2, §3.4)."""
from __future__ import annotations

import math


def restitution_block(alpha: float, lam: float) -> float:
    """Housner block: c_r = (1 − 2 sin²α/(1+λ))² (Eq 3.14)."""
    return (1.0 - 2.0 * math.sin(alpha) ** 2 / (1.0 + lam)) ** 2


def restitution_frame(alpha: float, lam: float, gamma: float) -> float:
    """Rocking frame: c_r = (1 − 2(1+4γ)/(1+λ+4γ) sin²α)² (Eq 3.80); γ = 0 gives Eq 3.14."""
    return (1.0 - 2.0 * (1.0 + 4.0 * gamma) / (1.0 + lam + 4.0 * gamma) * math.sin(alpha) ** 2) ** 2


def restitution_podium(alpha: float, lam: float, gamma: float, eta: float) -> float:
    """Podium: c_r = (1 − 2 sin²α (1+4γ+4γη)/(1+λ+4γ+4γη))² (Eq 4.20) = frame with γ̂ = γ(1+η)."""
    g4 = 4.0 * gamma * (1.0 + eta)
    return (1.0 - 2.0 * math.sin(alpha) ** 2 * (1.0 + g4) / (1.0 + lam + g4)) ** 2


def restitution_flat_extensions(alpha: float, alpha_ext: float, lam: float, gamma: float = 0.0,
                                printed: bool = False) -> float:
    """Flat extensions, CoAM about pivots 2B' apart: c_r = (1 − 2(1+4γ) sin²α'/(1+λ'+4γ))², λ' = λcos²α'/cos²α.

    This is the corrected Eq 3.39 (SPEC §8).  ``printed=True`` uses the thesis's printed sin²α
    (it reproduces Table 3.4's c_r = 0.970 for B5; the CoAM value is 0.887).
    """
    lam_e = lam * math.cos(alpha_ext) ** 2 / math.cos(alpha) ** 2
    s2 = math.sin(alpha if printed else alpha_ext) ** 2
    return (1.0 - 2.0 * (1.0 + 4.0 * gamma) / (1.0 + lam_e + 4.0 * gamma) * s2) ** 2


def _s(x: float) -> str:
    """A number inside a substituted formula (5 significant digits, as in the design quantities)."""
    return f"{x:.5g}"


def restitution_derivation(system) -> tuple[float, str, str, str]:
    """(c_r [-], equation, formula, substituted) of ``system``: the measured value, or CoAM per system
    type (Eq 3.14 block, Eq 3.80 frame, Eq 4.20 podium, Eq 3.39 flat extensions corrected or as printed).

    The value and the substituted numbers come from the same inputs in the same branch, so the
    report's substituted line evaluates to the printed c_r.
    """
    from .equivalence import effective_gamma
    from .geometry import slenderness_angle
    if system.restitution is not None:
        return system.restitution, "measured (project file)", "c_r measured", \
            f"{_s(system.restitution)} (project file)"
    c = system.column
    alpha = slenderness_angle(c.half_width, c.half_height)
    lam = c.mass_distribution
    if c.extension == "flat":
        alpha_e = slenderness_angle(c.half_width_ext, c.half_height)
        printed = system.restitution_rule == "thesis-eq-3.39"
        g_hat = effective_gamma(system)
        lam_e = lam * math.cos(alpha_e) ** 2 / math.cos(alpha) ** 2
        eq = "Eq 3.39 as printed (sin²α)" if printed else "Eq 3.39 corrected (CoAM about 2B', docs/model.md §9)"
        formula = ("c_r = (1 − 2(1+4γ̂) sin²α/(1+λ'+4γ̂))², λ' = λ cos²α'/cos²α" if printed else
                   "c_r = (1 − 2(1+4γ̂) sin²α'/(1+λ'+4γ̂))², λ' = λ cos²α'/cos²α")
        sub = (f"(1 − 2(1+4·{_s(g_hat)})·sin²{_s(alpha if printed else alpha_e)}/"
               f"(1+{_s(lam_e)}+4·{_s(g_hat)}))²")
        return restitution_flat_extensions(alpha, alpha_e, lam, g_hat, printed), eq, formula, sub
    gamma = system.gamma
    if system.superstructure is not None:
        eta = system.eta
        sub = (f"(1 − 2·sin²{_s(alpha)}·(1+4·{_s(gamma)}+4·{_s(gamma)}·{_s(eta)})/"
               f"(1+{_s(lam)}+4·{_s(gamma)}+4·{_s(gamma)}·{_s(eta)}))²")
        return restitution_podium(alpha, lam, gamma, eta), "Eq 4.20", \
            "c_r = (1 − 2 sin²α (1+4γ+4γη)/(1+λ+4γ+4γη))²", sub
    if gamma > 0.0:
        sub = f"(1 − 2(1+4·{_s(gamma)})/(1+{_s(lam)}+4·{_s(gamma)})·sin²{_s(alpha)})²"
        return restitution_frame(alpha, lam, gamma), "Eq 3.80", "c_r = (1 − 2(1+4γ)/(1+λ+4γ) sin²α)²", sub
    return restitution_block(alpha, lam), "Eq 3.14", "c_r = (1 − 2 sin²α/(1+λ))²", \
        f"(1 − 2·sin²{_s(alpha)}/(1+{_s(lam)}))²"
