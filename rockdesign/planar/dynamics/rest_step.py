"""The exact step of a resting podium: the fixed-base superstructure (Eq 4.3) under a piecewise-linear record.

Before uplift, and between coming to rest and the next uplift, the 2DOF podium is a linear damped
oscillator, ü_T + 2ζ_s ω_s u̇_T + ω_s² u_T = −ü_g, and a record's ü_g is linear between samples.  Its
solution over one step is therefore known in closed form (Nigam & Jennings 1968, the same recurrence
as the elastic spectra, SPEC §5): the engine steps the resting podium with it instead of a Runge–Kutta
method.  No tolerance is involved, so a resting phase is exact and costs a few multiplications per
step; the uplift criterion (Eq 4.7) is watched on the exact solution (engine.integrate).

The recurrence's coefficients are the elastic spectra's (:func:`rockdesign.motions.spectra.nigam_jennings_step`);
this module adds the Taylor series for very short steps, the uplift scan and the outputs — written
by hand because they are part of the numba integrator's inner loop.
"""
from __future__ import annotations

import math

from numba import njit

from ...motions.spectra import nigam_jennings_step
from .eom import P_OMEGA, P_TWO_DOF, P_ZETA, uplift_condition

TAYLOR_BELOW = 1e-3
"""ω_s·τ below which the step uses its Taylor series (to τ³): the closed-form coefficients lose digits
to cancellation as 1/(ω_s τ)² for very short steps (a step that ends at an event or a sample)."""

REST_STEP_PHASE = 0.4
"""Longest exact rest step, in radians of ω_s: steps split the sample interval so that ω_s h ≤ 0.4.
The quiet-step filter (quiet_steps.quiet_rest) reads u_T from the quintic Hermite interpolant of the
step's ends, whose error is at most (ω_s h)⁶/46080 ≈ 1e-7 of the amplitude: below its 1e-6 margin."""


@njit(cache=True)
def exact_rest_available(sp, kind_is_record):
    """True when a resting phase can use the closed form: a 2DOF podium (ω_s > 0, ζ_s < 1) under a
    piecewise-linear record; other excitations and overdamped superstructures use the Runge–Kutta step."""
    return kind_is_record and sp[P_TWO_DOF] != 0.0 and sp[P_OMEGA] > 0.0 and 0.0 <= sp[P_ZETA] < 1.0


@njit(cache=True)
def rest_state(u0, v0, a0, a1, tau, sp):
    """(u_T, u̇_T) [m, m/s] after a step τ [s] of the resting podium from (u0, v0), with ü_g linear
    from a0 to a1 [m/s²] over the step (Eq 4.3; Nigam & Jennings 1968)."""
    om = sp[P_OMEGA]
    ze = sp[P_ZETA]
    w2 = om * om
    if om * tau < TAYLOR_BELOW:
        # ü = −ü_g − ω²u − 2ζωu̇, u⃛ = −ü_g' − ω²u̇ − 2ζωü, u⁽⁴⁾ = −ω²ü − 2ζωu⃛ (ü_g'' = 0): the series to
        # τ⁴ in u and τ³ in u̇
        acc = -a0 - w2 * u0 - 2.0 * ze * om * v0
        jerk = (-(a1 - a0) / tau if tau > 0.0 else 0.0) - w2 * v0 - 2.0 * ze * om * acc
        snap = -w2 * acc - 2.0 * ze * om * jerk
        return (u0 + tau * (v0 + tau * (0.5 * acc + tau * (jerk / 6.0 + tau * snap / 24.0))),
                v0 + tau * (acc + tau * (0.5 * jerk + tau * snap / 6.0)))
    a11, a12, a21, a22, b11, b12, b21, b22 = nigam_jennings_step(om, ze, tau)
    return a11 * u0 + a12 * v0 + b11 * a0 + b12 * a1, a21 * u0 + a22 * v0 + b21 * a0 + b22 * a1


@njit(cache=True)
def rest_substeps(span, sp):
    """Number of equal exact steps for a rest interval of ``span`` [s] (ω_s h ≤ REST_STEP_PHASE)."""
    return max(1, int(math.ceil(sp[P_OMEGA] * span / REST_STEP_PHASE)))


@njit(cache=True)
def rest_uplift_scan(t, h, y, a0, a1, m_scan, hyst, sp):
    """The first uplift (Eq 4.7 above the hysteresis, either side) inside an exact rest step from
    state ``y`` over ``h`` [s] with ü_g linear from a0 to a1: the criterion is checked at ``m_scan``
    points of the exact solution and the first crossing is bisected on it to 1e-15 of the step.
    Returns (its position x ∈ (0, 1], or −1.0 for none; the side it uplifts to).

    The same scan as ``rest_phase.scan_podium_uplift`` on the Runge–Kutta dense output (pulses); kept as
    two loops because numba has no cheap way to pass the state evaluator as an argument."""
    x_prev = 0.0
    for k in range(1, m_scan + 1):
        x = k / m_scan
        ag = a0 + x * (a1 - a0)
        ut, utd = rest_state(y[2], y[3], a0, ag, x * h, sp)
        cp = uplift_condition(1.0, ag, ut, utd, sp) - hyst
        cm = uplift_condition(-1.0, ag, ut, utd, sp) - hyst
        if cp >= 0.0 or cm >= 0.0:
            s_up = 1.0 if cp >= 0.0 else -1.0
            xa = x_prev
            xb = x
            for _ in range(100):
                xm = 0.5 * (xa + xb)
                agm = a0 + xm * (a1 - a0)
                um, vm = rest_state(y[2], y[3], a0, agm, xm * h, sp)
                if uplift_condition(s_up, agm, um, vm, sp) - hyst >= 0.0:
                    xb = xm
                else:
                    xa = xm
                if xb - xa < 1e-15:
                    break
            return xb, s_up
        x_prev = x
    return -1.0, 0.0


@njit(cache=True)
def fill_rest_outputs(t_out, out_y, i_out, t_hi, t, h, y, a0, a1, sp):
    """Write output rows for t_out ≤ t_hi inside an exact rest step from (t, y) over h [s] (ü_g linear
    from a0 to a1), each from the exact solution; returns the next output index."""
    n_out = t_out.shape[0]
    while i_out < n_out and t_out[i_out] <= t_hi:
        tau = t_out[i_out] - t
        out_y[i_out, 0] = 0.0
        out_y[i_out, 1] = 0.0
        if tau <= 0.0:
            out_y[i_out, 2] = y[2]
            out_y[i_out, 3] = y[3]
        else:
            ut, utd = rest_state(y[2], y[3], a0, a0 + (tau / h) * (a1 - a0), tau, sp)
            out_y[i_out, 2] = ut
            out_y[i_out, 3] = utd
        i_out += 1
    return i_out
