"""All closed-form design quantities of a system (SPEC §2), each with symbol, unit, thesis equation, its
formula and the formula with the numbers substituted (what the calculation report prints).

Names are those of CONTRACT §3 (``alpha, R, p, lambda, c_r, ...``) plus a few documented extras.
"""
from __future__ import annotations

import dataclasses
import math

from ...project_tables import DEFAULTS
from ..system import RockingSystem
from .equivalence import (CRITICAL_CURVATURE_TOLERANCE, at_critical_curvature,  # noqa: F401 (re-exported)
                          effective_gamma, equivalent_size)
from .frequencies import (frequency_parameter, frequency_parameter_derivation, rocking_period,
                          uplifted_damping, uplifted_frequency_ratio)
from .geometry import (critical_curvature, critical_curvature_linear, displacement_capacity,
                       rocking_geometry, slenderness_angle, wedge_angle, wedge_angle_linear)
from .pushover import post_uplift_stiffness_linear
from .substitutions import substitution
from .restitution import restitution_derivation
from ...quantity import Quantity, format_number as _f  # noqa: F401 (re-exported)
from .uplift import (podium_uplift_factor, uplift_acceleration, uplift_acceleration_linear,
                     uplift_force)

RIGID_SUPERSTRUCTURE_RATIO = DEFAULTS.rigid_superstructure_ratio
"""ω_s/p at and above which the superstructure is treated as rigid by default (SPEC §6; the ``[analysis]``
default of :mod:`rockdesign.project_tables`)."""


def coefficient_of_restitution(system: RockingSystem) -> tuple[float, str]:
    """(c_r, equation) of the system: measured value, or CoAM per system type (SPEC §2)."""
    return restitution_derivation(system)[:2]


def system_frequency_parameter(system: RockingSystem) -> tuple[float, str]:
    """(p̂, equation): the frequency parameter of the system as modelled (SPEC §2)."""
    return frequency_parameter_derivation(system)[:2]


def design_quantities(system: RockingSystem, rigid_ratio: float = RIGID_SUPERSTRUCTURE_RATIO) -> dict[str, Quantity]:
    """Every closed-form design quantity of SPEC §2 that applies to ``system``, in report order.

    ``rigid_ratio``: ω_s/p at and above which the superstructure counts as rigid (the project's
    ``[analysis] rigid_superstructure_ratio``); it only words the note on ω_s/p."""
    c = system.column
    g = system.g
    H, B = c.half_height, c.half_width
    alpha = slenderness_angle(B, H)
    R = math.hypot(B, H)
    lam = c.mass_distribution
    geo = rocking_geometry(c)
    q: dict[str, Quantity] = {}

    def add(name, symbol, description, value, unit, equation, formula="", substituted="", note=""):
        q[name] = Quantity(name, symbol, description, float(value), unit, equation, formula, substituted, note)

    add("alpha", "α", "slenderness angle", alpha, "rad", "Eq 2.1", "α = atan(B/H)",
        f"atan({_f(B)} m / {_f(H)} m)", f"tan α = {_f(B / H)}")
    add("R", "R", "half-diagonal (size)", R, "m", "Eq 2.2", "R = √(B² + H²)", f"√({_f(B)}² + {_f(H)}²) m")
    add("lambda", "λ", "mass distribution I_C/(m_C R²)", lam, "-", "Eq 3.6")
    p = frequency_parameter(R, lam, g)
    add("p", "p", "frequency parameter of one column", p, "1/s", "Eq 3.13", "p = √(g/(R(1+λ)))",
        f"√({_f(g)}/({_f(R)}·(1+{_f(lam)})))")
    ext = c.extension
    if ext != "none":
        alpha_e = slenderness_angle(c.half_width_ext, H)
        add("alpha_ext", "α'", "slenderness angle of the extended base", alpha_e, "rad", "Sec 3.2.3",
            "α' = atan(B'/H)", f"atan({_f(c.half_width_ext)} m / {_f(H)} m)")
    if ext == "curved":
        rho = c.curvature
        beta = wedge_angle(c.tan_alpha, c.tan_alpha_ext, rho)
        add("rho", "ρ", "curvature parameter r/(2H)", rho, "-", "Eq 3.43", "ρ = r/(2H)",
            f"{_f(c.radius)} m / (2·{_f(H)} m)")
        add("beta", "β", "wedge angle (rolling ↔ rocking)", beta, "rad", "Eq 3.44",
            "β = asin((tan α' − tan α)/(2ρ))", f"asin(({_f(c.tan_alpha_ext)} − {_f(c.tan_alpha)})/(2·{_f(rho)}))",
            f"linearized {_f(wedge_angle_linear(alpha, alpha_e, rho))} rad")
        rho_c = critical_curvature(c.tan_alpha, c.tan_alpha_ext)
        add("rho_c", "ρc", "critical curvature (zero rolling stiffness)", rho_c, "-", "Eq 3.55",
            "ρc = ½(1 − tan α/tan α')", f"½(1 − {_f(c.tan_alpha)}/{_f(c.tan_alpha_ext)})",
            f"linearized ½(1 − α/α') = {_f(critical_curvature_linear(alpha, alpha_e))} (Eq 3.68)")
        regime = ("unstable while rolling (θc ≤ β)" if geo.theta_c <= beta else "unstable while rocking (θc > β)")
        add("theta_c", "θc", "rotation capacity (F_R = 0)", geo.theta_c, "rad", "Eq 3.56 (corrected)",
            "atan(tan α/(1−2ρ)) if ≤ β (always for ρ ≤ ρc), else atan(tan α'/(1−2ρ(1−cos β)))", "", regime)
        add("k_phase1", "k*_I", "linearized post-uplift stiffness, rolling phase", post_uplift_stiffness_linear(rho, 1),
            "-", "Eq 3.50", "k*_I = 2ρ − 1", f"2·{_f(rho)} − 1")
    else:
        add("theta_c", "θc", "rotation capacity (F_R = 0)", geo.theta_c, "rad", "Sec 3.2.4",
            "θc = α'" if ext == "flat" else "θc = α")
    add("k_phase2", "k*_II", "linearized post-uplift stiffness, rocking phase", -1.0, "-", "Eq 3.53",
        "k*_II = −1")
    tan_up = c.tan_alpha_ext if ext == "flat" else c.tan_alpha
    alpha_up = math.atan(tan_up)
    add("uplift_acceleration", "ü_g,up", "ground acceleration at uplift"
        + (" (rigid superstructure)" if system.superstructure is not None else ""),
        uplift_acceleration(tan_up, g), "m/s^2", "Eq 3.34", "ü_g,up = g tan α" + ("'" if ext == "flat" else ""),
        f"{_f(g)}·{_f(tan_up)}")
    add("uplift_acceleration_linear", "g α", "linearized uplift acceleration", uplift_acceleration_linear(alpha_up, g),
        "m/s^2", "Eq 2.17", "ü_g,up ≈ g α", f"{_f(g)}·{_f(alpha_up)}")
    c_r, c_r_eq, c_r_formula, c_r_sub = restitution_derivation(system)
    add("c_r", "c_r", "coefficient of restitution", c_r, "-", c_r_eq, c_r_formula, c_r_sub)
    add("u_capacity", "u_B(θc)", "column-top displacement capacity (Polyakov's 2B)", displacement_capacity(c), "m",
        "Eqs 3.46/3.51, 3.83 at θc", "u_B = 2u_C(θc)", "",
        "2B" if ext == "none" else ("2B'" if ext == "flat" else "generalized capacity (ours, docs/model.md §6)"))
    add("rocking_period", "T_R(α/2; p)", "linearized free-rocking period of one column (its p) from θ0 = α/2",
        rocking_period(p, alpha, alpha / 2), "s", "Eq 2.8", "T_R = (4/p) acosh(1/(1 − θ0/α))", f"(4/{_f(p)}) acosh(2)",
        "the rocking period at the design rotation θ = α/2, which bounds the ASCE 7-22 §16.2.1 period range")
    if system.kind == "podium":
        add("gamma", "γ", "cap-beam to columns mass ratio m_B/(N m_C)", system.gamma, "-", "Eq 3.77",
            "γ = m_B/(N m_C)", f"{_f(system.cap_beam_mass)} kg/({system.n_columns}·{_f(c.mass)} kg)")
        if system.superstructure is not None:
            add("eta", "η", "superstructure to cap-beam mass ratio m_T/m_B", system.eta, "-", "Eq 4.2",
                "η = m_T/m_B", f"{_f(system.superstructure.mass)} kg/{_f(system.cap_beam_mass)} kg")
    g_hat = effective_gamma(system)
    if system.kind == "podium":
        add("uplift_force", "F_up", "static horizontal uplift force (superstructure rigid)",
            uplift_force(system.n_columns, c.mass, g_hat, tan_up, g), "N", "Eq 3.78",
            "F_up = (1+2γ̂) N m_C g tan α, γ̂ = γ(1+η)")
    p_hat, p_hat_eq, p_hat_formula, p_hat_sub = frequency_parameter_derivation(system)
    if p_hat_eq != "Eq 3.13":
        add("p_hat", "p̂", "frequency parameter of the system", p_hat, "1/s", p_hat_eq, p_hat_formula, p_hat_sub)
        # one period, two frequency parameters: the table's T_R is one column's (p); the system rocks with p̂
        t_system = rocking_period(p_hat, alpha, alpha / 2)
        q["rocking_period"] = dataclasses.replace(q["rocking_period"], note=(
            f"one column's period; the {'podium' if system.kind == 'podium' else 'frame'} rocks with p̂ = "
            f"{p_hat:.4g} 1/s ({p_hat_eq}): T_R(α/2; p̂) = (4/p̂) acosh 2 = {t_system:.3g} s, the rocking period "
            "that bounds the ASCE 7-22 §16.2.1 period range"))
    crit = at_critical_curvature(system)
    if g_hat > 0.0 or crit or ext == "flat":
        ratio = (slenderness_angle(c.half_width_ext, H) / alpha) if crit else 1.0
        r_hat = equivalent_size(geo.R, geo.lam, g_hat, ratio)
        eq = "Eq 3.90" if (crit and g_hat > 0) else ("Eq 3.71" if crit else "Eq 3.81")
        note = "γ̂ = γ(1+η) (rigid superstructure)" if system.superstructure is not None else ""
        if ext == "flat":
            note = (note + "; " if note else "") + "flat extensions: block of size R', λ'"
        add("R_hat", "R̂", "equivalent size of a solitary flat-based block", r_hat, "m", eq,
            "R̂ = (1+λ+4γ)/((1+2γ)(1+λ)) · (α'/α) · R", "", note + "; holds to linear order up to the first impact"
            if note else "holds to linear order up to the first impact")
    s = system.superstructure
    if s is not None and not s.rigid:
        S_r = uplifted_frequency_ratio(lam, system.gamma, system.eta, alpha)
        add("uplift_superstructure_factor", "k", "podium uplift factor in Eq 4.7", podium_uplift_factor(
            system.gamma, system.eta), "-", "Eq 4.7", "k = 2γη/(2γ+1)")
        add("omega_s", "ω_s", "fixed-base superstructure frequency", s.omega_s, "1/s", "Eq 4.1",
            "", "", f"T_s = {_f(2 * math.pi / s.omega_s)} s")
        add("S_r", "S_r", "uplifted frequency amplification ω_su/ω_s", S_r, "-", "Eq 4.25",
            "S_r = √((1+λ+4γ(1+η))/(1+λ+4γ(1+η sin²α)))")
        add("omega_su", "ω_su", "uplifted superstructure frequency", S_r * s.omega_s, "1/s", "Eq 4.25",
            "ω_su = S_r ω_s", f"{_f(S_r)}·{_f(s.omega_s)}")
        zeta_in = s.damping / S_r if s.damping_correction else s.damping
        add("zeta_su", "ζ_su", "uplifted superstructure damping", uplifted_damping(zeta_in, S_r), "-", "Eq 4.27",
            "ζ_su = S_r ζ_in", f"{_f(S_r)}·{_f(zeta_in)}",
            "input damping ζ_s/S_r (damping correction)" if s.damping_correction else "no damping correction")
        ratio = s.omega_s / p
        verdict = ("rigid superstructure adequate (Polyakov rule 1)" if ratio >= rigid_ratio
                   else "superstructure flexibility matters: 2DOF podium model")
        add("omega_s_over_p", "ω_s/p", "superstructure to rocking frequency ratio", ratio, "-", "Sec 4.2.4, docs/model.md §7",
            "ω_s/p", f"{_f(s.omega_s)}/{_f(p)}", f"{verdict} (switch at {rigid_ratio:g})")
    # every quantity carries its formula and substituted numbers (the report only renders them)
    for name, quantity in q.items():
        formula, substituted, _ = substitution(name, quantity, system)
        q[name] = dataclasses.replace(quantity, formula=formula, substituted=substituted)
    return q
