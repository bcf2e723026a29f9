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
