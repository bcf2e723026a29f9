"""Formulas with the numbers substituted, for the quantities whose computation does not write its own
(thesis equation numbers as in :mod:`rockdesign.planar.design.quantities`).

Each branch also recomputes the value from the substituted numbers: the tests compare it with the
quantity, so a substituted line in the report always evaluates to the printed result.
"""
from __future__ import annotations

import math

from .equivalence import effective_gamma
from .geometry import rocking_geometry, slenderness_angle


def _s(x: float) -> str:
    """Inputs inside substituted formulas (5 significant digits, as in the design quantities)."""
    if math.isinf(x):
        return "∞"
    return f"{x:.5g}"


def substitution(name: str, quantity, system) -> tuple[str, str, float | None]:
    """(formula, substituted, value recomputed from the substituted numbers or None) for ``quantity``
    of :func:`~rockdesign.planar.design.quantities.design_quantities`, where the quantity itself has none.

    The recomputed value lets the tests check that every substituted line evaluates to the printed
    result.  λ's substitution says where λ came from (the project file), which the report adds.
    """
    formula, substituted = quantity.formula, quantity.substituted
    c = system.column
    H, B = c.half_height, c.half_width
    alpha = slenderness_angle(B, H)
    geo = rocking_geometry(c)
    lam = c.mass_distribution
    g = system.g
    value = None
    if name == "lambda" and not formula:
        formula = "λ = I_C/(m_C R²)"
        value = lam
    elif name == "theta_c" and not substituted:
        if c.extension == "curved":
            rho = c.curvature
            rolling = math.atan2(c.tan_alpha, 1.0 - 2.0 * rho)
            if rolling <= geo.beta:
                substituted = f"atan({_s(c.tan_alpha)}/(1 − 2·{_s(rho)}))  (F_R = 0 while rolling, θc ≤ β)"
                value = rolling
            else:
                substituted = (f"atan({_s(c.tan_alpha_ext)}/(1 − 2·{_s(rho)}·(1 − cos {_s(geo.beta)})))"
                               f"  (F_R = 0 while rocking, θc > β)")
                value = math.atan2(c.tan_alpha_ext, 1.0 - 2.0 * rho * (1.0 - math.cos(geo.beta)))
        elif c.extension == "flat":
            substituted = f"atan({_s(c.half_width_ext)} m / {_s(H)} m)"
            value = math.atan2(c.half_width_ext, H)
        else:
            substituted = f"atan({_s(B)} m / {_s(H)} m)"
            value = alpha
    elif name == "k_phase2" and not substituted:
        substituted = "−1 (independent of the geometry)"
        value = -1.0
    elif name == "uplift_force" and not substituted:
        gh = effective_gamma(system)
        tan_up = c.tan_alpha_ext if c.extension == "flat" else c.tan_alpha
        substituted = (f"(1 + 2·{_s(gh)})·{system.n_columns}·{_s(c.mass)} kg·{_s(g)} m/s²·{_s(tan_up)}")
        value = (1 + 2 * gh) * system.n_columns * c.mass * g * tan_up
    elif name == "R_hat" and not substituted:
        gh = effective_gamma(system)
        ratio = 1.0
        if quantity.equation in ("Eq 3.71", "Eq 3.90"):
            ratio = slenderness_angle(c.half_width_ext, H) / alpha
        lam_r = geo.lam
        substituted = (f"(1+{_s(lam_r)}+4·{_s(gh)})/((1+2·{_s(gh)})(1+{_s(lam_r)}))·{_s(ratio)}·{_s(geo.R)} m")
        value = (1 + lam_r + 4 * gh) / ((1 + 2 * gh) * (1 + lam_r)) * ratio * geo.R
    elif name == "uplift_superstructure_factor" and not substituted:
        gm, eta = system.gamma, system.eta
        substituted = f"2·{_s(gm)}·{_s(eta)}/(2·{_s(gm)} + 1)"
        value = 2 * gm * eta / (2 * gm + 1)
    elif name == "omega_s" and not formula:
        s = system.superstructure
        formula = "ω_s = 2π/T_s"
        substituted = f"2π/{_s(2 * math.pi / s.omega_s)} s"
        value = s.omega_s
    elif name == "S_r" and not substituted:
        gm, eta = system.gamma, system.eta
        substituted = (f"√((1+{_s(lam)}+4·{_s(gm)}·(1+{_s(eta)}))/(1+{_s(lam)}+4·{_s(gm)}·(1+{_s(eta)}·"
                       f"sin²{_s(alpha)})))")
        value = math.sqrt((1 + lam + 4 * gm * (1 + eta)) / (1 + lam + 4 * gm * (1 + eta * math.sin(alpha) ** 2)))
    elif name == "u_capacity" and not substituted:
        if c.extension == "none":
            substituted = f"2B = 2·{_s(B)} m"
            value = 2 * B
        elif c.extension == "flat":
            substituted = f"2B' = 2·{_s(c.half_width_ext)} m"
            value = 2 * c.half_width_ext
        else:
            r, beta, R, th = geo.radius, geo.beta, geo.R, geo.theta_c
            if th > beta:
                substituted = (f"2[R sin α − R sin(α − θc) + r(β − sin(β − θc) − sin θc)] = "
                               f"2[{_s(R)}·sin {_s(alpha)} − {_s(R)}·sin({_s(alpha)} − {_s(th)}) + {_s(r)}·"
                               f"({_s(beta)} − sin({_s(beta)} − {_s(th)}) − sin {_s(th)})] m  (phase II, Eq 3.51)")
                value = 2 * (R * math.sin(alpha) - R * math.sin(alpha - th)
                             + r * (beta - math.sin(beta - th) - math.sin(th)))
            else:
                substituted = (f"2[R sin α − R sin(α − θc) + r(θc − sin θc)] = 2[{_s(R)}·sin {_s(alpha)} − "
                               f"{_s(R)}·sin({_s(alpha)} − {_s(th)}) + {_s(r)}·({_s(th)} − sin {_s(th)})] m"
                               f"  (phase I, Eq 3.46)")
                value = 2 * (R * math.sin(alpha) - R * math.sin(alpha - th) + r * (th - math.sin(th)))
    return formula, substituted, value
