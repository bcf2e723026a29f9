"""Ground-motion intensity measures (thesis Table 5.6, Eqs 5.44–5.46; SPEC §5).

The acceleration is piecewise linear between samples (SPEC §0), and every integral here is exact
for that interpolation: velocity and displacement by exact integration (no baseline correction),
peaks including the extrema inside a step, Arias and CAV by exact step integrals, durations by
exact crossing times. All inputs and outputs are SI (m/s², m/s, m, s, Hz).

* PGA = max |a|; PGV = max |v|; PGD = max |d| over the record (the displacement of an
  uncorrected record drifts after its end, so PGD is taken over [0, t_end]).
* Arias intensity I_a = π/(2g) ∫ a² dt [m/s] (Eq 5.46).
* CAV = ∫ |a| dt [m/s] over the whole record (Eq 5.44; the thesis writes the limit as T_d, SPEC §5
  the whole record — the part outside the bracket is below 0.05 g anyway).
* Bracketed duration T_d: first to last exceedance of 0.05 g (Table 5.6).
* a_rms = √(1/T_d ∫ a² dt) over the bracketed duration (Eq 5.45).
* Significant duration D5–95: time between 5 % and 95 % of the final Arias intensity.
* Predominant frequency: peak of the Fourier amplitude spectrum smoothed with the Konno–Ohmachi
  window (b = 40) on 400 log-spaced frequencies between 0.1 Hz and min(25 Hz, 0.8 × Nyquist)
  (Table 5.6: "obtained from a smoothed spectrum").
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

BRACKET_THRESHOLD_G = 0.05
"""Threshold of the bracketed duration, in g (Table 5.6)."""

KONNO_OHMACHI_B = 40.0
"""Bandwidth coefficient b of the Konno–Ohmachi smoothing of the predominant frequency."""


@njit(cache=True)
def velocity_displacement(accel, dt):
    """Ground velocity [m/s] and displacement [m] at the samples, exact for linear a (v(0) = d(0) = 0)."""
    n = accel.shape[0]
    v = np.zeros(n)
    d = np.zeros(n)
    for i in range(n - 1):
        v[i + 1] = v[i] + 0.5 * dt * (accel[i] + accel[i + 1])
        d[i + 1] = d[i] + v[i] * dt + dt * dt * (2.0 * accel[i] + accel[i + 1]) / 6.0
    return v, d


@njit(cache=True)
def peak_velocity(accel, dt):
    """PGV [m/s]: max |v| including the extrema inside steps where a changes sign."""
    v = 0.0
    peak = 0.0
    for i in range(accel.shape[0] - 1):
        a0 = accel[i]
        a1 = accel[i + 1]
        if a0 * a1 < 0.0:
            slope = (a1 - a0) / dt
            inner = v - a0 * a0 / (2.0 * slope)
            peak = max(peak, abs(inner))
        v += 0.5 * dt * (a0 + a1)
        peak = max(peak, abs(v))
    return peak


@njit(cache=True)
def peak_displacement_ground(accel, dt):
    """PGD [m]: max |d| over [0, t_end], including extrema inside steps (where v = 0)."""
    v = 0.0
    d = 0.0
    peak = 0.0
    for i in range(accel.shape[0] - 1):
        a0 = accel[i]
        slope = (accel[i + 1] - a0) / dt
        # v(τ) = v + a0 τ + slope τ²/2 = 0 for τ in (0, dt)
        roots = np.empty(2)
        nroots = 0
        if abs(slope) * dt < 1e-14 * (abs(a0) + 1e-300):
            if a0 != 0.0:
                roots[0] = -v / a0
                nroots = 1
        else:
            disc = a0 * a0 - 2.0 * slope * v
            if disc >= 0.0:
                q = -(a0 + math.copysign(math.sqrt(disc), a0 if a0 != 0.0 else 1.0))
                if q != 0.0:
                    roots[0] = q / slope
                    roots[1] = 2.0 * v / q
                    nroots = 2
                else:
                    roots[0] = 0.0
                    nroots = 1
        for k in range(nroots):
            tau = roots[k]
            if 0.0 < tau < dt:
                inner = d + v * tau + a0 * tau * tau / 2.0 + slope * tau * tau * tau / 6.0
                peak = max(peak, abs(inner))
        d += v * dt + dt * dt * (2.0 * a0 + accel[i + 1]) / 6.0
        v += 0.5 * dt * (a0 + accel[i + 1])
        peak = max(peak, abs(d))
    return peak


@njit(cache=True)
def integral_of_square(accel, dt):
    """∫ a² dt [m²/s³] over the record, exact for linear a: Σ dt (a_i² + a_i a_j + a_j²)/3."""
    total = 0.0
    for i in range(accel.shape[0] - 1):
        a0 = accel[i]
        a1 = accel[i + 1]
        total += dt * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0
    return total


@njit(cache=True)
def integral_of_abs(accel, dt):
    """∫ |a| dt [m/s] over the record, exact for linear a (split at sign changes)."""
    total = 0.0
    for i in range(accel.shape[0] - 1):
        a0 = abs(accel[i])
        a1 = abs(accel[i + 1])
        if accel[i] * accel[i + 1] < 0.0:
            total += dt * (a0 * a0 + a1 * a1) / (2.0 * (a0 + a1))
        else:
            total += 0.5 * dt * (a0 + a1)
    return total


@njit(cache=True)
def _square_between(accel, dt, t1, t2):
    """∫_{t1}^{t2} a² dt for linear a (0 ≤ t1 ≤ t2 ≤ t_end)."""
    n = accel.shape[0]
    total = 0.0
    i0 = int(math.floor(t1 / dt))
    for i in range(max(i0, 0), n - 1):
        lo = max(t1, i * dt)
        hi = min(t2, (i + 1) * dt)
        if hi <= lo:
            if i * dt >= t2:
                break
            continue
        slope = (accel[i + 1] - accel[i]) / dt
        a_lo = accel[i] + slope * (lo - i * dt)
        a_hi = accel[i] + slope * (hi - i * dt)
        total += (hi - lo) * (a_lo * a_lo + a_lo * a_hi + a_hi * a_hi) / 3.0
    return total


@njit(cache=True)
def _arias_crossing(accel, dt, target):
    """Time [s] at which ∫_0^t a² dt reaches ``target`` (monotone; bisection inside the step)."""
    cumulative = 0.0
    for i in range(accel.shape[0] - 1):
        a0 = accel[i]
        a1 = accel[i + 1]
        step = dt * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0
        if cumulative + step >= target:
            slope = (a1 - a0) / dt
            lo = 0.0
            hi = dt
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                value = cumulative + a0 * a0 * mid + a0 * slope * mid * mid + slope * slope * mid ** 3 / 3.0
                if value < target:
                    lo = mid
                else:
                    hi = mid
            return i * dt + 0.5 * (lo + hi)
        cumulative += step
    return (accel.shape[0] - 1) * dt


@njit(cache=True)
def _threshold_crossings(accel, dt, threshold):
    """(first, last) times [s] where |a| reaches ``threshold``; (-1, -1) if it never does."""
    n = accel.shape[0]
    first = -1.0
    last = -1.0
    for i in range(n):
        if abs(accel[i]) >= threshold:
            if i == 0:
                first = 0.0
            else:
                target = math.copysign(threshold, accel[i])
                first = (i - 1) * dt + dt * (target - accel[i - 1]) / (accel[i] - accel[i - 1])
            break
    for i in range(n - 1, -1, -1):
        if abs(accel[i]) >= threshold:
            if i == n - 1:
                last = i * dt
            else:
                target = math.copysign(threshold, accel[i])
                last = i * dt + dt * (target - accel[i]) / (accel[i + 1] - accel[i])
            break
    return first, last


@njit(cache=True)
def _konno_ohmachi(freqs, amplitudes, centres, b):
    """Konno–Ohmachi smoothing [sin(b log10(f/fc))/(b log10(f/fc))]^4 at each centre frequency."""
    out = np.zeros(centres.shape[0])
    for j in range(centres.shape[0]):
        fc = centres[j]
        num = 0.0
        den = 0.0
        # the window is negligible beyond a factor 10^(π/b · 20) from fc
        lo = fc * 10.0 ** (-20.0 * math.pi / b)
        hi = fc * 10.0 ** (20.0 * math.pi / b)
        for k in range(freqs.shape[0]):
            f = freqs[k]
            if f <= 0.0 or f < lo:
                continue
            if f > hi:
                break
            x = b * math.log10(f / fc)
            w = 1.0 if x == 0.0 else (math.sin(x) / x) ** 4
            num += w * amplitudes[k]
            den += w
        out[j] = num / den if den > 0.0 else 0.0
    return out


def _as_array(accel) -> np.ndarray:
    accel = np.ascontiguousarray(accel, dtype=np.float64)
    if accel.ndim != 1 or accel.size < 2:
        raise ValueError("accel must be a 1-D array of at least 2 samples")
    return accel


def arias_intensity(accel, dt: float, gravity: float = 9.81) -> float:
    """Arias intensity I_a = π/(2g) ∫ a² dt [m/s] (thesis Eq 5.46); accel in m/s², dt in s."""
    return math.pi / (2.0 * gravity) * float(integral_of_square(_as_array(accel), float(dt)))


def cumulative_absolute_velocity(accel, dt: float) -> float:
    """CAV = ∫ |a| dt [m/s] over the record (thesis Eq 5.44)."""
    return float(integral_of_abs(_as_array(accel), float(dt)))


def bracketed_duration(accel, dt: float, threshold: float) -> tuple[float, float, float]:
    """(T_d, t_first, t_last) [s]: first to last time |a| reaches ``threshold`` [m/s²] (Table 5.6).

    Returns (0, nan, nan) if the threshold is never reached.
    """
    first, last = _threshold_crossings(_as_array(accel), float(dt), float(threshold))
    if first < 0:
        return 0.0, math.nan, math.nan
    return float(last - first), float(first), float(last)


def rms_acceleration(accel, dt: float, t_start: float, t_end: float) -> float:
    """a_rms = √(1/T_d ∫_{t_start}^{t_end} a² dt) [m/s²] (thesis Eq 5.45); 0 if the window is empty."""
    if not t_end > t_start:
        return 0.0
    integral = _square_between(_as_array(accel), float(dt), float(t_start), float(t_end))
    return math.sqrt(integral / (t_end - t_start))


def significant_duration(accel, dt: float, low: float = 0.05, high: float = 0.95) -> tuple[float, float, float]:
    """(D, t_low, t_high) [s]: time between ``low`` and ``high`` fractions of the final Arias intensity."""
    accel = _as_array(accel)
    total = integral_of_square(accel, float(dt))
    if total <= 0:
        return 0.0, math.nan, math.nan
    t_low = _arias_crossing(accel, float(dt), low * total)
    t_high = _arias_crossing(accel, float(dt), high * total)
    return float(t_high - t_low), float(t_low), float(t_high)


def fourier_amplitude(accel, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """(f [Hz], |A(f)| [m/s]) of the samples: dt·|FFT|, zero-padded to the next power of two."""
    accel = _as_array(accel)
    nfft = 1 << int(math.ceil(math.log2(accel.size)))
    amplitude = dt * np.abs(np.fft.rfft(accel, n=nfft))
    return np.fft.rfftfreq(nfft, dt), amplitude


def predominant_frequency(accel, dt: float, b: float = KONNO_OHMACHI_B, n_freqs: int = 400,
                          f_min: float = 0.1, f_max: float = 25.0) -> float:
    """Frequency [Hz] of the peak of the Konno–Ohmachi-smoothed Fourier amplitude spectrum (Table 5.6);
    None for a record without motion (all zeros)."""
    freqs, amplitude = fourier_amplitude(accel, dt)
    hi = min(f_max, 0.8 * 0.5 / dt)
    centres = np.geomspace(f_min, hi, n_freqs)
    smooth = _konno_ohmachi(freqs, amplitude, centres, float(b))
    if not np.any(smooth > 0.0):
        return None         # no motion: there is no predominant frequency
    return float(centres[int(np.argmax(smooth))])


def intensity_measures(accel, dt: float, gravity: float = 9.81) -> dict[str, float]:
    """All measures of a sampled record (SI), keyed as in CONTRACT §3 ``records spectrum --json``.

    Keys: pga [m/s²], pgv [m/s], pgd [m], arias [m/s], cav [m/s], bracketed_duration [s],
    significant_duration [s] (D5–95), a_rms [m/s²] (over the bracketed duration),
    predominant_frequency [Hz].
    """
    accel = _as_array(accel)
    dt = float(dt)
    t_d, t1, t2 = bracketed_duration(accel, dt, BRACKET_THRESHOLD_G * gravity)
    return {
        "pga": float(np.max(np.abs(accel))),
        "pgv": float(peak_velocity(accel, dt)),
        "pgd": float(peak_displacement_ground(accel, dt)),
        "arias": arias_intensity(accel, dt, gravity),
        "cav": cumulative_absolute_velocity(accel, dt),
        "bracketed_duration": t_d,
        "significant_duration": significant_duration(accel, dt)[0],
        "a_rms": rms_acceleration(accel, dt, t1, t2) if t_d > 0 else 0.0,
        "predominant_frequency": predominant_frequency(accel, dt),
    }


PLAUSIBLE_DT = (1e-4, 0.1)
"""Sample intervals [s] of real accelerograms (0.005–0.02 s typically); outside: a warning."""
PLAUSIBLE_PGA_G = 5.0
"""Largest PGA [g] not flagged (recorded peaks stay below ~4 g)."""


def plausibility_warnings(motion, gravity: float = 9.81) -> list[str]:
    """Warnings for a record that is probably not what the user meant (the record is still analysed).

    Flags a sample interval outside :data:`PLAUSIBLE_DT`, a PGA above :data:`PLAUSIBLE_PGA_G` g, an
    all-zero record and non-finite samples.  Pulses are not checked.
    """
    if not getattr(motion, "is_record", False):
        return []
    out = []
    name = motion.name
    dt = motion.dt
    if not PLAUSIBLE_DT[0] <= dt <= PLAUSIBLE_DT[1]:
        out.append(f"{name}: sample interval dt = {dt:g} s is implausible for an accelerogram "
                   f"(expected {PLAUSIBLE_DT[0]:g}–{PLAUSIBLE_DT[1]:g} s) — check the file's DT")
    samples = np.asarray(motion.samples)
    if samples.size and not np.all(np.isfinite(samples)):
        out.append(f"{name}: the record contains non-finite values")
        return out
    pga = float(np.max(np.abs(samples))) * abs(motion.scale) if samples.size else 0.0
    if pga == 0.0:
        out.append(f"{name}: the record is all zeros (no ground motion)")
    elif pga > PLAUSIBLE_PGA_G * gravity:
        out.append(f"{name}: PGA = {pga / gravity:.3g} g is implausible (recorded PGAs stay below ~4 g) — "
                   "check the file's units and the scale")
    return out


def motion_measures(motion, gravity: float = 9.81) -> dict[str, float]:
    """:func:`intensity_measures` of a GroundMotion (records: their scaled samples)."""
    from .spectra import motion_samples
    accel, dt = motion_samples(motion)
    return intensity_measures(accel, dt, gravity)
