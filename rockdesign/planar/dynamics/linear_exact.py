"""Closed-form solution of the linearized SDOF equations under piecewise-linear excitation (SPEC §3.8).

Between events and within one record segment (ü_g = a0 + a1 τ), the linearized equation
θ̈ − kθ = −P(c + ü_g/g) has constant coefficients: P = p̂², k = P(1 − 2ρ) in phase I of a curved base
(k = P for blocks, flat extensions and phase II), c = sα (block, phase I) or s(α + 2ρβ) (phase II).
Its solution is θ_p + A cosh(√k τ) + B sinh(√k τ) (cos/sin when ρ > ½, a cubic when ρ = ½) with
θ_p the particular solution for linear forcing.  Extrema of θ are found analytically (a quadratic
in e^(√k τ), a cosine equation, or a quadratic in τ), so every segment splits into monotone pieces
on which impact (θ = 0), phase change (|θ| = β), overturning (|θ| = π/2) and the exceedance of θc
are single, bracketed roots — found to machine precision.  This is the engine's accuracy reference
and the user-selectable ``linear-exact`` model.  Rest and uplift follow the same rules as the
integrator (SPEC §3.6).  Analytic pulses are passed in sampled (see :func:`sampled_pulse`).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ...motions.excitation import (EXC_NONE, excitation_end, ground_acceleration, ground_acceleration_right,
                                  next_breakpoint)
from .layout import (D_EVENTS, D_STATUS, D_STEPS, EV_EXCEEDED, EV_OVERTURN, EV_PHASE_ROCKING, EV_PHASE_ROLLING, N_DIAG,
                     ST_ENERGY_BOUND, ST_OK, ST_OVERTURNED, ST_STOPPED_EXCEEDED, ST_TOO_MANY_EVENTS, S_EXCEEDED, S_IMPACTS_BEFORE_EXCEEDED, S_THETA_MAX,
                     S_T_END, S_T_EXCEEDED, S_T_THETA_MAX, S_T_UPLIFT, S_UB_MAX,
                     S_UPLIFTS, S_UPLIFT_TIME)
from .eom import (P_ALPHA, P_BETA, P_G, P_GAMMA, P_LAM, P_R, P_RADIUS, P_TWO_RHO, potential_energy, total_energy, uplift_condition)
from .events import next_threshold_crossing
from .transitions import (change_phase, event_levels, new_summary, crossing_event, energy_bound, enter_overturn, enter_uplift, impact,
                          store_event, top_displacement)

PULSE_SAMPLES_PER_PERIOD = 64000
"""Analytic pulses are sampled at T_p/64000 for the closed form, which is exact for that piecewise-linear
input but not for the analytic pulse: the chord lies inside the curve by ≈ h² max|ü_g''|/8, which
delays uplift and shifts every later event by O(h²).  Measured against scipy DOP853 at rtol 1e-13 on
the linearized equations with the analytic antisymmetric Ricker (Table 3.4 B1, a_p = 0.38 g,
T_p = 0.95 s; tests/dynamics/test_linear_exact_pulses.py): first impact 1.6e-6 s early and θ_max
1.2e-6 rad low at T_p/2000 (the former default), 1.5e-9 s and 1.2e-9 rad at T_p/64000 (error ∝ h²),
while the integrator (``model="linear"``), which evaluates the pulse analytically, agrees with scipy to
1e-13 s.  On records (piecewise linear by definition) the closed form is exact."""


@njit(cache=True)
def _coefficients(theta0, v0, a0, a1, side, phase, sp):
    """(mode, ω, θ0, v0, p0, p1) of θ(τ) on one segment; mode 1: cosh/sinh, −1: cos/sin, 0: cubic.

    θ(τ) = θ0 C + v0 S − p0 (C − 1) − p1 (S − τ) with C = cosh ωτ, S = sinh(ωτ)/ω (or cos, sin), i.e.
    the particular solution p0 + p1 τ plus the homogeneous part matching θ0, v0.  Written this way,
    with C − 1 and S − τ evaluated without cancellation, the start of a rocking interval (θ0 = v0 = 0
    at uplift) keeps its sign to round-off.  For mode 0, (θ0, v0, p0, p1) hold the cubic
    θ = θ0 + v0 τ + p0 τ² + p1 τ³.
    """
    gam = sp[P_GAMMA]
    P = sp[P_G] / sp[P_R] * (1.0 + 2.0 * gam) / (sp[P_LAM] + 1.0 + 4.0 * gam)
    alpha = sp[P_ALPHA]
    tr = sp[P_TWO_RHO]
    if sp[P_RADIUS] != 0.0 and phase == 1:
        kappa = 1.0 - tr
        c = side * alpha
    elif sp[P_RADIUS] != 0.0:
        kappa = 1.0
        c = side * (alpha + tr * sp[P_BETA])
    else:
        kappa = 1.0
        c = side * alpha
    k = P * kappa
    g = sp[P_G]
    if abs(kappa) < 1e-12:
        return 0, 0.0, theta0, v0, -0.5 * P * (c + a0 / g), -P * a1 / (6.0 * g)
    p0 = P / k * (c + a0 / g)
    p1 = P / k * a1 / g
    if k > 0.0:
        return 1, math.sqrt(k), theta0, v0, p0, p1
    return -1, math.sqrt(-k), theta0, v0, p0, p1


@njit(cache=True)
def _c_minus_1(x, mode):
    """cosh x − 1 (mode 1) or cos x − 1 (mode −1) without cancellation."""
    h = math.sinh(0.5 * x) if mode == 1 else math.sin(0.5 * x)
    return 2.0 * h * h if mode == 1 else -2.0 * h * h


@njit(cache=True)
def _s_minus_x(x, mode):
    """sinh x − x (mode 1) or sin x − x (mode −1) without cancellation."""
    if abs(x) < 0.5:
        x2 = x * x if mode == 1 else -x * x
        return x * x2 / 6.0 * (1.0 + x2 / 20.0 * (1.0 + x2 / 42.0 * (1.0 + x2 / 72.0 * (1.0 + x2 / 110.0 * (
            1.0 + x2 / 156.0)))))
    return (math.sinh(x) if mode == 1 else math.sin(x)) - x


@njit(cache=True)
def _theta(tau, mode, om, th0, v0, p0, p1):
    if mode == 0:
        return th0 + tau * (v0 + tau * (p0 + tau * p1))
    x = om * tau
    cm1 = _c_minus_1(x, mode)
    smx = _s_minus_x(x, mode)
    # θ0 C + v0 S − p0 (C − 1) − p1 (S − τ), S = sinh(x)/ω = τ + (sinh x − x)/ω
    return th0 + (th0 - p0) * cm1 + v0 * tau + (v0 - p1) * smx / om


@njit(cache=True)
def _thetadot(tau, mode, om, th0, v0, p0, p1):
    if mode == 0:
        return v0 + tau * (2.0 * p0 + 3.0 * tau * p1)
    x = om * tau
    sn = math.sinh(x) if mode == 1 else -math.sin(x)
    cm1 = _c_minus_1(x, mode)
    # ω(θ0 − p0) sinh + v0 cosh − p1 (cosh − 1)   [cos/sin: −ω(θ0 − p0) sin + v0 cos − p1 (cos − 1)]
    return om * (th0 - p0) * sn + v0 + (v0 - p1) * cm1


@njit(cache=True)
def _quadratic_roots(qa, qb, qc, out):
    """Real roots of qa x² + qb x + qc = 0 into out[0:2]; returns their number (stable formula)."""
    if qa == 0.0:
        if qb == 0.0:
            return 0
        out[0] = -qc / qb
        return 1
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0:
        return 0
    sq = math.sqrt(disc)
    q = -0.5 * (qb + math.copysign(sq, qb))
    if q == 0.0:
        out[0] = 0.0
        return 1
    out[0] = q / qa
    out[1] = qc / q
    return 2


@njit(cache=True)
def _extrema(T, mode, om, th0, v0, p0, p1, out, tmp):
    """Times τ ∈ (0, T) where θ̇ = 0, sorted, into ``out``; returns their number."""
    n = 0
    if mode != 0:
        # θ = p0 + p1 τ + A cosh + B sinh (or cos/sin): the homogeneous coefficients
        A = th0 - p0
        B = (v0 - p1) / om
    else:
        A = th0
        B = v0
    if mode == 1:
        m = _quadratic_roots(0.5 * om * (A + B), p1, -0.5 * om * (A - B), tmp)
        for i in range(m):
            if tmp[i] > 0.0:
                tau = math.log(tmp[i]) / om
                if 0.0 < tau < T:
                    out[n] = tau
                    n += 1
    elif mode == -1:
        rc = math.sqrt(A * A + B * B)
        if rc > 0.0:
            q = -p1 / (om * rc)
            if -1.0 <= q <= 1.0:
                phi = math.atan2(A, B)
                base = math.acos(q)
                for sgn in (1.0, -1.0):
                    x0 = sgn * base - phi
                    # shift into [0, 2π) then enumerate the few periods inside (0, ωT)
                    x0 = x0 - 2.0 * math.pi * math.floor(x0 / (2.0 * math.pi))
                    x = x0
                    while x < om * T and n < out.shape[0]:
                        if x > 0.0:
                            out[n] = x / om
                            n += 1
                        x += 2.0 * math.pi
    else:
        m = _quadratic_roots(3.0 * p1, 2.0 * p0, B, tmp)
        for i in range(m):
            if 0.0 < tmp[i] < T:
                out[n] = tmp[i]
                n += 1
    # sort (n ≤ a few)
    for i in range(1, n):
        v = out[i]
        j = i - 1
        while j >= 0 and out[j] > v:
            out[j + 1] = out[j]
            j -= 1
        out[j + 1] = v
    return n


@njit(cache=True)
def _level_root(ta, tb, level, sgn, mode, om, A, B, p0, p1):
    """τ ∈ [ta, tb] with sgn·θ(τ) = level on a monotone piece (bisection to round-off + Newton polish)."""
    fa = sgn * _theta(ta, mode, om, A, B, p0, p1) - level
    fb = sgn * _theta(tb, mode, om, A, B, p0, p1) - level
    if fa == 0.0:
        return ta
    if fb == 0.0:
        return tb
    for _ in range(200):
        tm = 0.5 * (ta + tb)
        if tm <= ta or tm >= tb:
            break
        fm = sgn * _theta(tm, mode, om, A, B, p0, p1) - level
        if fm == 0.0:
            return tm
        if (fm > 0.0) == (fa > 0.0):
            ta, fa = tm, fm
        else:
            tb, fb = tm, fm
    return ta if abs(fa) < abs(fb) else tb


@njit(cache=True)
def integrate_linear_exact(sp, kind, xp, samples, y_init, side_init, t0, t_end, t_out, out_y, ev_t, ev_kind,
                           ev_y, max_events, stop_exceeded, energy_stop):
    """Exact event-driven solution of the linearized SDOF equations (same outputs as ``engine.integrate``)."""
    summary = new_summary()
    diag = np.zeros(N_DIAG, dtype=np.int64)
    theta_c, theta_ot, beta, curved, sqrt_cr, v_rest, hyst = event_levels(sp)
    gam = sp[P_GAMMA]
    P = sp[P_G] / sp[P_R] * (1.0 + 2.0 * gam) / (sp[P_LAM] + 1.0 + 4.0 * gam)
    chunk = 0.5 / math.sqrt(P * max(1.0, abs(1.0 - sp[P_TWO_RHO])))
    t_exc = excitation_end(kind, xp, samples)
    c0p = uplift_condition(1.0, 0.0, 0.0, 0.0, sp)
    c1p = uplift_condition(1.0, 1.0, 0.0, 0.0, sp) - c0p
    c0m = uplift_condition(-1.0, 0.0, 0.0, 0.0, sp)
    c1m = uplift_condition(-1.0, 1.0, 0.0, 0.0, sp) - c0m
    thr_lo = (hyst - c0p) / c1p
    thr_hi = (hyst - c0m) / c1m
    ext = np.zeros(8)
    tmp = np.zeros(2)
    ystate = np.zeros(4)

    th = y_init[0]
    v = y_init[1]
    t = t0
    rocking = th != 0.0 or v != 0.0
    side = side_init
    if rocking:
        side = (1.0 if th > 0.0 else -1.0) if th != 0.0 else (1.0 if v > 0.0 else -1.0)
        summary[S_UPLIFTS] = 1.0
        summary[S_T_UPLIFT] = t
        summary[S_THETA_MAX] = abs(th)
    phase = 1 if (curved and abs(th) <= beta) else 2
    impacts = 0
    status = ST_OK
    i_out = 0
    n_out = t_out.shape[0]
    while i_out < n_out and t_out[i_out] < t:
        i_out += 1
    t_rock = t

    while t < t_end:
        if diag[D_EVENTS] >= max_events:
            status = ST_TOO_MANY_EVENTS
            break
        if not rocking:
            if t >= t_exc:
                tu = math.inf
                s_up = 0.0
            else:
                tu, s_up = next_threshold_crossing(t, t_end, thr_lo, thr_hi, kind, xp, samples)
            while i_out < n_out and t_out[i_out] <= min(tu, t_end):
                out_y[i_out, 0] = 0.0
                out_y[i_out, 1] = 0.0
                i_out += 1
            if tu > t_end:
                t = t_end
                break
            t = tu
            rocking = True
            side = s_up
            phase = 1
            th = 0.0
            v = 0.0
            enter_uplift(ystate, t, summary, ev_t, ev_kind, ev_y, diag)
            t_rock = t
            continue
        te = min(next_breakpoint(t, kind, xp, samples), t_end, t + chunk)
        T = te - t
        if T <= 0.0:
            t = te
            continue
        diag[D_STEPS] += 1
        if t >= t_exc:
            a0 = 0.0
            a_end = 0.0
        else:
            # the segment's own line: right limit at its start, left limit at its end
            a0 = ground_acceleration_right(t, kind, xp, samples)
            a_end = ground_acceleration(te, kind, xp, samples)
        a1 = (a_end - a0) / T
        mode, om, A, B, p0, p1 = _coefficients(th, v, a0, a1, side, phase, sp)
        n_ext = _extrema(T, mode, om, A, B, p0, p1, ext, tmp)
        ev_type = 0
        ev_tau = T
        ev_level = 0.0
        pa = 0.0
        sa = side * th
        for piece in range(n_ext + 1):
            pb = ext[piece] if piece < n_ext else T
            sb = side * _theta(pb, mode, om, A, B, p0, p1)
            ev_type, ev_level = crossing_event(sa, sb, curved, phase, beta, theta_ot)
            if sb > sa:
                # rising: the exceedance of θc (non-terminal unless stop_exceeded) may come first
                if summary[S_EXCEEDED] == 0.0 and sa < theta_c <= sb:
                    tc = _level_root(pa, pb, theta_c, side, mode, om, A, B, p0, p1)
                    if ev_type == 0 or tc <= _level_root(pa, pb, ev_level, side, mode, om, A, B, p0, p1):
                        summary[S_EXCEEDED] = 1.0
                        summary[S_T_EXCEEDED] = t + tc
                        summary[S_IMPACTS_BEFORE_EXCEEDED] = impacts
                        ystate[0] = _theta(tc, mode, om, A, B, p0, p1)
                        ystate[1] = _thetadot(tc, mode, om, A, B, p0, p1)
                        store_event(ev_t, ev_kind, ev_y, diag, EV_EXCEEDED, t + tc, ystate)
                        if stop_exceeded:
                            ev_type = -1
                            ev_tau = tc
                            break
            if ev_type > 0:
                ev_tau = pa if sa == ev_level else _level_root(pa, pb, ev_level, side, mode, om, A, B, p0, p1)
                break
            if sb > summary[S_THETA_MAX]:
                summary[S_THETA_MAX] = sb
                summary[S_T_THETA_MAX] = t + pb
            pa = pb
            sa = sb
        # outputs up to the end of this piece of history
        t_stop = t + ev_tau
        while i_out < n_out and t_out[i_out] <= t_stop:
            tau = t_out[i_out] - t
            out_y[i_out, 0] = _theta(tau, mode, om, A, B, p0, p1)
            out_y[i_out, 1] = _thetadot(tau, mode, om, A, B, p0, p1)
            i_out += 1
        th_new = _theta(ev_tau, mode, om, A, B, p0, p1)
        v_new = _thetadot(ev_tau, mode, om, A, B, p0, p1)
        t = t_stop if ev_type != 0 else te
        th = th_new
        v = v_new
        if ev_type == 0:
            if energy_stop and t >= t_exc and summary[S_THETA_MAX] < theta_c:
                ystate[0] = th
                ystate[1] = v
                e = total_energy(ystate, True, side, phase, sp)
                if e < potential_energy(summary[S_THETA_MAX], 1.0,
                                        1 if (curved and summary[S_THETA_MAX] <= beta) else 2, sp):
                    status = ST_ENERGY_BOUND
                    break
            continue
        if ev_type == -1:
            status = ST_STOPPED_EXCEEDED
            if theta_c > summary[S_THETA_MAX]:
                summary[S_THETA_MAX] = theta_c
                summary[S_T_THETA_MAX] = t
            break
        ystate[0] = th
        ystate[1] = v
        if ev_type == EV_OVERTURN:
            enter_overturn(ystate, side, theta_ot, t, impacts, summary, ev_t, ev_kind, ev_y, diag)
            th = ystate[0]
            status = ST_OVERTURNED
            break
        if ev_type == EV_PHASE_ROCKING or ev_type == EV_PHASE_ROLLING:
            phase = change_phase(ystate, side, beta, ev_type, t, ev_t, ev_kind, ev_y, diag)
            th = ystate[0]
            continue
        rocking, impacts = impact(ystate, sqrt_cr, v_rest, impacts, t, t_rock, summary, ev_t, ev_kind, ev_y, diag)
        th = ystate[0]
        v = ystate[1]
        if rocking:
            side = -side
            phase = 1
            if energy_stop and t >= t_exc:
                ystate[0] = th
                ystate[1] = v
                if energy_bound(ystate, True, side, phase, summary[S_THETA_MAX], sp):
                    status = ST_ENERGY_BOUND
                    break
    if rocking:
        summary[S_UPLIFT_TIME] += t - t_rock
    while i_out < n_out and t_out[i_out] <= t + 1e-12:
        out_y[i_out, 0] = th
        out_y[i_out, 1] = v
        i_out += 1
    summary[S_T_END] = t
    summary[S_UB_MAX] = top_displacement(min(summary[S_THETA_MAX], theta_ot), sp)
    diag[D_STATUS] = status
    return summary, diag, i_out


def sampled_pulse(motion, samples_per_period: int = PULSE_SAMPLES_PER_PERIOD):
    """A piecewise-linear record of an analytic pulse (T_p/``samples_per_period``), for the closed form."""
    from ...motions.motion import record_motion
    if motion.is_record or motion.kind == EXC_NONE:
        return motion
    dt = float(motion.params[1]) / samples_per_period
    t, a = motion.sampled(dt)
    return record_motion(motion.name + " (sampled)", a, dt, meta=dict(motion.meta, sampled_dt=dt))
