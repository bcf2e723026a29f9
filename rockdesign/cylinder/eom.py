"""Equations of motion of the rocking and wobbling cylinder (thesis Eqs 5.22, 5.23 corrected, 5.36, 5.37).

State y = (θ, θ̇, φ, φ̇[, w_T, ẇ_T]) in rad, rad/s, m, m/s; θ ≥ 0 is the tilt toward the azimuth φ
about the rim point T; w_T is the upward displacement of T on the spring–dashpot contact, measured
from the static deflection (damped model, Sec 5.3).  Divided by R the equations read

    Eq 5.22  M θ̈ + φ̇² X(θ) = −(g + ẅ_T)/R · sin(α−θ) − cos(α−θ)(ü_gx cosφ + ü_gy sinφ)/R
    Eq 5.23  J(θ) φ̈ + K(θ) φ̇ θ̇ = (sinα − sin(α−θ))(ü_gx sinφ − ü_gy cosφ)/R       (corrected, see docs)
    Eq 5.37  ẅ_T + 2ζω_n ẇ_T + ω_n² w_T = θ̇² R cos(α−θ) − θ̈ R sin(α−θ)

with M = (15 + cos²α)/12,
X = sinθ cosθ (5/4 sin²α − 4/3 cos²α) − 3/2 sinθ sin²α + cosα sinα (cos²θ − sin²θ − cosθ),
J = (16 + 5 sin²α)/12 · sin²θ + (1 − cosθ)(sin2α sinθ − 3 sin²α cosθ),
K = sin2α (cosθ(1 − cosθ) + sin²θ) + sinθ (3 sin²α + (8/3 cos²α − 5/2 sin²α) cosθ).
Eq 5.36 (Eq 5.22 with g → g + ẅ_T) is solved together with Eq 5.37 for θ̈:
θ̈ R (M − sin²(α−θ)) = −φ̇² R X − (g + Q) sin(α−θ) − cos(α−θ) F, Q = θ̇² R cos(α−θ) − 2ζω_n ẇ_T − ω_n² w_T.

Near θ = 0 (a quasi-impact) the differences 1 − cosθ, cos2θ − cosθ and sinα − sin(α−θ) are
evaluated in product form (2 sin²(θ/2), −2 sin(3θ/2) sin(θ/2), 2 cos(α − θ/2) sin(θ/2)) so that
the singular azimuth equation (J ~ θ²(16 − 13 sin²α)/12) keeps full relative precision down to
θ ~ 1e-150.  Hand-written (numba) because it is the physics itself; SI floats only.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..motions.excitation import EXC_SAMPLES, ground_acceleration

# parameter vector layout (see :func:`parameters`)
P_R, P_ALPHA, P_G, P_OMEGA, P_ZETA, P_DAMPED, P_SA, P_CA, P_S2, P_C2, P_SIN2A, P_M, P_PLANAR = range(13)


def parameters(R: float, alpha: float, g: float, omega_n: float = 0.0, zeta: float = 0.0,
               damped: bool = False, planar: bool = False) -> np.ndarray:
    """The float64 parameter vector of the kernels: R [m], α [rad], g [m/s²], ω_n [rad/s], ζ [-], damped flag,
    the precomputed trigonometry sinα, cosα, sin²α, cos²α, sin2α, M = (15 + cos²α)/12, and the planar
    flag (φ̇ ≡ 0: a one-directional excitation without initial spin, Eq 5.26).  The kernel sets the flag to
    2 for the seed phase after an uplift (:mod:`.kernel`): φ̈ ≡ 0 and ü_gx cosφ + ü_gy sinφ = ∓|ü_g| in
    Eq 5.22 (the azimuth follows the force while θ is tiny; − while the body tilts toward the inertia force,
    + after a crossing to the other side)."""
    sa, ca = math.sin(alpha), math.cos(alpha)
    return np.array([R, alpha, g, omega_n, zeta, 1.0 if damped else 0.0, sa, ca, sa * sa, ca * ca,
                     math.sin(2 * alpha), (15.0 + ca * ca) / 12.0,
                     1.0 if planar else 0.0])


@njit(cache=True, inline="always")
def ground_xy(t, active, kind, params, sx, sy, dirx, diry):
    """(ü_gx, ü_gy) [m/s²] at t: records component-wise (dir = 1, 1), pulses along (dirx, diry);
    zero once the excitation has ended (``active`` false)."""
    if not active:
        return 0.0, 0.0
    if kind == EXC_SAMPLES:                  # both components share the time step: one index, two lerps
        n = sx.shape[0]
        x = t / params[1]
        if x < 0.0 or n == 0:
            return 0.0, 0.0
        i = int(math.floor(x))
        if i >= n - 1:
            if i == n - 1 and x - i <= 1e-12:
                return params[0] * sx[n - 1], params[0] * sy[n - 1]
            return 0.0, 0.0
        f = x - i
        return (params[0] * (sx[i] + f * (sx[i + 1] - sx[i])), params[0] * (sy[i] + f * (sy[i + 1] - sy[i])))
    return dirx * ground_acceleration(t, kind, params, sx), diry * ground_acceleration(t, kind, params, sy)


@njit(cache=True, inline="always")
def rhs(t, y, out, par, active, kind, params, sx, sy, dirx, diry):
    """Right-hand side dy/dt of Eqs 5.22–5.23 (undamped) or 5.23, 5.36–5.37 (damped) into ``out``."""
    ax, ay = ground_xy(t, active, kind, params, sx, sy, dirx, diry)
    rhs_ground(y, out, par, ax, ay)


@njit(cache=True, inline="always")
def rhs_ground(y, out, par, ax, ay):
    """:func:`rhs` for a given ground acceleration (ü_gx, ü_gy) [m/s²] (the integrator interpolates it
    linearly within a step, which never crosses a record sample)."""
    R = par[P_R]
    g = par[P_G]
    s2 = par[P_S2]
    c2 = par[P_C2]
    sin2a = par[P_SIN2A]
    M = par[P_M]
    th = y[0]
    thd = y[1]
    ph = y[2]
    phd = y[3]
    sa = par[P_SA]
    ca = par[P_CA]
    sh = math.sin(0.5 * th)                              # four transcendental calls, the rest by identities
    ch = math.cos(0.5 * th)
    cph = math.cos(ph)
    sph = math.sin(ph)
    sth = 2.0 * sh * ch
    omc = 2.0 * sh * sh                                  # 1 − cosθ
    cth = 1.0 - omc
    sam = sa * cth - ca * sth                            # sin(α−θ)
    cam = ca * cth + sa * sth                            # cos(α−θ)
    X = (sth * cth * (1.25 * s2 - 4.0 / 3.0 * c2) - 1.5 * sth * s2
         - sa * ca * 2.0 * (sth * ch + cth * sh) * sh)   # cos2θ − cosθ = −2 sin(3θ/2) sin(θ/2)
    F = ax * cph + ay * sph
    if par[P_PLANAR] > 1.5:                                  # the seed phase: the force's magnitude, on its side
        F = -math.sqrt(ax * ax + ay * ay) if F <= 0.0 else math.sqrt(ax * ax + ay * ay)
    if par[P_DAMPED] > 0.5:
        om = par[P_OMEGA]
        ze = par[P_ZETA]
        w = y[4]
        wd = y[5]
        Q = thd * thd * R * cam - 2.0 * ze * om * wd - om * om * w
        thdd = (-phd * phd * R * X - (g + Q) * sam - cam * F) / (R * (M - sam * sam))
        out[4] = wd
        out[5] = Q - thdd * R * sam
    else:
        thdd = (-phd * phd * R * X - g * sam - cam * F) / (R * M)
    J = (16.0 + 5.0 * s2) / 12.0 * sth * sth + omc * (sin2a * sth - 3.0 * s2 * cth)
    K = sin2a * (cth * omc + sth * sth) + sth * (3.0 * s2 + (8.0 / 3.0 * c2 - 2.5 * s2) * cth)
    lever = 2.0 * (ca * ch + sa * sh) * sh                   # sinα − sin(α−θ) = 2 cos(α − θ/2) sin(θ/2)
    if par[P_PLANAR] > 0.5:
        phdd = 0.0
    elif J > 0.0:
        phdd = (lever * (ax * sph - ay * cph) / R - K * phd * thd) / J
    else:
        phdd = 0.0                                           # θ = 0 exactly: no azimuth defined
    out[0] = thd
    out[1] = thdd
    out[2] = phd
    out[3] = phdd


@njit(cache=True)
def contact_force_ratio(y, f, par):
    """N/(m g) [-]: the contact force over the weight, N = m(g + z̈_G) (vertical balance).

    Damped model: N/(mg) = 1 − (ω_n² w_T + 2ζω_n ẇ_T)/g (w_T upward, as in Eqs 5.36–5.37);
    rigid contact: N/(mg) = 1 + R(sin(α−θ) θ̈ − cos(α−θ) θ̇²)/g."""
    if par[P_DAMPED] > 0.5:
        om = par[P_OMEGA]
        return 1.0 - (om * om * y[4] + 2.0 * par[P_ZETA] * om * y[5]) / par[P_G]
    a = par[P_ALPHA] - y[0]
    return 1.0 + par[P_R] * (math.sin(a) * f[1] - math.cos(a) * y[1] * y[1]) / par[P_G]


@njit(cache=True)
def rocking_energy(y, par):
    """Energy per unit mass [J/kg] of the rocking and wobbling alone (no contact spring):
    ½(M R² θ̇² + R² J φ̇²) + g R (cos(α−θ) − cos α) — the measure of the damped model's rest rule."""
    R = par[P_R]
    th = y[0]
    sth = math.sin(th)
    sh = math.sin(0.5 * th)
    omc = 2.0 * sh * sh
    J = (16.0 + 5.0 * par[P_S2]) / 12.0 * sth * sth + omc * (par[P_SIN2A] * sth - 3.0 * par[P_S2] * math.cos(th))
    return (0.5 * R * R * (par[P_M] * y[1] * y[1] + J * y[3] * y[3])
            + par[P_G] * R * 2.0 * math.sin(par[P_ALPHA] - 0.5 * th) * sh)


@njit(cache=True)
def energy(y, par):
    """Mechanical energy per unit mass [J/kg] above the upright rest position (undamped: conserved in
    free vibration): ½(M R² θ̇² + R² J φ̇²) + g R (cos(α−θ) − cos α)
    [+ ½ẇ_T² + R sin(α−θ) θ̇ ẇ_T + ½ω_n² w_T² for the damped model]."""
    e = rocking_energy(y, par)
    if par[P_DAMPED] > 0.5:
        om = par[P_OMEGA]
        e += 0.5 * y[5] * y[5] + par[P_R] * math.sin(par[P_ALPHA] - y[0]) * y[1] * y[5] + 0.5 * om * om * y[4] * y[4]
    return e
