"""Maximum-direction (RotD100) elastic spectra of a pair of horizontal components (SPEC §16).

ASCE 7-22 §16.2.3.2 scales a ground motion by the *maximum-direction* spectrum of its two horizontal
components: at each period, the largest peak response of a linear oscillator over all horizontal
directions (Boore 2010's RotD100).  For a linear oscillator the response to the component along a
direction θ is the projection of the responses to the two components,
u(θ, t) = u_x(t) cos θ + u_y(t) sin θ, so

    max over θ of max over t of |u(θ, t)| = max over t of √(u_x(t)² + u_y(t)²)

(for fixed t the largest projection is the length of the vector).  The maximum-direction spectral
displacement is therefore the peak of the *resultant* displacement of two identical oscillators, one
under each component — no search over angles.  PSA = ω² SD is the pseudo-acceleration, the quantity
ASCE 7 spectra and PEER's RotD100 spectra tabulate.

Exactness is that of :mod:`rockdesign.motions.spectra`: each oscillator advances from sample to
sample with the exact Nigam–Jennings recurrence for ü_g linear between samples; the peak is taken at
the samples, sub-stepped to Δt/m ≤ T/10 where T < 10 Δt (:data:`~rockdesign.motions.spectra.STEPS_PER_PERIOD`,
PEER's convention), and over the free vibration after the record's end in closed form
(:func:`resultant_free_vibration_peak`).  Both components must share the time step; the shorter one
is zero after its end.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from .spectra import STEPS_PER_PERIOD, nigam_jennings_coefficients  # noqa: E402

DEFAULT_DAMPING_ASCE = 0.05
"""ASCE 7-22 target spectra are 5 %-damped (§11.4.5, §16.2.1)."""


@njit(cache=True)
def resultant_free_vibration_peak(ux, vx, uy, vy, omega, zeta):
    """max |u(τ)| [m] for τ ≥ 0 of two identical free damped oscillators starting at (ux, vx), (uy, vy).

    Args:
        ux, uy: initial displacements [m]; vx, vy: initial velocities [m/s].
        omega: circular frequency ω [rad/s]; zeta: damping ratio ζ (0 ≤ ζ < 1).

    Each component is u(τ) = e^(−ζωτ)(A cos ω_d τ + B sin ω_d τ) with A = u0, B = (v0 + ζωu0)/ω_d, so
    |u|² = e^(−2ζωτ)(a + r cos θ), θ = 2ω_d τ − ψ, with a = (|A|² + |B|²)/2, r = √(b² + c²),
    b = (|A|² − |B|²)/2, c = A·B, ψ = atan2(c, b).  Its derivative vanishes where
    sin(θ + β) = −ζa/r (sin β = ζ); a maximum where cos(θ + β) > 0.  All later maxima repeat the bracket's
    value under a shrinking envelope, so the peak is |u(0)| or |u| at the first maximum after τ = 0
    (none when ζa ≥ r: |u| only decays).
    """
    root = math.sqrt(1.0 - zeta * zeta)
    omega_d = omega * root
    ax_ = ux
    bx_ = (vx + zeta * omega * ux) / omega_d
    ay_ = uy
    by_ = (vy + zeta * omega * uy) / omega_d
    a2 = ax_ * ax_ + ay_ * ay_
    b2 = bx_ * bx_ + by_ * by_
    a = 0.5 * (a2 + b2)
    b = 0.5 * (a2 - b2)
    c = ax_ * bx_ + ay_ * by_
    r = math.sqrt(b * b + c * c)
    start = math.sqrt(ux * ux + uy * uy)
    if r <= 0.0 or zeta * a >= r:
        return start
    psi = math.atan2(c, b)
    beta = math.asin(zeta)
    x = -beta - math.asin(zeta * a / r) + psi          # θ* + ψ = 2 ω_d τ* at the maxima, mod 2π
    two_pi = 2.0 * math.pi
    x = x - two_pi * math.floor(x / two_pi)
    tau = x / (2.0 * omega_d)
    theta = x - psi
    value = math.exp(-2.0 * zeta * omega * tau) * (a + r * math.cos(theta))
    peak = math.sqrt(max(value, 0.0))
    return max(start, peak)


@njit(cache=True)
def peak_resultant_displacement(accel_x, accel_y, dt, omega, zeta, include_tail):
    """max over t of √(u_x² + u_y²) [m]: the maximum-direction (RotD100) spectral displacement at ω.

    Args:
        accel_x, accel_y: the two horizontal components ü_g [m/s²] at t = i·dt (same length), linear in
            between.
        dt: sample spacing [s]; omega: circular frequency ω [rad/s]; zeta: damping ratio ζ.
        include_tail: also the free vibration after the last sample (ground at rest).

    Sub-stepped to Δt/m ≤ T/10 where T < 10 Δt, as :func:`rockdesign.motions.spectra.peak_displacement`.
    """
    m = max(1, int(math.ceil(STEPS_PER_PERIOD * dt * omega / (2.0 * math.pi) - 1e-9)))
    k = nigam_jennings_coefficients(omega, zeta, dt / m)
    ux = 0.0
    vx = 0.0
    uy = 0.0
    vy = 0.0
    peak2 = 0.0
    for i in range(accel_x.shape[0] - 1):
        sx = (accel_x[i + 1] - accel_x[i]) / m
        sy = (accel_y[i + 1] - accel_y[i]) / m
        for j in range(m):
            x0 = accel_x[i] + sx * j
            y0 = accel_y[i] + sy * j
            if j == m - 1:
                x1 = accel_x[i + 1]
                y1 = accel_y[i + 1]
            else:
                x1 = accel_x[i] + sx * (j + 1)
                y1 = accel_y[i] + sy * (j + 1)
            ux_next = k[0] * ux + k[1] * vx + k[4] * x0 + k[5] * x1
            vx = k[2] * ux + k[3] * vx + k[6] * x0 + k[7] * x1
            ux = ux_next
            uy_next = k[0] * uy + k[1] * vy + k[4] * y0 + k[5] * y1
            vy = k[2] * uy + k[3] * vy + k[6] * y0 + k[7] * y1
            uy = uy_next
            r2 = ux * ux + uy * uy
            if r2 > peak2:
                peak2 = r2
    peak = math.sqrt(peak2)
    if include_tail:
        tail = resultant_free_vibration_peak(ux, vx, uy, vy, omega, zeta)
        if tail > peak:
            peak = tail
    return peak


@njit(cache=True, parallel=True)
def max_direction_displacements(accel_x, accel_y, dt, periods, zeta, include_tail):
    """RotD100 SD(T) [m] for each period T [s] (:func:`peak_resultant_displacement`), periods in parallel."""
    out = np.empty(periods.shape[0])
    for j in prange(periods.shape[0]):
        out[j] = peak_resultant_displacement(accel_x, accel_y, dt, 2.0 * math.pi / periods[j], zeta, include_tail)
    return out


def _components(accel_x, accel_y):
    """The two components as float64 arrays of one length (the shorter is zero after its end)."""
    x = np.asarray(accel_x, dtype=np.float64).ravel()
    y = np.asarray(accel_y, dtype=np.float64).ravel()
    if x.size < 2 or y.size < 2:
        raise ValueError("each component needs at least 2 samples")
    n = max(x.size, y.size)
    if x.size < n:
        x = np.concatenate([x, np.zeros(n - x.size)])
    if y.size < n:
        y = np.concatenate([y, np.zeros(n - y.size)])
    return np.ascontiguousarray(x), np.ascontiguousarray(y)


def max_direction_spectrum(accel_x, accel_y, dt: float, periods, damping: float = DEFAULT_DAMPING_ASCE, *,
                           include_tail: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Maximum-direction (RotD100) spectrum (SD [m], PSV [m/s], PSA [m/s²]) of two horizontal components.

    SD(T) = max over t of √(u_x² + u_y²) of two identical oscillators (period T, damping ratio
    ``damping``) under the components; PSV = ωSD, PSA = ω²SD (the pseudo-acceleration of ASCE 7-22
    §16.2.3.2's maximum-direction spectrum).  Exact for ü_g linear between samples (module docstring).

    Args:
        accel_x, accel_y: orthogonal horizontal components ü_g [m/s²] at spacing ``dt`` (a shorter one is
            padded with zeros).
        dt: sample spacing [s].
        periods: oscillator periods T [s] (> 0).
        damping: damping ratio ζ (default 0.05, ASCE 7-22's 5 %).
        include_tail: count the free vibration after the records' end.

    Returns:
        (SD, PSV, PSA), arrays of the shape of ``periods``.
    """
    x, y = _components(accel_x, accel_y)
    periods = np.ascontiguousarray(np.atleast_1d(periods), dtype=np.float64)
    if not dt > 0.0:
        raise ValueError(f"dt must be > 0, got {dt!r}")
    if np.any(periods <= 0.0):
        raise ValueError("periods must be > 0")
    if not 0.0 <= damping < 1.0:
        raise ValueError(f"damping ratio must be in [0, 1), got {damping!r}")
    sd = max_direction_displacements(x, y, float(dt), periods, float(damping), include_tail)
    omega = 2.0 * np.pi / periods
    return sd, omega * sd, omega * omega * sd


def motions_max_direction_spectrum(motion_x, motion_y, periods, damping: float = DEFAULT_DAMPING_ASCE):
    """(SD [m], PSV [m/s], PSA [m/s²]) RotD100 spectrum of two record GroundMotions (their scaled samples).

    Raises:
        ValueError: a motion that is not a sampled record, or components with different time steps.
    """
    for motion in (motion_x, motion_y):
        if not motion.is_record:
            raise ValueError(f"{motion.name} is not a sampled record")
    if abs(motion_x.dt - motion_y.dt) > 1e-9 * motion_x.dt:
        raise ValueError(f"the components have different time steps: {motion_x.dt:g} s and {motion_y.dt:g} s")
    return max_direction_spectrum(motion_x.scale * motion_x.samples, motion_y.scale * motion_y.samples,
                                  motion_x.dt, periods, damping)
