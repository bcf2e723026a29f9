"""What the rocking storey passes up: the superstructure's force and drift, the cap beam's acceleration (SPEC §13).

The 2DOF podium (SPEC §3.1, Eq 4.9) carries the superstructure on a spring and dashpot; the force in
them per unit top mass is

    f_s = ω_s²(u_T − u_B) + 2ζ_s ω_s (u̇_T − u̇_B),   u_B = 2u_C(θ),  u̇_B = 2u_C'(θ) θ̇,

and ü_T + ü_g = −f_s: |f_s| is the superstructure's absolute acceleration, m_T f_s its base shear.
Before uplift and at rest u_B = u̇_B = 0 (Eq 4.3).  At an impact u̇_T is continuous (Eq 4.21) while
u̇_B jumps with θ̇ (Eq 4.20) and the side, so the engine evaluates f_s on both sides of it.

Rigid masses (a frame's cap beam, a rigid superstructure): θ̇ jumps at an impact, so the cap beam's
acceleration is impulsive there.  The engine keeps its absolute acceleration ü_B + ü_g between
impacts, ü_B = 2R(U''θ̇² + U'θ̈), and the largest velocity jump |Δu̇_B| at an impact — never a
step-size-dependent "peak" of the impulse.

The engine calls :func:`track_demand` at the end of every accepted step (steps end on every record
sample), after every exact rest step and on both sides of every event; :func:`force_history` gives
the same quantity on a recorded history.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .eom import P_GAMMA, P_OMEGA, P_R, P_TWO_DOF, P_ZETA, accelerations, normalised_kinematics
from .transitions import phase_of
from .layout import S_CAP_ACC_MAX, S_CAP_DV_MAX, S_DRIFT_MAX, S_FS_MAX, S_T_FS_MAX


@njit(cache=True)
def superstructure_force(y, rocking, side, phase, sp):
    """(f_s [m/s²], drift u_T − u_B [m]) of the 2DOF podium in state ``y`` = (θ, θ̇, u_T, u̇_T) (SPEC §13,
    Eq 4.9); at rest u_B = u̇_B = 0 (Eq 4.3).  |f_s| is the superstructure's absolute acceleration."""
    om = sp[P_OMEGA]
    ub = 0.0
    ubd = 0.0
    if rocking:
        U0, U1, _, _, _, _ = normalised_kinematics(y[0], side, phase, sp)
        ub = 2.0 * sp[P_R] * U0
        ubd = 2.0 * sp[P_R] * U1 * y[1]
    drift = y[2] - ub
    return om * om * drift + 2.0 * sp[P_ZETA] * om * (y[3] - ubd), drift


@njit(cache=True)
def track_demand(t, y, thdd, rocking, side, phase, ag, sp, summary):
    """Update the demand maxima of ``summary`` with the state ``y`` at time t [s] under ground acceleration
    ag [m/s²]: 2DOF podium — peak |f_s| (and its time) and peak |u_T − u_B|; a frame's rigid cap beam while
    rocking — its peak absolute acceleration |ü_B + ü_g| [m/s²] with θ̈ = ``thdd`` [rad/s²] (NaN: computed
    here) (SPEC §13).  A solitary column (γ = 0) carries nothing: no work."""
    if sp[P_TWO_DOF] != 0.0:
        fs, drift = superstructure_force(y, rocking, side, phase, sp)
        if abs(fs) > summary[S_FS_MAX]:
            summary[S_FS_MAX] = abs(fs)
            summary[S_T_FS_MAX] = t
        if abs(drift) > summary[S_DRIFT_MAX]:
            summary[S_DRIFT_MAX] = abs(drift)
    elif rocking and sp[P_GAMMA] != 0.0:
        if thdd != thdd:
            thdd, _ = accelerations(y[0], y[1], y[2], y[3], side, phase, ag, sp)
        _, U1, U2, _, _, _ = normalised_kinematics(y[0], side, phase, sp)
        acc = abs(2.0 * sp[P_R] * (U2 * y[1] * y[1] + U1 * thdd) + ag)
        if acc > summary[S_CAP_ACC_MAX]:
            summary[S_CAP_ACC_MAX] = acc


@njit(cache=True)
def track_impact_jump(thetadot_before, thetadot_after, side_before, side_after, sp, summary):
    """Rigid masses: update the largest jump |Δu̇_B| [m/s] of the cap beam's velocity at an impact (θ = 0,
    Eq 3.4 map θ̇⁺ = √c_r θ̇⁻, side flipped; SPEC §13) — an impulse per unit mass."""
    if sp[P_TWO_DOF] != 0.0 or sp[P_GAMMA] == 0.0:
        return
    _, U1m, _, _, _, _ = normalised_kinematics(0.0, side_before, 1, sp)
    _, U1p, _, _, _, _ = normalised_kinematics(0.0, side_after, 1, sp)
    dv = abs(2.0 * sp[P_R] * (U1p * thetadot_after - U1m * thetadot_before))
    if dv > summary[S_CAP_DV_MAX]:
        summary[S_CAP_DV_MAX] = dv


@njit(cache=True)
def force_history(theta, thetadot, u_t, u_tdot, sp):
    """f_s [m/s²] of the 2DOF podium at each row of a history (SPEC §13); the side is the sign of θ (at
    θ = 0 both sides give the same u_B' for every contact, so the side does not matter there), the contact
    phase follows from |θ|; a row with θ = θ̇ = 0 is at rest."""
    n = theta.shape[0]
    out = np.empty(n)
    y = np.zeros(4)
    for i in range(n):
        y[0] = theta[i]
        y[1] = thetadot[i]
        y[2] = u_t[i]
        y[3] = u_tdot[i]
        rocking = theta[i] != 0.0 or thetadot[i] != 0.0
        side = 1.0 if (theta[i] > 0.0 or (theta[i] == 0.0 and thetadot[i] >= 0.0)) else -1.0
        out[i], _ = superstructure_force(y, rocking, side, phase_of(abs(theta[i]), sp), sp)
    return out
