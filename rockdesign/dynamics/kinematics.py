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
    sa = side * alpha
    s_at = math.sin(sa - theta)
    c_at = math.cos(sa - theta)
    st = math.sin(theta)
    ct = math.cos(theta)
    u = R * (math.sin(sa) - s_at)
    u1 = R * c_at
    u2 = R * s_at
    w = R * c_at
    w1 = R * s_at
    w2 = -R * c_at
    if r != 0.0:
        if phase == 1:
            u += r * (theta - st)
            u1 += r * (1.0 - ct)
            u2 += r * st
            w += r * (1.0 - ct)
            w1 += r * st
            w2 += r * ct
        else:
            sb = side * beta
            s_bt = math.sin(sb - theta)
            c_bt = math.cos(sb - theta)
            u += r * (sb - s_bt - st)
            u1 += r * (c_bt - ct)
            u2 += r * (s_bt + st)
            w += r * (c_bt - ct)
            w1 += r * (s_bt + st)
            w2 += r * (ct - c_bt)
    return u, u1, u2, w, w1, w2


@njit(cache=True)
def top_displacement(theta, side, phase, R, alpha, r, beta):
    """Column-top (cap-beam) horizontal displacement u_B = 2u_C [m] (Eq 3.83)."""
    u, _, _, _, _, _ = centre_kinematics(theta, side, phase, R, alpha, r, beta)
    return 2.0 * u
