"""Polyakov's overturning line of a rocking spectrum (thesis Sec 4.2.4, Figs 4.6–4.7; SPEC §5).

Polyakov's second rule treats the rocking storey as a very flexible elastic oscillator: it is stable
while the maximum elastic spectral displacement SD_max (damping ζ, period band) of the ground motion
stays below the displacement capacity 2B (for columns with extensions, the column-top displacement
at θc — our generalisation, SPEC §5).  For a pulse of shape f and period T_p the ground motion is
linear in its amplitude, so SD_max(a_p, T_p) = a_p · SD_max(1, T_p) and the pulse amplitude that
Polyakov predicts to overturn the structure is

    a_p,P(T_p) = u_capacity / SD_max(unit pulse of period T_p).

SD_max of the unit pulse is computed exactly for the pulse sampled at T_p/200 (Nigam–Jennings,
including the free vibration after the pulse) with :func:`rockdesign.motions.spectra.sd_max`.
"""
from __future__ import annotations

import numpy as np

from ...motions.motion import pulse_motion
from ...motions.spectra import DEFAULT_BAND, DEFAULT_DAMPING, sd_max


def unit_pulse_sd_max(pulse: str, periods, *, tm_ratio: float = 1.5, damping: float = DEFAULT_DAMPING,
                      band: tuple[float, float] = DEFAULT_BAND) -> np.ndarray:
    """SD_max [m per m/s² of amplitude] of the pulse with a_p = 1 m/s² for each period T_p [s].

    Args:
        pulse: pulse name (``ricker-anti`` ...).
        periods: pulse periods T_p [s].
        tm_ratio: t_m/T_p of Ricker wavelets.
        damping: damping ratio ζ of the elastic spectrum (Polyakov: 2 %).
        band: oscillator period band [s] searched for the maximum.
    """
    out = np.empty(len(periods))
    for i, T in enumerate(np.asarray(periods, dtype=float)):
        motion = pulse_motion(pulse, 1.0, float(T), t_m=tm_ratio * float(T))
        out[i] = sd_max(motion, damping, band)[0]
    return out


def polyakov_amplitudes(pulse: str, periods, u_capacity: float, *, tm_ratio: float = 1.5,
                        damping: float = DEFAULT_DAMPING, band: tuple[float, float] = DEFAULT_BAND,
                        max_points: int = 401) -> tuple[np.ndarray, np.ndarray]:
    """Polyakov's overturning amplitude a_p,P [m/s²] at each pulse period T_p [s]: SD_max = u_capacity.

    SD_max is evaluated exactly at up to ``max_points`` periods spread over ``periods`` (all of
    them if fewer) and interpolated linearly in log T_p in between — SD_max(1, T_p) is smooth (it
    scales as T_p² wherever the band contains the spectral peak).

    Args:
        pulse: pulse name.
        periods: pulse periods T_p [s] (any order).
        u_capacity: displacement capacity [m] (2B; column-top displacement at θc with extensions).
        tm_ratio, damping, band: as :func:`unit_pulse_sd_max`.
        max_points: largest number of exact evaluations.

    Returns:
        (a_p,P [m/s²], SD_max of the unit pulse [m/(m/s²)]) per period.
    """
    T = np.asarray(periods, dtype=float)
    if T.size <= max_points:
        sd = unit_pulse_sd_max(pulse, T, tm_ratio=tm_ratio, damping=damping, band=band)
    else:
        order = np.argsort(T)
        Ts = T[order]
        idx = np.unique(np.round(np.linspace(0, T.size - 1, max_points)).astype(int))
        sd_nodes = unit_pulse_sd_max(pulse, Ts[idx], tm_ratio=tm_ratio, damping=damping, band=band)
        sd_sorted = np.exp(np.interp(np.log(Ts), np.log(Ts[idx]), np.log(sd_nodes)))
        sd = np.empty_like(T)
        sd[order] = sd_sorted
    with np.errstate(divide="ignore"):
        a_p = np.where(sd > 0.0, u_capacity / sd, np.inf)
    return a_p, sd
