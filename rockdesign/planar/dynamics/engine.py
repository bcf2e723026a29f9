"""The event-driven integrator: rest, uplift, rocking, impacts, phase changes, overturning (numba).

One kernel, :func:`integrate`, runs any planar system described by the parameter array ``sp`` of
:mod:`rockdesign.planar.dynamics.eom` under any excitation ``(kind, xp, samples)``.  Modes:

* **rest** — θ = θ̇ = 0.  Rigid systems wait for the ground acceleration to cross the uplift threshold
  (found exactly); a podium with an elastic superstructure steps the fixed-base SDOF (Eq 4.3) with
  its exact piecewise-linear solution under a record (:mod:`.rest_step`; Runge–Kutta under analytic
  pulses) and watches the Eq 4.7 criterion on that solution.  Uplift needs the criterion to exceed a tiny
  hysteresis (SPEC §3.6), so round-off cannot chatter uplift → impact → rest at one instant.
* **rocking** — DP5(4) steps that end exactly on every kink of ü_g (record samples, pulse ends);
  each step's dense output is scanned for impact (θ = 0), phase change (|θ| = β), overturning
  (|θ| = π/2) and the exceedance of θc; the peak |θ| is located where θ̇ = 0.  Terminal events are
  refined by re-stepping to the event and a Newton correction, so impact times are accurate to the
  integration tolerance, not to the interpolant.
* **impact** (SPEC §3.4) — θ̇⁺ = √c_r θ̇⁻, u̇_T unchanged, side flips; below the rest velocity the
  body comes to rest (ending Zeno sequences).

Counters make every run diagnosable; the kernel always returns (never hangs): the step count, the
event count and the step size are bounded, with a status code saying which bound stopped it.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ...motions.excitation import (EXC_SAMPLES, excitation_end, ground_acceleration, ground_acceleration_right,
                                  next_breakpoint)
from .eom import (rhs_given_acceleration, P_GAMMA, P_RADIUS, P_R, P_TWO_DOF, uplift_condition)
from .rest_step import exact_rest_available
from .events import next_threshold_crossing
from .transitions import (change_phase, event_levels, new_summary, energy_bound, enter_overturn, enter_uplift, impact, phase_of,
                          top_displacement)
from .demand import track_demand, track_impact_jump
from .dop853 import ERROR_EXPONENT_853, FSAL_ROW_853, N_STAGES_EXTENDED, dop853_dense, dop853_error_norm, dop853_step
from .rk import (ERROR_EXPONENT, MAX_FACTOR, MIN_FACTOR, SAFETY, dense_coefficients, dense_value,
                 dp5_step, error_norm, initial_step)

from .quiet_steps import quiet_rest, quiet_step, rest_uplift_coefficients
from .rest_phase import exact_rest_step, scan_podium_uplift
from .rocking_scan import scan_rocking_step
from .layout import (DOP853_BELOW_RTOL, D_EVENTS, D_NFEV, D_REFINE, D_REJECTED, D_STATUS,
                     D_STEPS, EV_OVERTURN, EV_PHASE_ROCKING, EV_PHASE_ROLLING, METHOD_AUTO,
                     METHOD_DOP853, METHOD_DP5, N_DIAG, O_ATOL, O_ENERGY_STOP,
                     O_H_MAX, O_MAX_EVENTS, O_MAX_STEPS, O_METHOD, O_RTOL, O_SCAN, O_STOP_EXCEEDED,
                     O_T_END, ST_ENERGY_BOUND, ST_OK, ST_OVERTURNED, ST_STEP_COLLAPSE, ST_STOPPED_EXCEEDED, ST_TOO_MANY_EVENTS,
                     ST_TOO_MANY_STEPS, S_DRIFT_MAX, S_EXCEEDED, S_THETA_MAX,
                     S_T_END, S_T_THETA_MAX, S_T_UPLIFT, S_UB_MAX,
                     S_UPLIFTS, S_UPLIFT_TIME)


@njit(cache=True)
def resolve_method(method, two_dof, rtol):
    """The stepper a run uses: ``method`` unless METHOD_AUTO, which picks by the work-precision data
    (benchmarks/bench_engine.py): DOP853 where DP5(4)'s steps are bound by the tolerance (the 2DOF
    podium's uplifted superstructure at rtol < :data:`DOP853_BELOW_RTOL`), DP5(4) where they are bound
    by the record samples (SDOF systems; the podium at loose tolerances)."""
    if method == METHOD_AUTO:
        return METHOD_DOP853 if (two_dof and rtol < DOP853_BELOW_RTOL) else METHOD_DP5
    return method


@njit(cache=True, inline="always")
def _rk_step(high, t, y, f0, h, K, y_new, ytmp, rocking, side, phase, kind, xp, samples, sp, n):
    """One step of the run's method (DOP853 if ``high``, else DP5(4)); returns the evaluations."""
    if high:
        return dop853_step(t, y, f0, h, K, y_new, ytmp, rocking, side, phase, kind, xp, samples, sp, n)
    return dp5_step(t, y, f0, h, K, y_new, ytmp, rocking, side, phase, kind, xp, samples, sp, n)


@njit(cache=True)
def _rigid_uplift_thresholds(hyst, sp):
    """(ü_lo, ü_hi) [m/s²]: a body at rest with a rigid superstructure uplifts to θ > 0 when ü_g ≤ ü_lo
    and to θ < 0 when ü_g ≥ ü_hi (Eq 4.7 with u_T = u̇_T = 0 is affine in ü_g), hysteresis included."""
    c0p = uplift_condition(1.0, 0.0, 0.0, 0.0, sp)
    c1p = uplift_condition(1.0, 1.0, 0.0, 0.0, sp) - c0p
    c0m = uplift_condition(-1.0, 0.0, 0.0, 0.0, sp)
    c1m = uplift_condition(-1.0, 1.0, 0.0, 0.0, sp) - c0m
    return (hyst - c0p) / c1p, (hyst - c0m) / c1m


@njit(cache=True, inline="always")
def _step_factor(high, y, y_new, K, h, rtol, atol, n, work, error_exponent, step_rejected):
    """(accepted, factor for the next step size) from the step's error norm: a rejected step shrinks
    (NaN errors by the largest factor); an accepted step grows at most by MAX_FACTOR, and not at all
    right after a rejection (as scipy: avoids reject/accept oscillation)."""
    if high:
        err = dop853_error_norm(y, y_new, K, h, rtol, atol, n, work)
    else:
        err = error_norm(y, y_new, K, h, rtol, atol, n)
    if not err <= 1.0:  # also catches NaN
        return False, (MIN_FACTOR if not err == err else max(MIN_FACTOR, SAFETY * err ** error_exponent))
    fac = MAX_FACTOR if err == 0.0 else min(MAX_FACTOR, SAFETY * err ** error_exponent)
    if step_rejected:
        fac = min(1.0, fac)
    return True, fac


@njit(cache=True)
def _step_to(high, t, y, f0, he, K, y_e, ytmp, rocking, side, phase, kind, xp, samples, sp, n, diag):
    """State ``y_e`` at t + he by one step of the run's method (he ≥ 0; he = 0 copies ``y``)."""
    if he > 0.0:
        diag[D_NFEV] += _rk_step(high, t, y, f0, he, K, y_e, ytmp, rocking, side, phase, kind, xp, samples, sp, n)
        diag[D_REFINE] += 1
    else:
        for i in range(4):
            y_e[i] = y[i]


@njit(cache=True)
def _fill_outputs(t_out, out_y, i_out, t_hi, t0, y, Q, h, y_end, use_dense, rest):
    """Write output rows for t_out ≤ t_hi; returns the next output index."""
    n_out = t_out.shape[0]
    while i_out < n_out and t_out[i_out] <= t_hi:
        if rest:
            out_y[i_out, 0] = 0.0
            out_y[i_out, 1] = 0.0
            out_y[i_out, 2] = y[2]
            out_y[i_out, 3] = y[3]
        elif t_out[i_out] == t_hi or not use_dense or h == 0.0:
            for i in range(4):
                out_y[i_out, i] = y_end[i]
        else:
            x = (t_out[i_out] - t0) / h
            for i in range(4):
                out_y[i_out, i] = dense_value(y, Q, h, x, i)
        i_out += 1
    return i_out


@njit(cache=True)
def _advance(t_out, out_y, i_out, t, t_new, tb, y, y_new, Q, h, K, fsal, f0, rocking, side, phase, kind, xp, samples,
             sp, diag):
    """Accept a step: write outputs up to t_new, move the state, keep the FSAL derivative — or, on a kink
    or jump of ü_g (a breakpoint), restart from its right limit.  Returns the next output index."""
    on = t_out.shape[0] >= 0     # run-time booleans (see integrate)
    i_out = _fill_outputs(t_out, out_y, i_out, t_new, t, y, Q, h, y_new, on, not on)
    for i in range(4):
        y[i] = y_new[i]
        f0[i] = K[fsal, i]
    if t_new == tb:
        # the FSAL derivative used ü_g(t + h); restart only where ü_g jumps there (a record's end, a
        # windowed pulse) — at a kink (a record sample) the left value is the right limit up to round-off
        ag_right = ground_acceleration_right(t_new, kind, xp, samples)
        ag_used = ground_acceleration(t + h, kind, xp, samples)
        if abs(ag_right - ag_used) > 1e-12 * (abs(ag_right) + abs(ag_used)):
            rhs_given_acceleration(ag_right, y, f0, rocking, side, phase, sp)
            diag[D_NFEV] += 1
    return i_out


@njit(cache=True)
def _refine_event(high, t, y, f0, x_e, h, level, sgn, K, y_e, ytmp, rocking, side, phase, kind, xp, samples, sp, n,
                  diag):
    """Re-step from t to the event and Newton-correct so that sgn·θ − level = 0 to round-off.

    Returns the refined event time; ``y_e`` holds the state there.
    """
    he = x_e * h
    for _ in range(4):
        if he <= 0.0:
            for i in range(4):
                y_e[i] = y[i]
            return t
        diag[D_NFEV] += _rk_step(high, t, y, f0, he, K, y_e, ytmp, rocking, side, phase, kind, xp, samples, sp, n)
        diag[D_REFINE] += 1
        g = sgn * y_e[0] - level
        gd = sgn * y_e[1]
        if gd == 0.0:
            break
        dh = -g / gd
        if abs(dh) <= 1e-14 * max(1.0, abs(t + he)) or abs(g) <= 1e-15:
            break
        he_new = min(max(he + dh, 0.0), h)
        if he_new == he:
            break
        he = he_new
    return t + he


@njit(cache=True)
def integrate(sp, kind, xp, samples, y_init, side_init, t0, opts, t_out, out_y, ev_t, ev_kind, ev_y):
    """Run one time-history analysis.

    Args:
        sp: system parameters (``eom.P_*`` layout).
        kind, xp, samples: the excitation (see :mod:`rockdesign.motions.excitation`).
        y_init: initial (θ, θ̇, u_T, u̇_T); θ = θ̇ = 0 starts at rest.
        side_init: side of an initial tilt (±1), ignored at rest.
        t0: start time [s]; opts: ``O_*`` options (t_end, rtol, atol, ...).
        t_out: sorted output times; ``out_y`` receives the state there (len(t_out) × 4).
        ev_t, ev_kind, ev_y: event buffers (capacity = their length; extra events are counted only).

    Returns:
        (summary ``S_*`` array, diagnostics ``D_*`` int array, number of output rows written).
    """
    summary = new_summary()
    diag = np.zeros(N_DIAG, dtype=np.int64)
    t_end = opts[O_T_END]
    rtol = opts[O_RTOL]
    atol = opts[O_ATOL]
    h_max = opts[O_H_MAX]
    max_steps = opts[O_MAX_STEPS]
    energy_stop = opts[O_ENERGY_STOP] != 0.0
    stop_exceeded = opts[O_STOP_EXCEEDED] != 0.0
    m_scan = int(opts[O_SCAN])
    max_events = opts[O_MAX_EVENTS]
    two_dof = sp[P_TWO_DOF] != 0.0
    n = 4 if two_dof else 2
    theta_c, theta_ot, beta, curved, sqrt_cr, v_rest, hyst = event_levels(sp)
    # |u_B(θ)| ≤ 2R(1 + 2r/R)|θ| (|dU/dθ| ≤ 1 + 2r/R for every contact phase): scan points whose bound
    # cannot raise the drift maximum skip the trigonometry of u_B
    drift_slope = 2.0 * sp[P_R] * (1.0 + 2.0 * sp[P_RADIUS] / sp[P_R])
    t_exc = excitation_end(kind, xp, samples)
    track_cap = (not two_dof) and sp[P_GAMMA] != 0.0     # a frame's rigid cap beam (SPEC §13)
    high = resolve_method(int(opts[O_METHOD]), two_dof, rtol) == METHOD_DOP853
    error_exponent = ERROR_EXPONENT_853 if high else ERROR_EXPONENT
    fsal = FSAL_ROW_853 if high else 6
    error_order = 7 if high else 4

    # run-time booleans for flag arguments: numba compiles a separate specialisation of a kernel for
    # every literal True/False/int it is called with (compile time, docs/engine.md)
    on = opts.shape[0] > 0
    off = not on
    c_theta = opts.shape[0] - opts.shape[0]     # component indices θ, θ̇ (run-time ints, same reason)
    c_rate = c_theta + 1
    y = np.zeros(4)
    for i in range(4):
        y[i] = y_init[i]
    f0 = np.zeros(4)
    y_new = np.zeros(4)
    y_e = np.zeros(4)
    ytmp = np.zeros(4)
    ftmp = np.zeros(4)
    K = np.zeros((N_STAGES_EXTENDED, 4))
    Q = np.zeros((4, 7 if high else 4))     # dense-output powers x¹ … x⁷ (DOP853) or x¹ … x⁴ (DP5(4))
    work = np.zeros(8)

    thr_lo, thr_hi = _rigid_uplift_thresholds(hyst, sp)
    rest_coef = rest_uplift_coefficients(sp)
    # a resting podium under a record is stepped exactly (rest_step.py), not by Runge–Kutta
    rest_exact = exact_rest_available(sp, kind == EXC_SAMPLES)

    t = t0
    rocking = y[0] != 0.0 or y[1] != 0.0
    side = side_init
    if rocking:
        if y[0] != 0.0:
            side = 1.0 if y[0] > 0.0 else -1.0
        else:
            side = 1.0 if y[1] > 0.0 else -1.0
    phase = phase_of(abs(y[0]), sp)
    impacts = c_theta   # a run-time 0: a literal would compile the event kernels twice
    i_out = 0
    n_out = t_out.shape[0]
    while i_out < n_out and t_out[i_out] < t:
        i_out += 1
    status = ST_OK
    need_start = True
    fresh_start = True
    step_rejected = False
    h = 0.0
    t_rock_start = t
    if rocking:
        summary[S_UPLIFTS] = 1.0
        summary[S_T_UPLIFT] = t
        summary[S_THETA_MAX] = abs(y[0])
        summary[S_T_THETA_MAX] = t

    while t < t_end:
        if diag[D_STEPS] >= max_steps:
            status = ST_TOO_MANY_STEPS
            break
        if diag[D_EVENTS] >= max_events:
            status = ST_TOO_MANY_EVENTS
            break
        # ---------------------------------------------------------------- rigid rest
        if not rocking and not two_dof:
            if t >= t_exc:
                i_out = _fill_outputs(t_out, out_y, i_out, t_end, t, y, Q, 0.0, y, off, on)
                t = t_end
                break
            tu, s_up = next_threshold_crossing(t, t_end, thr_lo, thr_hi, kind, xp, samples)
            if tu > t_end:
                i_out = _fill_outputs(t_out, out_y, i_out, t_end, t, y, Q, 0.0, y, off, on)
                t = t_end
                break
            i_out = _fill_outputs(t_out, out_y, i_out, tu, t, y, Q, 0.0, y, off, on)
            t = t_rock_start = tu
            rocking, side, phase = True, s_up, 1
            enter_uplift(y, t, summary, ev_t, ev_kind, ev_y, diag)
            need_start = fresh_start = True
            continue
        # ---------------------------------------------------------------- podium at rest: exact steps
        if not rocking and rest_exact:
            t, h, i_out, s_up = exact_rest_step(t, h, t_end, y, y_new, f0, ftmp, m_scan, hyst, kind, xp, samples,
                                                 sp, rest_coef, t_out, out_y, i_out, summary, ev_t, ev_kind, ev_y,
                                                 diag)
            track_demand(t, y, 0.0, rocking, side, phase, 0.0, sp, summary)
            if s_up != 0.0:
                t_rock_start = t
                rocking, side, phase = True, s_up, 1
                need_start = fresh_start = True
                continue
            if energy_stop and t >= t_exc and energy_bound(y, rocking, side, phase + 0, summary[S_THETA_MAX], sp):
                status = ST_ENERGY_BOUND
                break
            continue
        # ---------------------------------------------------------------- a step
        if need_start:
            rhs_given_acceleration(ground_acceleration_right(t, kind, xp, samples), y, f0, rocking, side, phase, sp)
            diag[D_NFEV] += 1
            if fresh_start or h == 0.0:
                # after uplift or at the start: no step-size history to continue from
                tb0 = min(next_breakpoint(t, kind, xp, samples), t_end)
                h0 = initial_step(t, y, f0, tb0, rtol, atol, ytmp, ftmp, rocking, side, phase, kind, xp,
                                  samples, sp, n, error_order)
                diag[D_NFEV] += 1
                h = h0 if h == 0.0 else min(h, h0) if h0 > 0.0 else h
            need_start = False
            fresh_start = False
        tb = min(next_breakpoint(t, kind, xp, samples), t_end)
        span = tb - t
        if span <= 0.0:
            span = t_end - t
        h = min(h, span, h_max)
        if h <= 1e-15 * max(1.0, abs(t)):
            if span <= 1e-15 * max(1.0, abs(t)):
                # sliver before a breakpoint: jump onto it
                h = span
            else:
                status = ST_STEP_COLLAPSE
                break
        diag[D_NFEV] += _rk_step(high, t, y, f0, h, K, y_new, ytmp, rocking, side, phase, kind, xp, samples, sp, n)
        diag[D_STEPS] += 1
        accepted, fac = _step_factor(high, y, y_new, K, h, rtol, atol, n, work, error_exponent, step_rejected)
        if not accepted:
            diag[D_REJECTED] += 1
            h *= fac
            step_rejected = True
            continue
        step_rejected = False
        h_next = h * fac
        t_new = t + h
        if t_new > tb - 1e-13 * max(1.0, abs(tb)) and tb < math.inf:
            t_new = tb
        # a quiet step needs no dense output (no output time inside it; see quiet_step, quiet_rest)
        if i_out < n_out and t_out[i_out] < t_new:
            quiet = False
        elif rocking:
            quiet = quiet_step(h, y, y_new, f0, K[fsal], m_scan, side, phase, curved, beta, theta_ot, theta_c,
                                summary[S_EXCEEDED] != 0.0, two_dof, drift_slope, summary[S_DRIFT_MAX], sp)
        else:
            quiet = quiet_rest(t, h, y, y_new, f0, K[fsal], m_scan, hyst, kind, xp, samples, rest_coef)
        if quiet:
            # nothing inside the step: its end is the only peak candidate
            if rocking and side * y_new[0] > summary[S_THETA_MAX]:
                summary[S_THETA_MAX] = side * y_new[0]
                summary[S_T_THETA_MAX] = t + h
        elif high:
            diag[D_NFEV] += dop853_dense(t, y, y_new, h, K, Q, ytmp, rocking, side, phase, kind, xp, samples, sp, n,
                                         work)
        else:
            dense_coefficients(K, Q, n)

        # ------------------------------------------------------------ rest of a 2DOF podium
        if not rocking:
            ev_x, ev_side = (-1.0, 0.0) if quiet else scan_podium_uplift(t, h, y, y_new, Q, m_scan, hyst, kind, xp,
                                                                           samples, sp)
            if ev_x >= 0.0:
                he = ev_x * h
                _step_to(high, t, y, f0, he, K, y_e, ytmp, rocking, side, phase, kind, xp, samples, sp, n, diag)
                t_e = t + he
                i_out = _fill_outputs(t_out, out_y, i_out, t_e, t, y, Q, h, y_e, on, off)
                t = t_rock_start = t_e
                for i in range(4):
                    y[i] = y_e[i]
                rocking, side, phase = True, ev_side, 1
                enter_uplift(y, t, summary, ev_t, ev_kind, ev_y, diag)
                need_start = fresh_start = True
                continue
            ev_type = 0
            ev_level = 0.0
        elif quiet:
            ev_type = 0
            ev_level = 0.0
        else:
            # -------------------------------------------------------- rocking: scan for events
            ev_type, ev_x, ev_level = scan_rocking_step(t, h, y, y_new, Q, ytmp, m_scan, side, phase, curved, beta,
                                                         theta_ot, theta_c, two_dof, drift_slope, impacts,
                                                         stop_exceeded, c_theta, c_rate, summary, ev_t, ev_kind,
                                                         ev_y, diag, sp)
        if ev_type == 0:
            # accept the step
            i_out = _advance(t_out, out_y, i_out, t, t_new, tb, y, y_new, Q, h, K, fsal, f0, rocking, side,
                             phase, kind, xp, samples, sp, diag)
            t = t_new
            h = h_next
            if track_cap:
                # θ̈ at the new state is the FSAL derivative (ü_g at t, or its right limit after a restart)
                track_demand(t, y, f0[1], rocking, side, phase, ground_acceleration(t, kind, xp, samples), sp,
                             summary)
            elif two_dof:
                track_demand(t, y, 0.0, rocking, side, phase, 0.0, sp, summary)
            if energy_stop and t >= t_exc and energy_bound(y, rocking, side, phase + 0, summary[S_THETA_MAX], sp):
                status = ST_ENERGY_BOUND
                if rocking:
                    summary[S_UPLIFT_TIME] += t - t_rock_start
                break
            continue

        # a terminal event inside the step -----------------------------------------------
        if ev_type == -1:
            for i in range(4):
                y_e[i] = dense_value(y, Q, h, ev_x, i)
            t_e = t + ev_x * h
        else:
            t_e = _refine_event(high, t, y, f0, ev_x, h, ev_level, side, K, y_e, ytmp, rocking, side, phase, kind,
                                xp, samples, sp, n, diag)
        i_out = _fill_outputs(t_out, out_y, i_out, t_e, t, y, Q, h, y_e, on, off)
        t = t_e
        for i in range(4):
            y[i] = y_e[i]
        ag_e = ground_acceleration(t, kind, xp, samples)
        track_demand(t, y, math.nan, rocking, side, phase, ag_e, sp, summary)
        if ev_type == -1:
            status = ST_STOPPED_EXCEEDED
            if theta_c > summary[S_THETA_MAX]:
                summary[S_THETA_MAX] = theta_c
                summary[S_T_THETA_MAX] = t
            summary[S_UPLIFT_TIME] += t - t_rock_start
            break
        if ev_type == EV_OVERTURN:
            enter_overturn(y, side, theta_ot, t, impacts, summary, ev_t, ev_kind, ev_y, diag)
            status = ST_OVERTURNED
            summary[S_UPLIFT_TIME] += t - t_rock_start
            break
        if ev_type == EV_PHASE_ROCKING or ev_type == EV_PHASE_ROLLING:
            phase = change_phase(y, side, beta, ev_type, t, ev_t, ev_kind, ev_y, diag)
            need_start = True
            continue
        # impact
        thd_before = y[1]
        rocking, impacts = impact(y, sqrt_cr, v_rest, impacts, t, t_rock_start, summary, ev_t, ev_kind, ev_y, diag)
        phase = 1
        track_impact_jump(thd_before, y[1], side, -side, sp, summary)
        if rocking:
            side = -side
        else:
            fresh_start = True
        # after the impact map: u̇_B jumps with θ̇, u̇_T does not (Eq 4.21) — f_s on the other side
        track_demand(t, y, math.nan, rocking, side, phase, ag_e, sp, summary)
        need_start = True
        if energy_stop and t >= t_exc and energy_bound(y, rocking, side, phase + 0, summary[S_THETA_MAX], sp):
            status = ST_ENERGY_BOUND
            if rocking:
                summary[S_UPLIFT_TIME] += t - t_rock_start
                rocking = False   # accounted for
            break

    if rocking and status == ST_OK:
        summary[S_UPLIFT_TIME] += t - t_rock_start
    # remaining output rows (after overturning or an early stop) repeat the last state
    while i_out < n_out and t_out[i_out] <= t + 1e-12:
        for i in range(4):
            out_y[i_out, i] = y[i]
        i_out += 1
    summary[S_T_END] = t
    summary[S_UB_MAX] = top_displacement(min(summary[S_THETA_MAX], theta_ot), sp)
    diag[D_STATUS] = status
    return summary, diag, i_out
