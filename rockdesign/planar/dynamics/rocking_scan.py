"""The event scan of an accepted rocking step (SPEC §3.4–3.7): impact, phase change, overturning and
the exceedance of θc on the step's dense output, with two crossings in one step found by the interior
scan points.  Split from :mod:`rockdesign.planar.dynamics.engine`.
"""
from __future__ import annotations


from numba import njit

from .events import root_on_dense
from .transitions import (crossing_event, store_event, top_displacement)
from .rk import (dense_value)

from .layout import (EV_EXCEEDED, S_DRIFT_MAX, S_EXCEEDED, S_IMPACTS_BEFORE_EXCEEDED, S_THETA_MAX,
                     S_T_EXCEEDED, S_T_THETA_MAX)




@njit(cache=True)
def scan_rocking_step(t, h, y, y_new, Q, ytmp, m_scan, side, phase, curved, beta, theta_ot, theta_c, two_dof,
                       drift_slope, impacts, stop_exceeded, c_theta, c_rate, summary, ev_t, ev_kind, ev_y, diag, sp):
    """Scan an accepted rocking step's dense output at ``m_scan`` points for the first event.

    Each sub-interval splits at an extremum of sθ (where θ̇ changes sign) into monotone pieces, each
    classified by :func:`~.transitions.crossing_event`; the first exceedance of θc is recorded on the
    way (terminal only with ``stop_exceeded``), and the peak |θ| and the superstructure drift are
    updated.  Returns (event kind, its position x ∈ [0, 1] in the step, its level [rad]); kind 0: none,
    −1: stop at θc.
    """
    ev_type = 0
    ev_x = 2.0
    ev_level = 0.0
    x_a = 0.0
    sa = side * y[0]
    va = side * y[1]
    for k in range(1, m_scan + 1):
        x_b = k / m_scan
        if k == m_scan:
            sb = side * y_new[0]
            vb = side * y_new[1]
        else:
            sb = side * dense_value(y, Q, h, x_b, 0)
            vb = side * dense_value(y, Q, h, x_b, 1)
        # split at an extremum of sθ (θ̇ changes sign)
        n_piece = 1
        x_mid = x_b
        s_mid = sb
        if (va > 0.0 and vb < 0.0) or (va < 0.0 and vb > 0.0):
            x_mid = root_on_dense(y, Q, h, c_rate, side, 0.0, x_a, x_b)
            s_mid = side * dense_value(y, Q, h, x_mid, 0)
            n_piece = 2
        px0 = x_a
        ps0 = sa
        for piece in range(n_piece):
            if piece == 0:
                px1 = x_mid
                ps1 = s_mid
            else:
                px0 = x_mid
                ps0 = s_mid
                px1 = x_b
                ps1 = sb
            ev_type, ev_level = crossing_event(ps0, ps1, curved, phase, beta, theta_ot)
            if ps1 > ps0:
                # rising: the exceedance of θc (non-terminal unless stop_exceeded) may come first
                if summary[S_EXCEEDED] == 0.0 and ps0 < theta_c <= ps1:
                    xc = root_on_dense(y, Q, h, c_theta, side, theta_c, px0, px1)
                    if ev_type == 0 or xc <= root_on_dense(y, Q, h, c_theta, side, ev_level, px0, px1):
                        summary[S_EXCEEDED] = 1.0
                        summary[S_T_EXCEEDED] = t + xc * h
                        summary[S_IMPACTS_BEFORE_EXCEEDED] = impacts
                        for i in range(4):
                            ytmp[i] = dense_value(y, Q, h, xc, i)
                        store_event(ev_t, ev_kind, ev_y, diag, EV_EXCEEDED, t + xc * h, ytmp)
                        if stop_exceeded:
                            ev_type = -1
                            ev_x = xc
                            break
            if ev_type > 0:
                if ps0 == ev_level:
                    ev_x = px0
                else:
                    ev_x = root_on_dense(y, Q, h, c_theta, side, ev_level, px0, px1)
                break
            # peak candidate at the end of a piece
            if ps1 > summary[S_THETA_MAX]:
                summary[S_THETA_MAX] = ps1
                summary[S_T_THETA_MAX] = t + px1 * h
        if ev_type != 0:
            break
        if two_dof:
            ut_b = y_new[2] if k == m_scan else dense_value(y, Q, h, x_b, 2)
            if abs(ut_b) + drift_slope * abs(sb) > summary[S_DRIFT_MAX]:
                rel = abs(ut_b - side * top_displacement(sb, sp))
                if rel > summary[S_DRIFT_MAX]:
                    summary[S_DRIFT_MAX] = rel
        x_a = x_b
        sa = sb
        va = vb
    return ev_type, ev_x, ev_level
