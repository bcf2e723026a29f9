"""State transitions of a rocking body, shared by the integrator (:mod:`.engine`) and the closed form
(:mod:`.linear_exact`): uplift, impact (with rest), change of contact phase, overturning, and the
classification of a monotone piece of the response into the event it crosses (numba).

Each transition updates the state ``y`` = (θ, θ̇, u_T, u̇_T), the run summary (``S_*``), the event
buffers and the diagnostics (``D_*``) in place (layouts in :mod:`.layout`); the caller keeps its own
mode flags (rocking, side, phase) from the returned values.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .eom import P_BETA, P_CR, P_HYST, P_OVERTURN, P_R, P_RADIUS, P_REST_V, P_THETA_C, normalised_kinematics, potential_energy, total_energy
from .layout import (N_SUMMARY, S_IMPACTS_BEFORE_EXCEEDED, S_T_EXCEEDED, D_EVENTS, D_EVENTS_STORED, D_REST, EV_IMPACT, EV_OVERTURN, EV_PHASE_ROCKING, EV_PHASE_ROLLING,
                     EV_REST, EV_UPLIFT, S_DYNAMIC, S_IMPACTS, S_IMPACTS_BEFORE_OVERTURN, S_T_OVERTURN,
                     S_T_THETA_MAX, S_T_UPLIFT, S_THETA_MAX, S_UPLIFT_TIME, S_UPLIFTS)


@njit(cache=True)
def new_summary():
    """A run summary (``S_*`` layout) before the run: times of events not yet seen are NaN, counts −1."""
    summary = np.zeros(N_SUMMARY)
    summary[S_T_UPLIFT] = math.nan
    summary[S_T_EXCEEDED] = math.nan
    summary[S_T_OVERTURN] = math.nan
    summary[S_IMPACTS_BEFORE_OVERTURN] = -1.0
    summary[S_IMPACTS_BEFORE_EXCEEDED] = -1.0
    return summary


@njit(cache=True, inline="always")
def store_event(ev_t, ev_kind, ev_y, diag, kind, t, y):
    """Count an event and store (t, kind, y) while the buffers have room."""
    diag[D_EVENTS] += 1
    k = diag[D_EVENTS_STORED]
    if k < ev_t.shape[0]:
        ev_t[k] = t
        ev_kind[k] = kind
        for i in range(4):
            ev_y[k, i] = y[i]
        diag[D_EVENTS_STORED] = k + 1


@njit(cache=True)
def phase_of(abs_theta, sp):
    """Contact phase at |θ| [rad]: 1 rolling on the curved extension (|θ| ≤ β, Eq 3.44), 2 rocking."""
    return 1 if (sp[P_RADIUS] != 0.0 and abs_theta <= sp[P_BETA]) else 2


@njit(cache=True)
def top_displacement(abs_theta, sp):
    """Column-top displacement u_B = 2u_C [m] at tilt |θ| (Eqs 3.1, 3.46, 3.51, 3.83), model kinematics."""
    U0, _, _, _, _, _ = normalised_kinematics(abs_theta, 1.0, phase_of(abs_theta, sp), sp)
    return 2.0 * sp[P_R] * U0


@njit(cache=True)
def top_displacements(theta, sp):
    """Column-top displacement u_B(θ) [m] for an array of tilts (sign of θ = side), model kinematics."""
    out = np.empty(theta.shape[0])
    for i in range(theta.shape[0]):
        a = abs(theta[i])
        u = top_displacement(min(a, sp[P_OVERTURN]), sp)
        out[i] = u if theta[i] >= 0.0 else -u
    return out


@njit(cache=True)
def energy_bound(y, rocking, side, phase, theta_max, sp):
    """True when the mechanical energy can no longer lift |θ| to θ_max (docs/early_termination.md).

    Valid once the ground is at rest: E never increases, and the potential is increasing in |θ| on
    [0, θc], so E < V(θ_max) < V(θc) means neither θ_max nor θc (nor overturning) can be reached.
    """
    if theta_max >= sp[P_THETA_C]:
        return False
    return total_energy(y, rocking, side, phase, sp) < potential_energy(theta_max, 1.0, phase_of(theta_max, sp), sp)


@njit(cache=True, inline="always")
def event_levels(sp):
    """The levels and constants of the transitions: (θc [rad], |θ| of overturning [rad], β [rad], curved
    extensions?, √c_r, rest velocity [rad/s], uplift hysteresis [rad/s²]) — ``sp`` in the eom layout."""
    return (sp[P_THETA_C], sp[P_OVERTURN], sp[P_BETA], sp[P_RADIUS] != 0.0, math.sqrt(sp[P_CR]), sp[P_REST_V],
            sp[P_HYST])


@njit(cache=True, inline="always")
def crossing_event(s0, s1, curved, phase, beta, theta_ot):
    """The event a monotone piece of sθ from ``s0`` to ``s1`` [rad] crosses, as (kind, level [rad]):
    rising — rolling → rocking at β (curved extensions), overturning at π/2; falling — rocking →
    rolling at β, impact at 0; (0, 0.0) for none.  The exceedance of θc is not terminal and is
    checked by the caller, which knows whether it was exceeded before."""
    if s1 > s0:
        if curved and phase == 1 and s0 < beta <= s1:
            return EV_PHASE_ROCKING, beta
        elif s1 >= theta_ot:
            return EV_OVERTURN, theta_ot
    elif s1 < s0:
        if curved and phase == 2 and s1 <= beta < s0:
            return EV_PHASE_ROLLING, beta
        elif s1 <= 0.0:
            return EV_IMPACT, 0.0
    return 0, 0.0


@njit(cache=True)
def enter_uplift(y, t, summary, ev_t, ev_kind, ev_y, diag):
    """Uplift at time t [s]: θ = θ̇ = 0 on the new side; counted, and its first time kept."""
    y[0] = 0.0
    y[1] = 0.0
    store_event(ev_t, ev_kind, ev_y, diag, EV_UPLIFT, t, y)
    summary[S_UPLIFTS] += 1.0
    if math.isnan(summary[S_T_UPLIFT]):
        summary[S_T_UPLIFT] = t


@njit(cache=True)
def enter_overturn(y, side, theta_ot, t, impacts, summary, ev_t, ev_kind, ev_y, diag):
    """Dynamic overturning at time t [s]: |θ| = π/2 reached after ``impacts`` impacts."""
    y[0] = side * theta_ot
    summary[S_DYNAMIC] = 1.0
    summary[S_T_OVERTURN] = t
    summary[S_IMPACTS_BEFORE_OVERTURN] = impacts
    if theta_ot > summary[S_THETA_MAX]:
        summary[S_THETA_MAX] = theta_ot
        summary[S_T_THETA_MAX] = t
    store_event(ev_t, ev_kind, ev_y, diag, EV_OVERTURN, t, y)


@njit(cache=True)
def change_phase(y, side, beta, ev_type, t, ev_t, ev_kind, ev_y, diag):
    """|θ| = β: rolling → rocking about the extension's edge, or back; returns the new phase."""
    y[0] = side * beta
    phase = 2 if ev_type == EV_PHASE_ROCKING else 1
    store_event(ev_t, ev_kind, ev_y, diag, ev_type, t, y)
    return phase


@njit(cache=True)
def impact(y, sqrt_cr, v_rest, impacts, t, t_rock_start, summary, ev_t, ev_kind, ev_y, diag):
    """Impact at θ = 0 (SPEC §3.4): θ̇⁺ = √c_r θ̇⁻, u̇_T unchanged; below the rest velocity [rad/s] the
    body comes to rest (its uplifted time is accounted).  Returns (still rocking, impacts)."""
    y[0] = 0.0
    store_event(ev_t, ev_kind, ev_y, diag, EV_IMPACT, t, y)
    impacts += 1
    summary[S_IMPACTS] = impacts
    y[1] = sqrt_cr * y[1]
    if abs(y[1]) < v_rest:
        y[1] = 0.0
        diag[D_REST] += 1
        store_event(ev_t, ev_kind, ev_y, diag, EV_REST, t, y)
        summary[S_UPLIFT_TIME] += t - t_rock_start
        return False, impacts
    return True, impacts
