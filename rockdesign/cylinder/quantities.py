"""Closed-form design quantities of the rocking and wobbling cylinder (thesis Ch. 5), SI units.

Each function states the thesis equation it implements; :func:`cylinder_quantities` collects them
for ``quantities`` (names of the ``quantities --json`` object: ``alpha, R, p, c_r,
uplift_acceleration, angle_of_turn`` plus the inertias and the wobbling period at θ = α/2).
"""
from __future__ import annotations

import math

import numpy as np

from ..quantity import Quantity, format_number as _f
from .system import Cylinder


def inertia_transverse(R: float, alpha: float) -> float:
    """I1* = R²(3 + cos²α)/12 [m²]: transverse moment of inertia about the centre per unit mass (Eq 5.20)."""
    return R * R * (3.0 + math.cos(alpha) ** 2) / 12.0


def inertia_axial(R: float, alpha: float) -> float:
    """I2* = R² sin²α/2 [m²]: axial moment of inertia per unit mass (Eq 5.21)."""
    return R * R * math.sin(alpha) ** 2 / 2.0


def frequency_parameter(R: float, alpha: float, g: float = 9.81) -> float:
    """p = √(12 g/((15 + cos²α) R)) [1/s] of the cylinder rocking about its rim (Eq 5.27)."""
    return math.sqrt(12.0 * g / ((15.0 + math.cos(alpha) ** 2) * R))


def restitution_root(alpha: float) -> float:
    """√c_r = 1 − sin²α/(5/8 + cos²α/24): Housner's planar restitution of the cylinder (Eq 5.41)."""
    return 1.0 - math.sin(alpha) ** 2 / (5.0 / 8.0 + math.cos(alpha) ** 2 / 24.0)


def angle_of_turn(alpha: float) -> float:
    """Δφ = π √((3 + 13 cos²α)/(15 + cos²α)) [rad]: azimuth turned in a quasi-impact (Eq 5.38).

    The numerical quasi-rocking turn 2π − Δφ is the same turn measured the other way round.
    """
    c2 = math.cos(alpha) ** 2
    return math.pi * math.sqrt((3.0 + 13.0 * c2) / (15.0 + c2))


def uplift_acceleration(alpha: float, g: float = 9.81) -> float:
    """g tan α [m/s²]: the resultant ground acceleration √(ü_gx² + ü_gy²) at uplift (Eq 5.24)."""
    return g * math.tan(alpha)


def wobbling_factor(theta, alpha: float):
    """X(θ) of the pure-wobbling condition (Eq 5.22 with θ̈ = θ̇ = 0), dimensionless.

    X = sinθ cosθ (5/4 sin²α − 4/3 cos²α) − 3/2 sinθ sin²α + cosα sinα (cos²θ − sin²θ − cosθ).
    """
    th = np.asarray(theta, dtype=float)
    s2, c2 = math.sin(alpha) ** 2, math.cos(alpha) ** 2
    return (np.sin(th) * np.cos(th) * (1.25 * s2 - 4.0 / 3.0 * c2) - 1.5 * np.sin(th) * s2
            + math.cos(alpha) * math.sin(alpha) * (np.cos(2 * th) - np.cos(th)))


def wobbling_spin(theta, R: float, alpha: float, g: float = 9.81):
    """φ̇0(θ) [rad/s]: the spin that keeps the tilt θ constant, φ̇0² = −g sin(α−θ)/(R X(θ)) (Sec 5.4.2)."""
    th = np.asarray(theta, dtype=float)
    return np.sqrt(-g * np.sin(alpha - th) / (R * wobbling_factor(th, alpha)))


def wobbling_period(theta, R: float, alpha: float, g: float = 9.81):
    """T_w(θ) = 2π/φ̇0(θ) [s]: the wobbling period at constant tilt θ, 0 < θ < α (Eq 5.29; Eq 5.28 corrected)."""
    return 2.0 * math.pi / wobbling_spin(theta, R, alpha, g)


def housner_period(theta0, p: float, alpha: float):
    """Housner's linearized planar free-rocking period T = (4/p) acosh(1/(1 − θ0/α)) [s] (Eq 2.8), for Fig 5.2."""
    return 4.0 / p * np.arccosh(1.0 / (1.0 - np.asarray(theta0, dtype=float) / alpha))


def wobbling_curve(cyl: Cylinder, n: int = 99) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(θ/α, T_w p, T_Housner p) on θ/α ∈ (0, 1): the curve of thesis Fig 5.2 for this cylinder."""
    ratio = np.linspace(0.0, 1.0, n + 2)[1:-1]
    p = frequency_parameter(cyl.R, cyl.alpha, cyl.g)
    tw = wobbling_period(ratio * cyl.alpha, cyl.R, cyl.alpha, cyl.g)
    return ratio, tw * p, housner_period(ratio * cyl.alpha, p, cyl.alpha) * p


def cylinder_quantities(cyl: Cylinder) -> dict[str, Quantity]:
    """Every closed-form quantity of the cylinder (thesis Ch. 5), in report order."""
    H, B, g = cyl.half_height, cyl.base_radius, cyl.g
    alpha, R = cyl.alpha, cyl.R
    q: dict[str, Quantity] = {}

    def add(name, symbol, description, value, unit, equation, formula="", substituted="", note=""):
        q[name] = Quantity(name, symbol, description, float(value), unit, equation, formula, substituted, note)

    add("alpha", "α", "slenderness angle", alpha, "rad", "Eq 2.1", "α = atan(B/H)", f"atan({_f(B)} m / {_f(H)} m)",
        f"tan α = {_f(B / H)}")
    add("R", "R", "distance base rim – centre of mass", R, "m", "Eq 2.2", "R = √(B² + H²)", f"√({_f(B)}² + {_f(H)}²) m")
    add("I1", "I1*", "transverse moment of inertia about the centre per unit mass", inertia_transverse(R, alpha),
        "m^2", "Eq 5.20", "I1* = R²(3 + cos²α)/12")
    add("I2", "I2*", "axial moment of inertia per unit mass", inertia_axial(R, alpha), "m^2", "Eq 5.21",
        "I2* = R² sin²α/2")
    p = frequency_parameter(R, alpha, g)
    add("p", "p", "frequency parameter", p, "1/s", "Eq 5.27", "p = √(12 g/((15 + cos²α) R))",
        f"√(12·{_f(g)}/((15 + cos²{_f(alpha)})·{_f(R)}))")
    root = restitution_root(alpha)
    add("c_r", "c_r", "Housner's coefficient of restitution of the planar cylinder", root * root, "-", "Eq 5.41",
        "√c_r = 1 − sin²α/(5/8 + cos²α/24)", "", f"√c_r = {_f(root)}")
    add("uplift_acceleration", "ü_g,up", "resultant ground acceleration at uplift", uplift_acceleration(alpha, g),
        "m/s^2", "Eq 5.24", "√(ü_gx² + ü_gy²) = g tan α", f"{_f(g)}·{_f(B / H)}")
    add("angle_of_turn", "Δφ", "azimuth turned in a quasi-impact", angle_of_turn(alpha), "rad", "Eq 5.38",
        "Δφ = π√((3 + 13cos²α)/(15 + cos²α))", "", f"measured the other way: 2π − Δφ = {_f(2 * math.pi - angle_of_turn(alpha))} rad")
    half = 0.5 * alpha
    add("wobbling_period", "T_w(α/2)", "wobbling period at the tilt θ = α/2", float(wobbling_period(half, R, alpha, g)),
        "s", "Eq 5.29", "T_w = 2π/φ̇0, φ̇0² = −g sin(α−θ)/(R X(θ))", "",
        f"X(θ) = sin θ cos θ (5/4 sin²α − 4/3 cos²α) − 3/2 sin θ sin²α + cos α sin α (cos 2θ − cos θ), the "
        f"coefficient of φ̇² in Eq 5.22 (X({_f(half)}) = {_f(float(wobbling_factor(half, alpha)))}); spin "
        f"φ̇0 = {_f(float(wobbling_spin(half, R, alpha, g)))} rad/s; T_w(θ) is a curve, see the figure")
    add("theta_overturn", "θ_ot", "overturning tilt", cyl.theta_overturn, "rad", "Sec 5.5.1",
        "θ_ot = n_ot·α", f"{_f(cyl.overturn_tilt)}·{_f(alpha)}",
        f"n_ot = {_f(cyl.overturn_tilt)}: the overturning tilt in units of α given by the project (default 1.5, "
        f"Sec 5.5.1)")
    if cyl.damped:
        add("contact_frequency", "ω_n", "contact spring frequency", cyl.contact_frequency, "1/s", "Eq 5.31")
        add("contact_damping", "ζ", "contact damping ratio", cyl.contact_damping, "-", "Eq 5.31")
    return q


def quantities_json(project) -> dict:
    """``quantities --json`` of a cylinder: alpha, R, p, c_r, uplift_acceleration, angle_of_turn (+ extras)."""
    q = cylinder_quantities(project.system)
    return {"quantities": {name: x.as_json() for name, x in q.items()}, "warnings": list(project.warnings)}
