"""The rest phase of a podium with an elastic superstructure inside the integrator (Eq 4.3, SPEC §3.6).

:func:`exact_rest_step` advances the fixed-base SDOF exactly under a piecewise-linear record
(:mod:`.rest_step`) and watches the Eq 4.7 uplift criterion; :func:`scan_podium_uplift` scans a
Runge–Kutta rest step's dense output (analytic pulses) for uplift.  Split from
:mod:`rockdesign.planar.dynamics.engine`.
"""
from __future__ import annotations


from numba import njit

from ...motions.excitation import (ground_acceleration, ground_acceleration_right,
                                  next_breakpoint)
from .eom import (rest_acceleration, uplift_condition)
from .rest_step import fill_rest_outputs, rest_state, rest_substeps, rest_uplift_scan
from .transitions import (enter_uplift)
from .rk import (dense_value)

from .layout import (D_STEPS)


from .quiet_steps import quiet_rest


@njit(cache=True)
def exact_rest_step(t, h, t_end, y, y_new, f0, f1, m_scan, hyst, kind, xp, samples, sp, rest_coef, t_out, out_y,
                     i_out, summary, ev_t, ev_kind, ev_y, diag):
    """One exact step of the resting 2DOF podium under a record (:mod:`.rest_step`, Eq 4.3): to the next
    sample (split so that ω_s h ≤ 0.4), outputs written from the exact solution, Eq 4.7 watched on it.

    Moves ``y`` and returns (t, h, i_out, side): side = ±1 when the podium uplifted at the returned t
    (``y`` is then the state at uplift and the event is stored), 0.0 otherwise.  A separate kernel, not
    inlined into :func:`integrate`: numba's compile time grows with the integrator's size."""
    tb = min(next_breakpoint(t, kind, xp, samples), t_end)
    span = tb - t
    if span <= 1e-15 * max(1.0, abs(t)):
        return tb, h, i_out, 0.0     # sliver before a breakpoint: the state moves by round-off
    h = span / rest_substeps(span, sp)
    t_new = t + h
    if t_new > tb - 1e-13 * max(1.0, abs(tb)):
        t_new = tb
        h = tb - t
    a0 = ground_acceleration_right(t, kind, xp, samples)
    a1 = ground_acceleration(t_new, kind, xp, samples)
    u1, v1 = rest_state(y[2], y[3], a0, a1, h, sp)
    y_new[0] = 0.0
    y_new[1] = 0.0
    y_new[2] = u1
    y_new[3] = v1
    f0[2] = y[3]
    f0[3] = rest_acceleration(y[2], y[3], a0, sp)
    f1[2] = v1
    f1[3] = rest_acceleration(u1, v1, a1, sp)
    diag[D_STEPS] += 1
    if quiet_rest(t, h, y, y_new, f0, f1, m_scan, hyst, kind, xp, samples, rest_coef):
        ev_x = -1.0
        ev_side = 0.0
    else:
        ev_x, ev_side = rest_uplift_scan(t, h, y, a0, a1, m_scan, hyst, sp)
    if ev_x >= 0.0:
        he = ev_x * h
        ue, ve = rest_state(y[2], y[3], a0, a0 + ev_x * (a1 - a0), he, sp)
        t_e = t + he
        i_out = fill_rest_outputs(t_out, out_y, i_out, t_e, t, h, y, a0, a1, sp)
        y[2] = ue
        y[3] = ve
        enter_uplift(y, t_e, summary, ev_t, ev_kind, ev_y, diag)
        return t_e, h, i_out, ev_side
    i_out = fill_rest_outputs(t_out, out_y, i_out, t_new, t, h, y, a0, a1, sp)
    for i in range(4):
        y[i] = y_new[i]
    return t_new, h, i_out, 0.0


@njit(cache=True)
def scan_podium_uplift(t, h, y, y_new, Q, m_scan, hyst, kind, xp, samples, sp):
    """Scan an accepted step of the fixed-base 2DOF podium (at rest, Eq 4.3) for uplift (Eq 4.7 above
    the hysteresis, either side) at ``m_scan`` points of the dense output, and bisect the first one.
    Returns (its position x ∈ [0, 1] in the step, or −1.0 for none; the side it uplifts to)."""
    ev_x = -1.0
    ev_side = 0.0
    x_prev = 0.0
    for k in range(1, m_scan + 1):
        x = k / m_scan
        tx = t + x * h
        ag = ground_acceleration(tx, kind, xp, samples)
        ut = y_new[2] if k == m_scan else dense_value(y, Q, h, x, 2)
        utd = y_new[3] if k == m_scan else dense_value(y, Q, h, x, 3)
        cp = uplift_condition(1.0, ag, ut, utd, sp) - hyst
        cm = uplift_condition(-1.0, ag, ut, utd, sp) - hyst
        if cp >= 0.0 or cm >= 0.0:
            s_up = 1.0 if cp >= 0.0 else -1.0
            xa = x_prev
            xb = x
            for _ in range(100):  # bisection on the dense output
                xm = 0.5 * (xa + xb)
                agm = ground_acceleration(t + xm * h, kind, xp, samples)
                cm_ = uplift_condition(s_up, agm, dense_value(y, Q, h, xm, 2),
                                       dense_value(y, Q, h, xm, 3), sp) - hyst
                if cm_ >= 0.0:
                    xb = xm
                else:
                    xa = xm
                if xb - xa < 1e-15:
                    break
            ev_x = xb
            ev_side = s_up
            break
        x_prev = x
    return ev_x, ev_side
