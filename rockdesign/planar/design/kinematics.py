"""Contact kinematics of one rocking column: the centre C as a function of the tilt θ (SPEC §3.1).

For the current side s = ±1 and phase (1: rolling on the curved extension, |θ| < β; 2: rocking
about the extension's outer edge, |θ| > β), these functions return u_C, w_C and their first and
second θ-derivatives.  The cap beam (column top) moves with u_B = 2u_C, w_B = 2w_C (Eq 3.83).

A block is r = 0 (Eqs 3.1–3.2); flat extensions are a block of size R', α' (Eqs 3.35–3.36);
curved extensions use Eqs 3.46–3.47 (phase I) and 3.51–3.52 (phase II).  Lengths in m, angles in rad.
"""
from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def centre_kinematics(theta, side, phase, R, alpha, r, beta):
    """(u_C, u_C', u_C'', w_C, w_C', w_C'') of the column centre at tilt θ [m, m/rad, m/rad²].

    Args:
        theta: tilt θ [rad]; side·θ ≥ 0 while rocking on ``side``.
        side: s = +1 (pivot on the right, θ > 0) or −1.
        phase: 1 (|θ| ≤ β, rolling) or 2 (|θ| > β, rocking); ignored when r = 0.
        R: half-diagonal √(B²+H²) [m]; alpha: atan(B/H) [rad]; r: extension radius [m];
        beta: wedge angle β [rad] (Eq 3.44).
    """
    u, u1, u2, w, w1, w2 = unit_centre_kinematics(theta, side, phase, r / R, beta, math.sin(alpha), math.cos(alpha),
                                                  math.sin(beta), math.cos(beta))
    return R * u, R * u1, R * u2, R * w, R * w1, R * w2


@njit(cache=True, inline="always")
def unit_centre_kinematics(theta, side, phase, r_over_R, beta, sin_a, cos_a, sin_b, cos_b):
    """(u_C, u_C', u_C'', w_C, w_C', w_C'')/R for a column of unit size R = 1 and radius r/R.

    Eqs 3.1–3.2 (block), 3.46–3.47 (phase I), 3.51–3.52 (phase II), with sin(sα − θ), cos(sα − θ),
    sin(sβ − θ), cos(sβ − θ) expanded on the given sin α, cos α, sin β, cos β: two trigonometric calls.
    """
    st = math.sin(theta)
    ct = math.cos(theta)
    sa = side * sin_a
    s_at = sa * ct - cos_a * st
    c_at = cos_a * ct + sa * st
    u = sa - s_at
    u1 = c_at
    u2 = s_at
    w = c_at
    w1 = s_at
    w2 = -c_at
    if r_over_R != 0.0:
        rr = r_over_R
        if phase == 1:
            u += rr * (theta - st)
            u1 += rr * (1.0 - ct)
            u2 += rr * st
            w += rr * (1.0 - ct)
            w1 += rr * st
            w2 += rr * ct
        else:
            sb = side * sin_b
            s_bt = sb * ct - cos_b * st
            c_bt = cos_b * ct + sb * st
            u += rr * (side * beta - s_bt - st)
            u1 += rr * (c_bt - ct)
            u2 += rr * (s_bt + st)
            w += rr * (c_bt - ct)
            w1 += rr * (s_bt + st)
            w2 += rr * (ct - c_bt)
    return u, u1, u2, w, w1, w2


@njit(cache=True)
def top_displacement(theta, side, phase, R, alpha, r, beta):
    """Column-top (cap-beam) horizontal displacement u_B = 2u_C [m] (Eq 3.83)."""
    u, _, _, _, _, _ = centre_kinematics(theta, side, phase, R, alpha, r, beta)
    return 2.0 * u
