"""An engine-made free-vibration "measurement" with different restitution on the two sides.

The engine applies one c_r at every impact (θ̇⁺ = √c_r θ̇⁻, Eq 3.14 / SPEC §3.4). A specimen that
loses more energy on one side (thesis Sec 6.4.3, observation 2) is synthesised piecewise: each
half-cycle is an engine run with c_r = 1 from θ = 0 up to its first impact, and the next run
starts at θ = 0 with θ̇ multiplied by √c_r of that side. Used to test :mod:`.calibrate` and to
demonstrate it.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import CubicSpline

from ..design.geometry import rocking_geometry
from ..design.quantities import system_frequency_parameter
from ..dynamics.simulate import simulate
from ..system import RockingSystem


def free_rocking_history(system: RockingSystem, theta0: float, *, c_r_left: float, c_r_right: float,
                         duration: float, rate: float = 500.0, noise: float = 0.0, offset: float = 0.0,
                         seed: int = 0, min_rate: float = 1e-3) -> tuple[np.ndarray, np.ndarray]:
    """(t [s], θ [rad]) of free rocking released at rest from ``theta0`` [rad], sampled at ``rate`` [Hz].

    ``c_r_right`` applies to impacts ending a half-cycle with θ > 0, ``c_r_left`` to those with
    θ < 0. Gaussian noise of SD ``noise`` [rad] (seeded) and a constant ``offset`` [rad] are added.
    The history stays at θ = 0 once |θ̇| after an impact falls below ``min_rate`` [rad/s].
    """
    elastic = system.with_restitution(1.0)
    fine = 2e-4
    pieces_t, pieces_y = [], []
    t0, th0, thd0 = 0.0, float(theta0), 0.0
    geo = rocking_geometry(system.column)
    p = system_frequency_parameter(system)[0]
    while t0 < duration:
        # the half-cycle's length from Eq 2.8 (θ0 from the energy, Eq 2.10), with a margin
        cos_peak = math.cos(geo.alpha - abs(th0)) + thd0 ** 2 / (2.0 * p ** 2)
        theta_peak = max(1e-9, geo.alpha - math.acos(min(1.0, cos_peak)))
        span = 2.0 / p * math.acosh(1.0 / max(1e-12, 1.0 - min(theta_peak, 0.999 * geo.alpha) / geo.alpha))
        impact, horizon = None, 1.5 * span + 0.05
        while impact is None:
            r = simulate(elastic, None, theta0=th0, thetadot0=thd0, t_end=min(duration - t0, horizon) + fine,
                         output_dt=fine, rtol=1e-12, atol=1e-14)
            impact = next((e for e in r.events if e.kind == "impact" and e.time > 1e-9), None)
            if horizon >= duration - t0:
                break
            horizon *= 2.0
        end = impact.time if impact is not None else r.t[-1]
        keep = r.t <= end
        pieces_t.append(t0 + r.t[keep])
        pieces_y.append(r.theta[keep])
        if impact is None:
            break
        side = 1 if thd0 > 0 or (thd0 == 0 and th0 > 0) else -1   # the half-cycle just ended was on this side
        rate_before = impact.state[1]
        t0 += impact.time
        thd0 = math.sqrt(c_r_right if side > 0 else c_r_left) * rate_before
        th0 = 0.0
        if abs(thd0) < min_rate:
            pieces_t.append(np.array([t0 + 1e-9, duration + 1.0]))
            pieces_y.append(np.zeros(2))
            break
    t_all = np.concatenate(pieces_t)
    y_all = np.concatenate(pieces_y)
    t_all, unique = np.unique(t_all, return_index=True)
    y_all = y_all[unique]
    t = np.arange(0.0, duration, 1.0 / rate)
    theta = _piecewise_interp(t_all, y_all, t)
    if noise > 0.0:
        theta = theta + np.random.default_rng(seed).normal(0.0, noise, t.size)
    return t, theta + offset


def _piecewise_interp(t_src: np.ndarray, y_src: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Cubic-spline interpolation within each half-cycle (the kinks at θ = 0 are not smoothed)."""
    out = np.interp(t, t_src, y_src)
    zero = np.flatnonzero(np.abs(y_src) < 1e-15)
    bounds = np.unique(np.concatenate([[0], zero, [t_src.size - 1]]))
    for a, b in zip(bounds[:-1], bounds[1:]):
        if b - a < 4:
            continue
        sel = (t >= t_src[a]) & (t <= t_src[b])
        if sel.any():
            out[sel] = CubicSpline(t_src[a:b + 1], y_src[a:b + 1])(t[sel])
    return out
