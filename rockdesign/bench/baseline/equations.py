"""Right-hand sides of the reference equations of motion (SPEC §3.1–§3.3), plain Python floats.

The exact equations are the one generic Lagrangian equation of SPEC §3.1 (thesis Eq 4.8 with the
θ̇² sign corrected; Eq 4.9 for the superstructure), assembled from the cap-beam kinematics
u_B(θ) = 2u_C, w_B(θ) = 2w_C and their θ-derivatives, which are derived here by hand from
SPEC §3.1 (and checked against finite differences in the tests).  The linearized equations are
those of SPEC §3.2 (first order in α and θ; p → p̂ for frames and podia).
"""
from __future__ import annotations

import math

import numpy as np

from .parameters import ModelParameters


def cap_beam_kinematics(theta: float, side: int, phase: int, params: ModelParameters):
    """Cap-beam (column-top) position and its θ-derivatives for one phase and side (SPEC §3.1).

    Returns ``(u_B, u_B', u_B'', w_B, w_B', w_B'')`` in m, m/rad, m/rad².  u_B = 2u_C, w_B = 2w_C with
    block: u_C = R sin(sα) − R sin(sα−θ), w_C = R cos(sα−θ) (Eqs 3.1–3.2; R', α' for flat
    extensions, Eqs 3.35–3.36); curved phase I adds r(θ − sin θ), r(1 − cos θ) (Eqs 3.46–3.47);
    phase II adds r(sβ − sin(sβ−θ) − sin θ), r(cos(sβ−θ) − cos θ) (Eqs 3.51–3.52).
    """
    R = params.R_kin
    s_alpha = side * params.alpha_kin
    x = s_alpha - theta
    sx, cx = math.sin(x), math.cos(x)
    u, du, ddu = R * (math.sin(s_alpha) - sx), R * cx, R * sx
    w, dw, ddw = R * cx, R * sx, -R * cx
    if params.extension == "curved":
        r = params.radius
        st, ct = math.sin(theta), math.cos(theta)
        if phase == 1:
            u += r * (theta - st)
            du += r * (1.0 - ct)
            ddu += r * st
            w += r * (1.0 - ct)
            dw += r * st
            ddw += r * ct
        else:
            s_beta = side * params.beta
            sy, cy = math.sin(s_beta - theta), math.cos(s_beta - theta)
            u += r * (s_beta - sy - st)
            du += r * (cy - ct)
            ddu += r * (sy + st)
            w += r * (cy - ct)
            dw += r * (sy + st)
            ddw += r * (ct - cy)
    return 2.0 * u, 2.0 * du, 2.0 * ddu, 2.0 * w, 2.0 * dw, 2.0 * ddw


def accelerations_exact(theta, theta_dot, u_T, u_T_dot, a_g, side, phase, params: ModelParameters):
    """(θ̈ [rad/s²], ü_T [m/s²]) of the generic equation of SPEC §3.1 and Eq 4.9.

    θ̈ [λ + (1+4γ)(u'²+w'²)/(4R²) + 4γη w'²/(4R²)] = −θ̇²[(1+4γ)(u'u''+w'w'') + 4γη w'w'']/(4R²)
      − (g/R)(1+2γ+2γη) w'/(2R) − (ü_g/R)(1+2γ) u'/(2R) + 4γη (u'/(2R)) F/(2R),
    ü_T = −F − ü_g,  F = ω_s²(u_T − u_B) + 2ζ_s ω_s (u̇_T − u'θ̇).
    Without an elastic superstructure (γη = 0) ü_T is returned as ü_B (the cap-beam acceleration).
    """
    u, du, ddu, w, dw, ddw = cap_beam_kinematics(theta, side, phase, params)
    R = params.R
    g_col = 1.0 + 4.0 * params.gamma
    g_top = 4.0 * params.gamma_eta
    inv_4R2 = 0.25 / (R * R)
    mass = params.lam + (g_col * (du * du + dw * dw) + g_top * dw * dw) * inv_4R2
    rhs = (-theta_dot * theta_dot * (g_col * (du * ddu + dw * ddw) + g_top * dw * ddw) * inv_4R2
           - params.g / R * (1.0 + 2.0 * params.gamma + 2.0 * params.gamma_eta) * dw / (2.0 * R)
           - a_g / R * (1.0 + 2.0 * params.gamma) * du / (2.0 * R))
    if g_top == 0.0:
        theta_ddot = rhs / mass
        return theta_ddot, du * theta_ddot + ddu * theta_dot * theta_dot
    om = params.omega_s
    shear = om * om * (u_T - u) + 2.0 * params.zeta * om * (u_T_dot - du * theta_dot)
    rhs += g_top * du / (2.0 * R) * shear / (2.0 * R)
    return rhs / mass, -shear - a_g


def lever_linear(theta: float, side: int, phase: int, params: ModelParameters) -> float:
    """The linearized w_B'/(2R) [rad] of SPEC §3.2: sα − θ (block), sα' − θ (flat extensions),
    sα − (1−2ρ)θ (curved phase I), sα' − θ = sα − θ + 2sρβ (curved phase II, linearized β)."""
    if params.extension == "curved":
        if phase == 1:
            return side * params.alpha - (1.0 - 2.0 * params.rho) * theta
        return side * params.alpha - theta + 2.0 * side * params.rho * params.beta
    return side * params.alpha_kin - theta


def accelerations_linear(theta, theta_dot, u_T, u_T_dot, a_g, side, phase, params: ModelParameters):
    """(θ̈, ü_T) of the linearized equations (SPEC §3.2; first order in α, θ).

    (1+λ+4γ) θ̈ = −(g/R)(1+2γ+2γη) φ − (ü_g/R)(1+2γ) + 4γη F/(2R), φ = :func:`lever_linear`,
    F = ω_s²(u_T − 2Rθ) + 2ζ_s ω_s (u̇_T − 2Rθ̇); i.e. θ̈ = −p̂²(φ + ü_g/g) for frames (Eq 3.76) and
    −p̂²φ − ... with p̂² of Eq 4.32 for podia.  Flat extensions use R, λ (p̂ = p to first order,
    Eq 3.40).  Without an elastic superstructure ü_T is returned as 2Rθ̈.
    """
    R = params.R
    mass = 1.0 + params.lam + 4.0 * params.gamma
    lever = lever_linear(theta, side, phase, params)
    rhs = (-params.g / R * (1.0 + 2.0 * params.gamma + 2.0 * params.gamma_eta) * lever
           - a_g / R * (1.0 + 2.0 * params.gamma))
    if params.gamma_eta == 0.0:
        theta_ddot = rhs / mass
        return theta_ddot, 2.0 * R * theta_ddot
    om = params.omega_s
    shear = om * om * (u_T - 2.0 * R * theta) + 2.0 * params.zeta * om * (u_T_dot - 2.0 * R * theta_dot)
    rhs += 4.0 * params.gamma_eta * shear / (2.0 * R)
    return rhs / mass, -shear - a_g


def cap_beam_state(theta: float, theta_dot: float, side: int, phase: int, params: ModelParameters):
    """(u_B [m], u̇_B [m/s]) of the model: exact kinematics, or 2Rθ when linearized."""
    if params.linear:
        return 2.0 * params.R * theta, 2.0 * params.R * theta_dot
    u, du, *_ = cap_beam_kinematics(theta, side, phase, params)
    return u, du * theta_dot


def phase_of(theta: float, side: int, params: ModelParameters) -> int:
    """Phase (1 rolling, 2 rocking) of a curved base at tilt θ on ``side``; 1 otherwise."""
    if params.extension == "curved" and side * theta > params.beta:
        return 2
    return 1


def rocking_rhs(params: ModelParameters, side: int, phase: int, accel):
    """f(t, y) for scipy: y = [θ, θ̇] (rigid superstructure or none) or [θ, θ̇, u_T, u̇_T] (podium).

    ``accel(t)`` is the ground acceleration ü_g [m/s²].  Side and phase are fixed for one call.
    """
    acc = accelerations_linear if params.linear else accelerations_exact
    if params.elastic:
        def fun(t, y):
            thdd, utdd = acc(y[0], y[1], y[2], y[3], accel(t), side, phase, params)
            return np.array([y[1], thdd, y[3], utdd])
    else:
        def fun(t, y):
            thdd, _ = acc(y[0], y[1], 0.0, 0.0, accel(t), side, phase, params)
            return np.array([y[1], thdd])
    return fun


def fixed_base_rhs(params: ModelParameters, accel):
    """f(t, y) of the superstructure on the podium at rest, y = [u_T, u̇_T] (Eq 4.3):
    ü_T + 2ζ_s ω_s u̇_T + ω_s² u_T = −ü_g."""
    om2 = params.omega_s ** 2
    c = 2.0 * params.zeta * params.omega_s

    def fun(t, y):
        return np.array([y[1], -accel(t) - c * y[1] - om2 * y[0]])
    return fun
