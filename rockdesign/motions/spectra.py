"""Elastic response spectra of ground motions, exact for piecewise-linear input (SPEC §5).

The single-degree-of-freedom oscillator ü + 2ζωu̇ + ω²u = −ü_g(t) is advanced from sample to
sample with the exact Nigam–Jennings (1968) recurrence: between samples ü_g is linear in t (the
same interpolation the dynamics engine uses, SPEC §0), so the state at the next sample follows
exactly from x_{i+1} = A x_i + B (ü_g,i, ü_g,i+1). The oscillator starts at rest at the first
sample. After the last sample the ground is at rest (ü_g = 0, as in
:mod:`rockdesign.motions.excitation`) and the oscillator decays freely; the largest |u| of that
free decay is found in closed form (:func:`free_vibration_peak`), not by padding zeros.

SD is the maximum |u| at the samples — sub-stepped to Δt/m ≤ T/10 where T < 10 Δt, as PEER computes
its NGA-West2 spectra (a peak between samples is otherwise missed: 2 % low at T = 8.4 Δt) — and
over the free-vibration tail; PSV = ω SD and
PSA = ω² SD. SD_max (Polyakov's rule 2, thesis Sec 4.2.5) is the maximum of SD over a period band,
found on a logarithmic grid and refined around the largest local maxima.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from .defaults import DEFAULT_BAND, DEFAULT_DAMPING, DEFAULT_N_PERIODS  # noqa: F401  (re-exported)


@njit(cache=True)
def nigam_jennings_step(omega, zeta, dt):
    """The 8 coefficients (A11, A12, A21, A22, B11, B12, B21, B22) of one exact step, as a tuple.

    Args:
        omega: circular frequency ω [rad/s] (> 0).
        zeta: damping ratio ζ (0 ≤ ζ < 1).
        dt: step [s] (> 0; the B coefficients lose digits as 1/(ω dt)² for very short steps).

    For ü + 2ζωu̇ + ω²u = −ü_g with ü_g linear from a_i to a_j over the step,
    u_j = A11 u_i + A12 v_i + B11 a_i + B12 a_j and v_j = A21 u_i + A22 v_i + B21 a_i + B22 a_j
    (Nigam & Jennings 1968).  Used by the elastic spectra and by the engine's exact rest step of a
    podium (rockdesign.planar.dynamics.rest_step).
    """
    root = math.sqrt(1.0 - zeta * zeta)
    omega_d = omega * root
    e = math.exp(-zeta * omega * dt)
    s = math.sin(omega_d * dt)
    c = math.cos(omega_d * dt)
    w2 = omega * omega
    k1 = (2.0 * zeta * zeta - 1.0) / (w2 * dt)
    k2 = 2.0 * zeta / (w2 * omega * dt)
    c_minus = c - zeta / root * s
    d_sin = omega_d * s + zeta * omega * c
    return (e * (zeta / root * s + c), e * s / omega_d, -omega / root * e * s, e * c_minus,
            e * ((k1 + zeta / omega) * s / omega_d + (k2 + 1.0 / w2) * c) - k2,
            -e * (k1 * s / omega_d + k2 * c) - 1.0 / w2 + k2,
            e * ((k1 + zeta / omega) * c_minus - (k2 + 1.0 / w2) * d_sin) + 1.0 / (w2 * dt),
            -e * (k1 * c_minus - k2 * d_sin) - 1.0 / (w2 * dt))


@njit(cache=True)
def nigam_jennings_coefficients(omega, zeta, dt):
    """:func:`nigam_jennings_step` as a float64 array of 8 (A11, A12, A21, A22, B11, B12, B21, B22)."""
    out = np.empty(8)
    k = nigam_jennings_step(omega, zeta, dt)
    for i in range(8):
        out[i] = k[i]
    return out


@njit(cache=True)
def free_vibration_peak(u0, v0, omega, zeta):
    """max |u(τ)| for τ ≥ 0 of the free damped oscillator starting at (u0 [m], v0 [m/s]).

    u(τ) = e^(−ζωτ)(u0 cos ω_d τ + (v0 + ζωu0)/ω_d sin ω_d τ). Its extrema (u̇ = 0) are π/ω_d apart
    and shrink by e^(−ζωπ/ω_d) each, so the maximum is |u0| or |u| at the first extremum
    τ1 ∈ [0, π/ω_d), where tan(ω_d τ1) = v0 ω_d/(ζωv0 + ω²u0).
    """
    if v0 == 0.0:
        return abs(u0)
    root = math.sqrt(1.0 - zeta * zeta)
    omega_d = omega * root
    x = math.atan2(v0 * omega_d, zeta * omega * v0 + omega * omega * u0)
    if x < 0.0:
        x += math.pi
    tau = x / omega_d
    u1 = math.exp(-zeta * omega * tau) * (u0 * math.cos(x) + (v0 + zeta * omega * u0) / omega_d * math.sin(x))
    return max(abs(u0), abs(u1))


@njit(cache=True)
def sdof_response(accel, dt, omega, zeta):
    """Relative displacement u [m] and velocity v [m/s] at the samples (oscillator at rest at t = 0).

    Args:
        accel: ground acceleration samples ü_g [m/s²] at t = i·dt, linear in between.
        dt: sample spacing [s].
        omega: circular frequency ω [rad/s].
        zeta: damping ratio ζ.
    """
    n = accel.shape[0]
    u = np.zeros(n)
    v = np.zeros(n)
    k = nigam_jennings_coefficients(omega, zeta, dt)
    for i in range(n - 1):
        u[i + 1] = k[0] * u[i] + k[1] * v[i] + k[4] * accel[i] + k[5] * accel[i + 1]
        v[i + 1] = k[2] * u[i] + k[3] * v[i] + k[6] * accel[i] + k[7] * accel[i + 1]
    return u, v


STEPS_PER_PERIOD = 10.0
"""Where T < 10 Δt the record is sub-stepped to Δt/m ≤ T/10 (ü_g linear in between, as in every step) so
the peak is not missed between samples — the convention of the PEER NGA-West2 spectra (reproduced to
1e-5, tests/validation/test_elastic_spectra_published.py)."""


@njit(cache=True)
def substepped_peak(accel, dt, omega, zeta, include_tail, absolute):
    """The oscillator's peak response (at rest at t = 0) over the samples — sub-stepped to Δt/m ≤ T/10 where
    T < 10 Δt (:data:`STEPS_PER_PERIOD`; the exact Nigam–Jennings recurrence over each sub-step) — and, if
    ``include_tail``, over the free decay after the record: max |u| [m], or with ``absolute`` the absolute
    acceleration max |ü + ü_g| = max |ω²u + 2ζωu̇| [m/s²].

    In free vibration a = ω²u + 2ζωu̇ obeys the oscillator's own equation, so the tail's peak of the absolute
    acceleration is :func:`free_vibration_peak` of (a, ȧ) with ȧ = ω²u̇ + 2ζωü, ü = −ω²u − 2ζωu̇ (ground at
    rest), not the pseudo-acceleration ω²|u|.
    """
    m = max(1, int(math.ceil(STEPS_PER_PERIOD * dt * omega / (2.0 * math.pi) - 1e-9)))
    k = nigam_jennings_coefficients(omega, zeta, dt / m)
    w2 = omega * omega
    c = 2.0 * zeta * omega
    u = 0.0
    v = 0.0
    peak = 0.0
    for i in range(accel.shape[0] - 1):
        slope = (accel[i + 1] - accel[i]) / m
        for r in range(m):
            a0 = accel[i] + slope * r
            a1 = accel[i + 1] if r == m - 1 else accel[i] + slope * (r + 1)
            u_next = k[0] * u + k[1] * v + k[4] * a0 + k[5] * a1
            v = k[2] * u + k[3] * v + k[6] * a0 + k[7] * a1
            u = u_next
            y = abs(w2 * u + c * v) if absolute else abs(u)
            if y > peak:
                peak = y
    if include_tail:
        if absolute:
            tail = free_vibration_peak(w2 * u + c * v, w2 * v + c * (-w2 * u - c * v), omega, zeta)
        else:
            tail = free_vibration_peak(u, v, omega, zeta)
        if tail > peak:
            peak = tail
    return peak


@njit(cache=True)
def peak_displacement(accel, dt, omega, zeta, include_tail):
    """max |u| [m] of the oscillator (:func:`substepped_peak`), the elastic spectra's SD (SPEC §5)."""
    return substepped_peak(accel, dt, omega, zeta, include_tail, False)


@njit(cache=True)
def peak_absolute_acceleration(accel, dt, omega, zeta, include_tail):
    """max |ü + ü_g| [m/s²] of the oscillator (:func:`substepped_peak`), the fixed-base reference of
    SPEC §13."""
    return substepped_peak(accel, dt, omega, zeta, include_tail, True)


def fixed_base_acceleration(accel_si, dt: float, period: float, damping: float, *, include_tail: bool = True) -> float:
    """Peak absolute acceleration [m/s²] of a fixed-base oscillator of ``period`` [s] and ``damping`` ratio
    under the sampled ground acceleration ``accel_si`` [m/s²] at spacing ``dt`` [s] (SPEC §13's fixed-base
    reference: ü + 2ζωu̇ + ω²u = −ü_g, exact for ü_g linear between samples, peak of |ω²u + 2ζωu̇|)."""
    accel, periods = _check_inputs(accel_si, dt, period, damping)
    return float(peak_absolute_acceleration(accel, float(dt), 2.0 * math.pi / float(periods[0]), float(damping),
                                            include_tail))


@njit(cache=True, parallel=True)
def spectral_displacements(accel, dt, periods, zeta, include_tail):
    """SD(T) [m] for each period T [s] (exact piecewise-linear recurrence, SPEC §5), periods in parallel."""
    out = np.empty(periods.shape[0])
    for j in prange(periods.shape[0]):
        out[j] = peak_displacement(accel, dt, 2.0 * math.pi / periods[j], zeta, include_tail)
    return out


def _check_inputs(accel, dt, periods, damping):
    accel = np.ascontiguousarray(accel, dtype=np.float64)
    periods = np.ascontiguousarray(np.atleast_1d(periods), dtype=np.float64)
    if accel.ndim != 1 or accel.size < 2:
        raise ValueError("accel must be a 1-D array of at least 2 samples")
    if not dt > 0.0:
        raise ValueError(f"dt must be > 0, got {dt!r}")
    if np.any(periods <= 0.0):
        raise ValueError("periods must be > 0")
    if not 0.0 <= damping < 1.0:
        raise ValueError(f"damping ratio must be in [0, 1), got {damping!r}")
    return accel, periods


def response_spectrum(accel_si, dt: float, periods, damping: float = DEFAULT_DAMPING, *,
                      include_tail: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Elastic response spectrum (SD [m], PSV [m/s], PSA [m/s²]) of a sampled ground acceleration.

    Exact for ü_g linear between samples (Nigam–Jennings); the oscillator starts at rest; the
    free vibration after the last sample is included unless ``include_tail`` is False (SPEC §5).

    Args:
        accel_si: ü_g samples [m/s²] at spacing ``dt`` [s].
        dt: sample spacing [s].
        periods: oscillator periods T [s].
        damping: damping ratio ζ (0.02 = 2 %).
        include_tail: count the free decay after the record's end.

    Returns:
        (SD, PSV = ωSD, PSA = ω²SD), arrays of the shape of ``periods``.
    """
    accel, periods = _check_inputs(accel_si, dt, periods, damping)
    sd = spectral_displacements(accel, float(dt), periods, float(damping), include_tail)
    omega = 2.0 * np.pi / periods
    return sd, omega * sd, omega * omega * sd


def period_grid(band=DEFAULT_BAND, n_periods: int = DEFAULT_N_PERIODS) -> np.ndarray:
    """Logarithmically spaced periods [s] from band[0] to band[1] inclusive."""
    lo, hi = float(band[0]), float(band[1])
    if not 0.0 < lo < hi:
        raise ValueError(f"period band must satisfy 0 < Tmin < Tmax, got {band!r}")
    return np.geomspace(lo, hi, int(n_periods))


def sd_max_of_samples(accel_si, dt: float, damping: float = DEFAULT_DAMPING, band=DEFAULT_BAND,
                      n_periods: int = DEFAULT_N_PERIODS, *, include_tail: bool = True,
                      refine: bool = True) -> tuple[float, float]:
    """SD_max [m] over the period band and the period [s] where it occurs (SPEC §5).

    A logarithmic grid of ``n_periods`` periods is searched first; then every local maximum within
    3 % of the largest (at most 4) is refined by three rounds of 21-point grids shrinking the
    bracket tenfold each time, so the period is resolved to ~3e-5 relative and SD_max to round-off.
    """
    accel, periods = _check_inputs(accel_si, dt, period_grid(band, n_periods), damping)
    zeta = float(damping)
    sd = spectral_displacements(accel, float(dt), periods, zeta, include_tail)
    best_i = int(np.argmax(sd))
    best_sd, best_t = float(sd[best_i]), float(periods[best_i])
    if not refine:
        return best_sd, best_t
    n = periods.size
    is_peak = np.zeros(n, dtype=bool)
    for i in range(n):
        left = sd[i - 1] if i > 0 else -np.inf
        right = sd[i + 1] if i < n - 1 else -np.inf
        is_peak[i] = sd[i] >= left and sd[i] >= right
    candidates = [i for i in np.argsort(sd)[::-1] if is_peak[i] and sd[i] >= 0.97 * best_sd][:4]
    lo_band, hi_band = float(periods[0]), float(periods[-1])
    for i in candidates:
        lo = periods[max(i - 1, 0)]
        hi = periods[min(i + 1, n - 1)]
        for _ in range(3):
            grid = np.geomspace(lo, hi, 21)
            values = spectral_displacements(accel, float(dt), grid, zeta, include_tail)
            j = int(np.argmax(values))
            if values[j] > best_sd:
                best_sd, best_t = float(values[j]), float(grid[j])
            lo = max(grid[max(j - 1, 0)], lo_band)
            hi = min(grid[min(j + 1, 20)], hi_band)
            if hi <= lo:
                break
    return best_sd, best_t


def motion_samples(motion) -> tuple[np.ndarray, float]:
    """(ü_g samples [m/s²], dt [s]) of a GroundMotion: a record's scaled samples, or an analytic
    pulse sampled at T_p/200 over its support (piecewise-linear between those samples)."""
    if motion.is_record:
        return motion.sampled()[1], motion.dt
    if motion.params.size < 2:
        raise ValueError(f"{motion.name} has no samples (free vibration)")
    dt = float(motion.params[1]) / 200.0
    return motion.sampled(dt)[1], dt


def sd_max(motion, damping: float = DEFAULT_DAMPING, band=DEFAULT_BAND,
           n_periods: int = DEFAULT_N_PERIODS, *, refine: bool = True) -> tuple[float, float]:
    """Polyakov's SD_max [m] of a GroundMotion and its period [s] (thesis Sec 4.2.5, SPEC §5).

    Defaults: 2 % damping, band 0.05–10 s; state both wherever SD_max is reported. Records use
    their samples (times the motion's scale); analytic pulses are sampled at T_p/200.
    """
    accel, dt = motion_samples(motion)
    return sd_max_of_samples(accel, dt, damping, band, n_periods, refine=refine)


def motion_spectrum(motion, periods, damping: float = DEFAULT_DAMPING):
    """(SD [m], PSV [m/s], PSA [m/s²]) of a GroundMotion at the given periods [s]."""
    accel, dt = motion_samples(motion)
    return response_spectrum(accel, dt, periods, damping)

