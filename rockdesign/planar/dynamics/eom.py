"""One Lagrangian equation of motion for every planar rocking system (SPEC §3.1), in numba.

Systems differ only in contact kinematics (block, flat extensions, curved phases I/II) and mass
ratios (γ, η).  The state is y = (θ, θ̇, u_T, u̇_T): tilt [rad], its rate [rad/s], and the
superstructure displacement relative to the ground [m] and its rate [m/s] (zero for SDOF systems).

Exact (SPEC §3.1, Eq 4.8 corrected; Eq 4.9), with U = u_C/R, W = w_C/R and primes d/dθ:

    θ̈ [λ + (1+4γ)(U'² + W'²) + 4γη W'²] = −θ̇²[(1+4γ)(U'U'' + W'W'') + 4γη W'W'']
        − (g/R)(1+2γ+2γη) W' − (ü_g/R)(1+2γ) U' + 4γη U' f/(2R),
    ü_T = −ü_g − f,   f = ω_s²(u_T − u_B) + 2ζ_s ω_s (u̇_T − u̇_B),  u_B = 2u_C.

Linearized (SPEC §3.2, first order in α and θ): U' = 1, θ̇² terms and W'² dropped, W' = sα − θ + 2ρθ
(phase I) or sα − θ + 2ρsβ (phase II), u_B = 2Rθ.  Housner's Eq 3.12 is the case γ = η = 0.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ...motions.excitation import ground_acceleration
from ..design.kinematics import unit_centre_kinematics

# Layout of the system parameter array ``sp`` (float64) --------------------------------------
P_R = 0            # R used by the EOM [m] (R' for flat extensions)
P_ALPHA = 1        # α used by the EOM [rad] (α' for flat extensions)
P_RADIUS = 2       # r [m] of curved extensions (0 otherwise)
P_BETA = 3         # β [rad] (exact Eq 3.44, or linearized for the linear model)
P_LAM = 4          # λ relative to R
P_GAMMA = 5        # γ
P_ETA = 6          # η (0 unless a 2DOF superstructure is modelled)
P_G = 7            # g [m/s²]
P_OMEGA = 8        # ω_s [rad/s]
P_ZETA = 9         # ζ used in the model (ζ_s/S_r with the damping correction)
P_CR = 10          # coefficient of restitution c_r
P_LINEAR = 11      # 1.0: linearized equations
P_THETA_C = 12     # θc [rad] (static overturning / capacity exceeded)
P_OVERTURN = 13    # |θ| of dynamic overturning [rad] (π/2)
P_REST_V = 14      # rest velocity threshold [rad/s] (SPEC §3.6)
P_TWO_DOF = 15     # 1.0: the superstructure DOF u_T is integrated
P_HYST = 16        # uplift hysteresis [rad/s²] (SPEC §3.6 chatter guard)
P_TWO_RHO = 17     # 2ρ (linearized r/R)
P_SIN_ALPHA = 18   # sin α, cos α, sin β, cos β (precomputed: two trigonometric calls per evaluation)
P_COS_ALPHA = 19
P_SIN_BETA = 20
P_COS_BETA = 21
N_PARAMS = 22


@njit(cache=True, inline="always")
def normalised_kinematics(theta, side, phase, sp):
    """(U, U', U'', W, W', W'') = (u_C, w_C and θ-derivatives)/R for the model (exact or linear)."""
    R = sp[P_R]
    if sp[P_LINEAR] != 0.0:
        alpha = sp[P_ALPHA]
        tr = sp[P_TWO_RHO]
        if sp[P_RADIUS] != 0.0 and phase == 2:
            b = sp[P_BETA]
            w1 = side * alpha - theta + tr * side * b
            # W = ∫W' dθ, continuous at θ = sβ (constant irrelevant for the dynamics)
            w0 = side * alpha * theta - 0.5 * theta * theta + tr * side * b * theta - 0.5 * tr * b * b
        elif sp[P_RADIUS] != 0.0:
            w1 = side * alpha - theta + tr * theta
            w0 = side * alpha * theta - 0.5 * theta * theta + 0.5 * tr * theta * theta
        else:
            w1 = side * alpha - theta
            w0 = side * alpha * theta - 0.5 * theta * theta
        return theta, 1.0, 0.0, w0, w1, 0.0
    # centre_kinematics divided by R, on precomputed sin α, cos α, sin β, cos β (two trig calls)
    return unit_centre_kinematics(theta, side, phase, sp[P_RADIUS] / R, sp[P_BETA], sp[P_SIN_ALPHA],
                                  sp[P_COS_ALPHA], sp[P_SIN_BETA], sp[P_COS_BETA])



@njit(cache=True, inline="always")
def accelerations(theta, thetadot, u_t, u_tdot, side, phase, ag, sp):
    """(θ̈ [rad/s²], ü_T [m/s²]) while rocking on ``side`` in ``phase`` under ground acceleration ag."""
    R = sp[P_R]
    g = sp[P_G]
    gam = sp[P_GAMMA]
    eta = sp[P_ETA]
    U0, U1, U2, W0, W1, W2 = normalised_kinematics(theta, side, phase, sp)
    f = 0.0
    if sp[P_TWO_DOF] != 0.0:
        om = sp[P_OMEGA]
        u_b = 2.0 * R * U0
        u_bdot = 2.0 * R * U1 * thetadot
        f = om * om * (u_t - u_b) + 2.0 * sp[P_ZETA] * om * (u_tdot - u_bdot)
    kg = 1.0 + 2.0 * gam + 2.0 * gam * eta
    ge = 4.0 * gam * eta
    if sp[P_LINEAR] != 0.0:
        mass = sp[P_LAM] + 1.0 + 4.0 * gam
        rhs = -(g / R) * kg * W1 - (ag / R) * (1.0 + 2.0 * gam) + ge * f / (2.0 * R)
    else:
        mass = sp[P_LAM] + (1.0 + 4.0 * gam) * (U1 * U1 + W1 * W1) + ge * W1 * W1
        rhs = (-thetadot * thetadot * ((1.0 + 4.0 * gam) * (U1 * U2 + W1 * W2) + ge * W1 * W2)
               - (g / R) * kg * W1 - (ag / R) * (1.0 + 2.0 * gam) * U1 + ge * U1 * f / (2.0 * R))
    return rhs / mass, -ag - f


@njit(cache=True, inline="always")
def rest_acceleration(u_t, u_tdot, ag, sp):
    """ü_T [m/s²] of the fixed-base superstructure before uplift (Eq 4.3); 0 without a 2DOF model."""
    if sp[P_TWO_DOF] == 0.0:
        return 0.0
    om = sp[P_OMEGA]
    return -ag - om * om * u_t - 2.0 * sp[P_ZETA] * om * u_tdot


@njit(cache=True)
def uplift_condition(side, ag, u_t, u_tdot, sp):
    """s·θ̈ at θ = θ̇ = 0 on ``side`` [rad/s²]: uplift to that side when it exceeds the hysteresis.

    For a rigid system this is ü_g beyond ∓g tan α (Eq 3.34; g α linearized); for a podium with an
    elastic superstructure it reproduces Eq 4.7 with f = ω_s² u_T + 2ζ_s ω_s u̇_T.
    """
    thdd, _ = accelerations(0.0, 0.0, u_t, u_tdot, side, 1, ag, sp)
    return side * thdd


@njit(cache=True, inline="always")
def rhs(t, y, out, rocking, side, phase, kind, xp, samples, sp):
    """dy/dt into ``out`` for the rocking (rocking=True) or resting (θ frozen at 0) state."""
    state_derivatives(ground_acceleration(t, kind, xp, samples), y, out, rocking, side, phase, sp)


@njit(cache=True)
def rhs_given_acceleration(ag, y, out, rocking, side, phase, sp):
    """dy/dt into ``out`` for a given ground acceleration ag [m/s²] (the same as :func:`rhs`)."""
    state_derivatives(ag, y, out, rocking, side, phase, sp)


@njit(cache=True, inline="always")
def state_derivatives(ag, y, out, rocking, side, phase, sp):
    """dy/dt into ``out`` under ground acceleration ag: θ̇, θ̈ (or 0, 0 at rest), u̇_T, ü_T (0, 0 for SDOF)."""
    if rocking:
        thdd, utdd = accelerations(y[0], y[1], y[2], y[3], side, phase, ag, sp)
        out[0] = y[1]
        out[1] = thdd
    else:
        utdd = rest_acceleration(y[2], y[3], ag, sp)
        out[0] = 0.0
        out[1] = 0.0
    if sp[P_TWO_DOF] != 0.0:
        out[2] = y[3]
        out[3] = utdd
    else:
        out[2] = 0.0
        out[3] = 0.0


@njit(cache=True)
def potential_energy(theta, side, phase, sp):
    """Potential energy above the resting position per (N m_C R²) [1/s²]: (g/R)(1+2γ+2γη)(W(θ) − W(0))."""
    gam = sp[P_GAMMA]
    kg = 1.0 + 2.0 * gam + 2.0 * gam * sp[P_ETA]
    _, _, _, W0, _, _ = normalised_kinematics(theta, side, phase, sp)
    _, _, _, Wr, _, _ = normalised_kinematics(0.0, side, 1, sp)
    return sp[P_G] / sp[P_R] * kg * (W0 - Wr)


@njit(cache=True)
def total_energy(y, rocking, side, phase, sp):
    """Mechanical energy per (N m_C R²) [1/s²] relative to rest: rocking + superstructure + spring.

    Without ground motion it never increases (impacts and damping only dissipate) — the basis of the
    early-termination bound of rocking spectra.
    """
    R = sp[P_R]
    gam = sp[P_GAMMA]
    eta = sp[P_ETA]
    e = 0.0
    U0 = 0.0
    if rocking:
        U0, U1, U2, W0, W1, W2 = normalised_kinematics(y[0], side, phase, sp)
        if sp[P_LINEAR] != 0.0:
            mass = sp[P_LAM] + 1.0 + 4.0 * gam
        else:
            mass = sp[P_LAM] + (1.0 + 4.0 * gam) * (U1 * U1 + W1 * W1) + 4.0 * gam * eta * W1 * W1
        e = 0.5 * mass * y[1] * y[1] + potential_energy(y[0], side, phase, sp)
    if sp[P_TWO_DOF] != 0.0:
        om = sp[P_OMEGA]
        rel = y[2] - 2.0 * R * U0
        e += 0.5 * gam * eta * (y[3] * y[3] + om * om * rel * rel) / (R * R)
    return e


def pack_parameters(values: dict) -> np.ndarray:
    """Build the ``sp`` array from a dict of the P_* names (lower-case, without the prefix)."""
    sp = np.zeros(N_PARAMS)
    for key, value in values.items():
        sp[globals()["P_" + key.upper()]] = float(value)
    if sp[P_OVERTURN] == 0.0:
        sp[P_OVERTURN] = math.pi / 2
    sp[P_SIN_ALPHA] = math.sin(sp[P_ALPHA])
    sp[P_COS_ALPHA] = math.cos(sp[P_ALPHA])
    sp[P_SIN_BETA] = math.sin(sp[P_BETA])
    sp[P_COS_BETA] = math.cos(sp[P_BETA])
    return sp
