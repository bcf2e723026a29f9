"""Equivalent sizes: the solitary flat-based block that responds like a frame or a critically curved column."""
from __future__ import annotations

import math

from ..system import RockingSystem
from .geometry import critical_curvature, critical_curvature_linear

CRITICAL_CURVATURE_TOLERANCE = 0.02
"""ρ counts as 'at ρc' (for p̂ of Eq 3.94 and R̂ of Eq 3.71) within this relative distance of the
exact (Eq 3.55) or linearized (Eq 3.68) ρc; the thesis examples use the linearized value."""


def effective_gamma(system: RockingSystem) -> float:
    """γ of the frame that carries the superstructure rigidly: γ̂ = γ(1+η) (SPEC §3.3, Polyakov rule 1)."""
    return system.gamma * (1.0 + system.eta)


def at_critical_curvature(system: RockingSystem) -> bool:
    """True for curved extensions with ρ = ρc (exact Eq 3.55 or linearized Eq 3.68) within tolerance."""
    c = system.column
    if c.extension != "curved":
        return False
    rho = c.curvature
    rc = critical_curvature(c.tan_alpha, c.tan_alpha_ext)
    rcl = critical_curvature_linear(math.atan(c.tan_alpha), math.atan(c.tan_alpha_ext))
    return abs(rho - rc) <= CRITICAL_CURVATURE_TOLERANCE * rc or abs(rho - rcl) <= CRITICAL_CURVATURE_TOLERANCE * rcl


def frame_size_factor(lam: float, gamma: float) -> float:
    """R̂/R = (1+λ+4γ)/((1+2γ)(1+λ)) of a frame's equivalent solitary block (Eqs 3.81, 3.89; Eq 2.24).

    γ = inf gives the limit 4/(2(1+λ)) = 2/(1+λ).
    """
    if gamma == float("inf"):
        return 2.0 / (1.0 + lam)
    return (1.0 + lam + 4.0 * gamma) / ((1.0 + 2.0 * gamma) * (1.0 + lam))


def equivalent_size(R: float, lam: float, gamma: float = 0.0, alpha_ratio: float = 1.0,
                    lam_hat: float | None = None) -> float:
    """R̂ [m] (Eq 3.90): R̂ = (1+λ+4γ)/((1+2γ)(1+λ)) · (α'/α) · R.

    ``alpha_ratio`` = α'/α for a curved column at ρ = ρc (Eq 3.71), 1 otherwise.  With ``lam_hat``
    (λ̂ of the equivalent block ≠ λ) the curved-column factor is (α'/α)(1+λ)/(1+λ̂) (Eq 3.70).
    Equivalence holds to linear order up to the first impact (c_r differs).
    """
    geometric = alpha_ratio if lam_hat is None else alpha_ratio * (1.0 + lam) / (1.0 + lam_hat)
    return frame_size_factor(lam, gamma) * geometric * R


def equivalent_size_from_spectra(x1: float, x2: float) -> float:
    """R̂/R = (x1/x2)² from the abscissae ω_p/p of two overturning lines at one ordinate (Eq 3.65)."""
    return (x1 / x2) ** 2
