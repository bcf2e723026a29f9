"""The cylinder's integrator: DOP853 with 7th-order dense output, as numba kernels (thesis Ch. 5).

Hand-written because scipy's ``solve_ivp`` calls Python per stage (≈100× slower, see
``benchmarks/bench_cylinder.py``) and cannot land on record samples, uplift from rest or apply the
planar reflection.  The step, its error norm and dense output are :mod:`.stepper`'s (Hairer's DOP853,
scipy's tableau); the step control is scipy's (safety 0.9, factors 0.2–10, exponent −1/8).

One run (:func:`integrate`):

* at rest, wait until the resultant |ü_g| = √(ü_gx² + ü_gy²) reaches ``up`` (Eq 5.24's g tan α plus the
  hysteresis), found exactly on each linear record segment (a quadratic in t) or by a T_p/2000 scan and
  bisection for pulses; then start at θ = θ̇ = φ̇ = 0 toward φ0 = atan2(−ü_gy, −ü_gx) (Eq 5.25 with its
  quadrant);
* the planar reduction (:mod:`.motion_line`, Sec 5.2.6): from an uplift the body has no angular momentum
  about the vertical, and while every piece of the excitation lies on the line of the uplift force Eq 5.23
  keeps it at zero: the run integrates Eq 5.22 with φ̇ ≡ 0 (Housner's cylinder, Eq 5.26 with the ground
  term), whatever the azimuth of the line.  Checked before every step; where a piece leaves the line the
  3D equations take over from the planar state (through the seed phase below θ_seed, tilting toward the
  inertia force);
* the seed phase (an uplift where the force is not on one line): from θ = 0 up to θ = θ_seed the body
  tilts toward the inertia force by Eq 5.22 alone (φ̈ ≡ 0, ü_gx cosφ + ü_gy sinφ = −|ü_g|: regular at
  θ = 0, where Eq 5.23 is singular); at θ_seed the 3D equations take over with φ = the azimuth of −ü_g
  and φ̇ its rate of turn (:func:`_force_direction`:
  Eq 5.23 locks the azimuth to the force as θ → 0, its stiffness cos α |ü_g|/(R J/θ) being unbounded).
  The state at θ_seed is thus the small-tilt solution from rest, not a disturbance of size θ_seed: θ_max
  does not depend on the seed to first order (docs/cylinder.md).  A seed phase that comes back to θ = 0
  is a planar crossing (and rests below the rest energy, as the planar engine's block);
* steps end exactly on every record sample (records are piecewise linear) and on the end of the
  excitation (the right-hand side is re-evaluated there with ü_g = 0); a step that would stop short of
  a sample by less than 25 % of its size is stretched onto it; within a step a record's ü_g is linear,
  so it is evaluated at the two ends only and interpolated at the 12 stages;
* quasi-impacts (θ → 0 with a spike of φ̇) are resolved by the step control alone, no event;
* on every accepted step the dense output locates: the overturning tilt θ_ot (terminal), minima of
  θ (θ̇: − → +; a minimum below ``quasi_tilt`` is a quasi-impact), maxima of θ, and — only under the
  planar reduction or in the seed phase (φ̇ ≡ 0) — θ = 0, where the body switches to the opposite rim
  point: θ → −θ, θ̇ → −r θ̇, φ → φ + π (r = 1 rigid, √c_r of Eq 5.41 damped);
* rest rule (both contacts, the planar engine's, SPEC §3.6): at a quasi-impact (a minimum of θ below
  ``quasi_tilt``, or in 3D the end of a step below ``quasi_tilt`` on the way to one) or a planar crossing
  whose rocking energy ½ R²(M θ̇² + J φ̇²) + gR(cos(α−θ) − cos α)
  (Eqs 5.22–5.23; the contact spring excluded: its deflection under the rocking body's own acceleration
  is no motion to end) is below ``rest_energy`` = ½ M R² v_rest², the cylinder rests (θ = θ̇ = φ̇ = w_T =
  ẇ_T = 0, φ kept).  At a planar crossing this is the planar rule |θ̇⁺| < v_rest.  At rest it uplifts
  when |ü_g| reaches ``up`` (g tan α plus the planar engine's hysteresis, :mod:`.engine`) — at once if
  |ü_g| is already beyond it, as the planar engine's rest → uplift.  ``rest_energy`` = 0 disables the rule.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..motions.excitation import next_breakpoint
from .uplift import uplift_time
from .eom import contact_force_ratio, ground_xy, rhs, rocking_energy
from .motion_line import piece_line, piece_on_line
from .stepper import dense_at, dense_coefficients, dense_root, dop853_step, error_norm

SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
EXPONENT = -1.0 / 8.0
STRETCH = 1.25
"""A step that would end within 25 % of h short of a record sample is stretched onto it instead of
leaving a sliver step (measured: −5 % right-hand sides for the damped model, error unchanged to 10 %)."""

# event codes
EV_UPLIFT, EV_QUASI_IMPACT, EV_THETA_MAX, EV_CROSSING, EV_REST, EV_OVERTURN = 0, 1, 2, 3, 4, 5
# where an accepted step is cut
STOP_NONE, STOP_OVERTURN, STOP_SEEDED, STOP_CROSSING, STOP_REST = 0, 1, 2, 3, 4
# status codes
ST_COMPLETED, ST_OVERTURNED, ST_STEP_COLLAPSED, ST_STEP_LIMIT = 0, 1, 2, 3
HISTORY_COLUMNS = 8          # t, θ, θ̇, φ, φ̇, w_T, ẇ_T, N/(mg)


@njit(cache=True)
def _force_direction(t, active, kind, params, sx, sy, dirx, diry):
    """(ψ, ψ̇): the azimuth [rad] of the inertia force −ü_g at t and its rate of turn [rad/s],
    ψ̇ = (ü_gx d/dt ü_gy − ü_gy d/dt ü_gx)/|ü_g|² (central difference over ±1e-7 s; a record is linear there
    but at its samples)."""
    ax, ay = ground_xy(t, active, kind, params, sx, sy, dirx, diry)
    d = 1e-7
    bx, by = ground_xy(t + d, active, kind, params, sx, sy, dirx, diry)
    cx, cy = ground_xy(max(t - d, 0.0), active, kind, params, sx, sy, dirx, diry)
    span = t + d - max(t - d, 0.0)
    a2 = ax * ax + ay * ay
    if a2 == 0.0:
        return math.atan2(-ay, -ax), 0.0
    return math.atan2(-ay, -ax), (ax * (by - cy) - ay * (bx - cx)) / (span * a2)


@njit(cache=True)
def _push(buf, count, row):
    if count >= buf.shape[0]:
        new = np.empty((2 * buf.shape[0], buf.shape[1]))
        new[:count] = buf[:count]
        buf = new
    for k in range(buf.shape[1]):
        buf[count, k] = row[k]
    return buf, count + 1


@njit(cache=True)
def _record(hist, nh, t, y, f, par, row):
    row[0] = t
    for k in range(6):
        row[1 + k] = y[k]
    row[7] = contact_force_ratio(y, f, par)
    return _push(hist, nh, row)


@njit(cache=True)
def _event(events, ne, code, t, theta, value, ev):
    ev[0] = code
    ev[1] = t
    ev[2] = theta
    ev[3] = value
    return _push(events, ne, ev)


@njit(cache=True, nogil=True)     # threads of this process run analyses side by side (execution.executor.one_core)
def integrate(y0, t0, t_end, t_exc_end, par, kind, params, sx, sy, dirx, diry, rtol, atol, theta_seed,
              theta_ot, quasi_tilt, rest_energy, planar_restitution, up, max_steps, out_dt, planar_reduction):
    """Integrate one cylinder from (t0, y0) to t_end (module docstring).

    ``theta_seed`` [rad]: the tilt at which the seed phase of a 3D uplift hands over to Eq 5.23 (θ = 0 is its
    singular point); ``rest_energy`` [J/kg]: the rest rule's energy (0: no rest); ``up`` [m/s²]: the resultant
    |ü_g| at which a resting cylinder uplifts (Eq 5.24 with the hysteresis, :func:`.engine.uplift_level`).
    ``out_dt`` > 0 adds dense-output rows on the grid k·out_dt to the history.  ``planar_reduction``: an uplift
    runs the planar equations while the excitation stays on the line of the uplift (:mod:`.motion_line`);
    False: the 3D equations from every uplift (the stability study shows what they do on a planar motion).
    ``par``'s planar flag says whether a run that starts tilted starts planar (along φ0's line).
    Returns (history rows [t, θ, θ̇, φ, φ̇, w_T, ẇ_T, N/(mg)] at every accepted step and event,
    events rows [code, t, θ, value], stats [steps, rejected, rhs evaluations, dense outputs, status,
    t_stop]).
    """
    n = 6 if par[5] > 0.5 else 4
    par_seed = par.copy()
    par_seed[12] = 2.0          # the seed phase: Eq 5.22 toward the inertia force, φ̈ ≡ 0 (regular at θ = 0)
    par_3d = par.copy()
    par_3d[12] = 0.0            # Eqs 5.22-5.23
    par_planar = par.copy()
    par_planar[12] = 1.0        # their planar reduction along the line (lx, ly): φ̇ ≡ 0 (Eq 5.26)
    pc = par                    # the equations in force: par_3d, par_planar, or par_seed while seeding
    seeding = False
    lx = math.cos(y0[2])        # the line of a planar motion (a start tilted toward φ0, or the uplift's)
    ly = math.sin(y0[2])
    y = np.zeros(6)
    y_new = np.zeros(6)
    ytmp = np.zeros(6)
    f = np.zeros(6)
    fg = np.zeros(6)
    yg = np.zeros(6)
    k_out = 1
    K = np.zeros((16, 6))
    F = np.zeros((7, 6))
    row = np.zeros(HISTORY_COLUMNS)
    ev = np.zeros(4)
    hist = np.empty((4096, HISTORY_COLUMNS))
    events = np.empty((64, 4))
    nh = 0
    ne = 0
    steps = 0
    rejected = 0
    nfev = 0
    ndense = 0
    status = ST_COMPLETED
    for i in range(6):
        y[i] = y0[i]
    t = t0
    resting = y[0] <= 0.0 and y[1] == 0.0
    h = 0.0
    active = t < t_exc_end
    if not resting:
        rhs(t, y, f, pc, active, kind, params, sx, sy, dirx, diry)
        nfev += 1
    hist, nh = _record(hist, nh, t, y, f, par, row)
    while t < t_end:
        if resting:
            tu = uplift_time(t, min(t_end, t_exc_end), up, kind, params, sx, sy, dirx, diry)
            if out_dt > 0.0:                      # grid rows while at rest
                t_hi = min(tu, t_end)
                while k_out * out_dt < t_hi - 1e-12 * max(1.0, t_hi):
                    if k_out * out_dt > t:
                        hist, nh = _record(hist, nh, k_out * out_dt, y, f, par, row)
                    k_out += 1
            if tu == math.inf or tu >= t_end:
                t = t_end
                hist, nh = _record(hist, nh, t, y, f, par, row)
                break
            ax, ay = ground_xy(tu, True, kind, params, sx, sy, dirx, diry)
            t = tu
            # ℓ = 0 at an uplift: planar while the ground stays on the line of this piece (checked every step)
            lx, ly = piece_line(tu, kind, params, sx, sy, dirx, diry)
            if planar_reduction and piece_on_line(tu, min(t_exc_end, next_breakpoint(tu, kind, params, sx)),
                                                  kind, params, sx, sy, dirx, diry, lx, ly):
                seeding = False
                pc = par_planar
            else:
                seeding = theta_seed > 0.0
                pc = par_seed if seeding else par_3d
            y[0] = 0.0
            y[1] = 0.0
            y[2] = math.atan2(-ay, -ax)
            y[3] = 0.0
            y[4] = 0.0
            y[5] = 0.0
            resting = False
            active = t < t_exc_end
            rhs(t, y, f, pc, active, kind, params, sx, sy, dirx, diry)
            nfev += 1
            hist, nh = _record(hist, nh, t, y, f, par, row)
            events, ne = _event(events, ne, EV_UPLIFT, t, y[0], y[2], ev)
            h = 0.0
        if h == 0.0:
            # initial step (Hairer's rule on the first two derivatives)
            d0 = 0.0
            d1 = 0.0
            for i in range(n):
                sc = atol + rtol * abs(y[i])
                d0 += (y[i] / sc) ** 2
                d1 += (f[i] / sc) ** 2
            d0 = math.sqrt(d0 / n)
            d1 = math.sqrt(d1 / n)
            h = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
            h = min(h, 1e-3)
        active = t < t_exc_end
        t_stop = t_end
        if active:
            t_stop = min(t_stop, t_exc_end, next_breakpoint(t, kind, params, sx))
            if 0.5 < pc[12] < 1.5 and not piece_on_line(t, t_stop, kind, params, sx, sy, dirx, diry, lx, ly):
                # the ground leaves the tilt's line: Eq 5.23 gains a torque, the 3D equations take over from the
                # planar state — through the seed phase if the body is still below θ_seed, tilting toward the
                # inertia force (as just after an uplift: the seed phase's premise)
                ax, ay = ground_xy(t, active, kind, params, sx, sy, dirx, diry)
                seeding = y[0] < theta_seed and ax * math.cos(y[2]) + ay * math.sin(y[2]) <= 0.0
                pc = par_seed if seeding else par_3d
                rhs(t, y, f, pc, active, kind, params, sx, sy, dirx, diry)
                nfev += 1
        accepted = False
        rejected_now = False
        while not accepted:
            if steps + rejected >= max_steps:
                status = ST_STEP_LIMIT
                break
            h_min = 10.0 * (np.nextafter(t, math.inf) - t)
            if h < h_min:
                status = ST_STEP_COLLAPSED
                break
            t_new = t + h
            if t_new >= t_stop - 1e-12 * max(1.0, abs(t_stop)) or (not rejected_now and t_stop - t <= STRETCH * h):
                t_new = t_stop
            hh = t_new - t
            dop853_step(t, y, f, hh, K, y_new, ytmp, n, pc, active, kind, params, sx, sy, dirx, diry)
            nfev += 12
            err = error_norm(y, y_new, K, hh, rtol, atol, n)
            if y_new[0] < 0.0 and pc[12] < 0.5:
                err = 10.0           # θ < 0 off the planar case: the step overshot a quasi-impact
            if err < 1.0 and math.isfinite(err):
                factor = MAX_FACTOR if err == 0.0 else min(MAX_FACTOR, SAFETY * err ** EXPONENT)
                if rejected_now:
                    factor = min(1.0, factor)
                h = hh * factor if t_new < t_stop else max(h, hh * factor)
                accepted = True
            else:
                factor = MIN_FACTOR if not math.isfinite(err) else max(MIN_FACTOR, SAFETY * err ** EXPONENT)
                h = hh * factor
                rejected += 1
                rejected_now = True
        if not accepted:
            break
        steps += 1
        # ---- events on the dense output of the accepted step [t, t_new]
        have_dense = False
        stop_at = -1.0            # x where the step is cut (overturn, rest, crossing, end of the seed phase)
        stop_kind = STOP_NONE
        if (y_new[0] >= theta_ot or y_new[0] < 0.0 or (y[1] < 0.0 <= y_new[1]) or (y[1] > 0.0 >= y_new[1])
                or (seeding and y_new[0] >= theta_seed)):
            dense_coefficients(t, y, y_new, K, hh, F, ytmp, n, pc, active, kind, params, sx, sy, dirx, diry)
            nfev += 3
            ndense += 1
            have_dense = True
        if have_dense:
            # scan the step at 16 points for θ̇ sign changes (extrema of θ) and level crossings
            xa = 0.0
            va = y[1]
            ta_ = y[0]
            for k in range(1, 17):
                xb = k / 16.0
                vb = dense_at(F, y, xb, 1) if k < 16 else y_new[1]
                tb_ = dense_at(F, y, xb, 0) if k < 16 else y_new[0]
                if tb_ >= theta_ot and ta_ < theta_ot:
                    x = dense_root(F, y, 0, theta_ot, xa, xb)
                    stop_at = x
                    tt = t + x * hh
                    events, ne = _event(events, ne, EV_OVERTURN, tt, theta_ot, dense_at(F, y, x, 3), ev)
                    status = ST_OVERTURNED
                    stop_kind = STOP_OVERTURN
                    break
                if seeding and tb_ >= theta_seed > ta_:
                    # the seed phase ends: the 3D equations take over at θ = θ_seed
                    stop_at = dense_root(F, y, 0, theta_seed, xa, xb)
                    stop_kind = STOP_SEEDED
                    break
                if tb_ < 0.0 <= ta_:
                    # exactly planar motion reaches θ = 0: switch to the opposite rim point
                    x = dense_root(F, y, 0, 0.0, xa, xb)
                    stop_at = x
                    stop_kind = STOP_CROSSING
                    break
                if va < 0.0 <= vb:
                    x = dense_root(F, y, 1, 0.0, xa, xb)
                    thmin = dense_at(F, y, x, 0)
                    if thmin < quasi_tilt:
                        tt = t + x * hh
                        events, ne = _event(events, ne, EV_QUASI_IMPACT, tt, thmin, dense_at(F, y, x, 3), ev)
                        if rest_energy > 0.0:
                            for i in range(6):
                                ytmp[i] = dense_at(F, y, x, i) if i < n else 0.0
                            if rocking_energy(ytmp, par) < rest_energy:
                                stop_at = x
                                stop_kind = STOP_REST
                                break
                elif va > 0.0 >= vb:
                    x = dense_root(F, y, 1, 0.0, xa, xb)
                    events, ne = _event(events, ne, EV_THETA_MAX, t + x * hh, dense_at(F, y, x, 0), 0.0, ev)
                xa = xb
                va = vb
                ta_ = tb_
        if (stop_at < 0.0 and rest_energy > 0.0 and pc[12] < 0.5 and y_new[0] < quasi_tilt and y_new[1] < 0.0
                and rocking_energy(y_new, par) < rest_energy):
            # on its way to a quasi-impact with less than the rest energy: at rest now (in 3D the minimum of
            # an orbit of tiny angular momentum can lie below what the step control resolves)
            stop_at = 1.0
            stop_kind = STOP_REST
        if out_dt > 0.0:
            t_hi = t + stop_at * hh if stop_at >= 0.0 else t_new
            while k_out * out_dt <= t_hi - 1e-12 * max(1.0, t_hi):
                tg = k_out * out_dt
                k_out += 1
                if tg <= t:
                    continue
                if not have_dense:
                    dense_coefficients(t, y, y_new, K, hh, F, ytmp, n, pc, active, kind, params, sx, sy, dirx, diry)
                    nfev += 3
                    ndense += 1
                    have_dense = True
                for i in range(6):
                    yg[i] = dense_at(F, y, (tg - t) / hh, i) if i < n else 0.0
                rhs(tg, yg, fg, pc, active, kind, params, sx, sy, dirx, diry)
                hist, nh = _record(hist, nh, tg, yg, fg, par, row)
        if stop_at >= 0.0:
            if stop_at < 1.0:
                for i in range(n):
                    y_new[i] = dense_at(F, y, stop_at, i)
                t_new = t + stop_at * hh
            if stop_kind == STOP_OVERTURN:
                y_new[0] = theta_ot
                rhs(t_new, y_new, f, pc, active, kind, params, sx, sy, dirx, diry)
                hist, nh = _record(hist, nh, t_new, y_new, f, par, row)
                t = t_new
                break
            if stop_kind == STOP_SEEDED:
                seeding = False
                pc = par_3d
                y_new[0] = theta_seed
                # while θ ≪ θ_seed the azimuth is locked to the inertia force (Eq 5.23: its stiffness
                # cos α |ü_g|/(R J/θ) grows without bound as θ → 0): φ = its direction, φ̇ = its rate of turn
                psi, psid = _force_direction(t_new, t_new < t_exc_end, kind, params, sx, sy, dirx, diry)
                dpsi = psi - y_new[2]
                y_new[2] = y_new[2] + dpsi - 2.0 * math.pi * math.floor(dpsi / (2.0 * math.pi) + 0.5)
                y_new[3] = psid
                for i in range(n):
                    y[i] = y_new[i]
                t = t_new
                active = t < t_exc_end
                rhs(t, y, f, pc, active, kind, params, sx, sy, dirx, diry)
                nfev += 1
                hist, nh = _record(hist, nh, t, y, f, par, row)
                continue
            if stop_kind == STOP_CROSSING:
                # planar crossing
                y_new[0] = 0.0
                thd = y_new[1]
                events, ne = _event(events, ne, EV_CROSSING, t_new, thd, y_new[2], ev)
                y_new[1] = -planar_restitution * thd
                y_new[2] = y_new[2] + math.pi
                for i in range(n):
                    y[i] = y_new[i]
                if rest_energy > 0.0 and rocking_energy(y, par) < rest_energy:
                    resting = True
                else:
                    t = t_new
                    active = t < t_exc_end
                    rhs(t, y, f, pc, active, kind, params, sx, sy, dirx, diry)
                    nfev += 1
                    hist, nh = _record(hist, nh, t, y, f, par, row)
                    continue
            else:
                resting = True
            if resting:
                seeding = False
                pc = par
                for i in range(6):
                    if i != 2:
                        y[i] = 0.0
                y[2] = y_new[2]
                t = t_new
                events, ne = _event(events, ne, EV_REST, t, 0.0, y[2], ev)
                for i in range(6):
                    f[i] = 0.0
                hist, nh = _record(hist, nh, t, y, f, par, row)
                h = 0.0
                continue
        for i in range(n):
            y[i] = y_new[i]
            f[i] = K[12, i]
        t = t_new
        if active and t >= t_exc_end:
            active = False
            rhs(t, y, f, pc, active, kind, params, sx, sy, dirx, diry)   # right limit: ü_g = 0
            nfev += 1
        hist, nh = _record(hist, nh, t, y, f, par, row)
    stats = np.array([steps, rejected, nfev, ndense, status, t], dtype=np.float64)
    return hist[:nh].copy(), events[:ne].copy(), stats
