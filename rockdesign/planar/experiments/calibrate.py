"""Back-calculation of p, λ and c_r from a free-vibration test (thesis Sec 6.3.5, 6.4.3).

* p per half-cycle by inverting Eq 2.8, T_R = (4/p) acosh(1/(1 − θ0/α)), with T_R = 2 × the
  half-cycle duration and θ0 from a polynomial fit of the peak tilts against time (the thesis's
  regression; fitted separately to the peaks on each side so a left/right asymmetry is kept);
  p is the mean over the half-cycles.
* λ from p by solving the system's own frequency parameter (Eq 3.13 for a column, Eq 3.76 for a
  frame) for λ (scipy ``brentq``).
* c_r per impact = E_p,i+1/E_p,i (Eq 6.19) with the peak potential energy of Eq 2.10,
  E_p ∝ cos(α − θ0) − cos α; impacts are grouped by the side of the half-cycle they end
  (``c_r_right``: θ > 0 before the impact, ``c_r_left``: θ < 0). The velocity ratio at the impacts
  ((θ̇⁺/θ̇⁻)², Eq 3.14's definition) is not used: slopes read at the impacts from noisy samples
  scatter by several per cent, far more than the energy ratio of fitted peaks.
* The theoretical CoAM value (Eq 3.14/3.80/3.39/4.20 of the project's system) for comparison.

Eq 2.8 and Eq 2.10 describe a flat-based body; with curved extensions the back-calculated values
are an approximation (a warning says so).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import brentq

from ..design.geometry import rocking_geometry
from ..design.quantities import coefficient_of_restitution, system_frequency_parameter
from ..system import RockingSystem
from ...experiments.free_vibration import ExperimentError, HalfCycle, Impact, TiltHistory, find_half_cycles


@dataclass
class Calibration:
    """The result of a free-vibration calibration (SI: p [rad/s], angles [rad], times [s])."""

    p: float
    p_sd: float
    lam: float
    c_r: float
    c_r_left: float | None
    c_r_right: float | None
    c_r_theory: float
    c_r_theory_equation: str
    p_theory: float
    alpha: float
    offset: float
    offset_source: str
    noise: float
    half_cycles: list[HalfCycle]
    theta0_fit: np.ndarray
    p_per_half_cycle: np.ndarray
    c_r_per_impact: np.ndarray
    impacts: list[Impact]
    warnings: list[str] = field(default_factory=list)

    def as_json(self) -> dict:
        """CONTRACT JSON: p, lambda, c_r (all/left/right), c_r_theory, half_cycles, alpha (+ details)."""
        rows = []
        for k, hc in enumerate(self.half_cycles):
            rows.append({"start": hc.start, "end": hc.end, "duration": hc.duration, "side": hc.side,
                         "theta0": hc.theta0, "theta0_fit": float(self.theta0_fit[k]),
                         "p": float(self.p_per_half_cycle[k]),
                         "c_r_next_impact": (float(self.c_r_per_impact[k])
                                             if k < self.c_r_per_impact.size else None)})
        return {"p": self.p, "lambda": self.lam, "c_r": self.c_r, "c_r_left": self.c_r_left,
                "c_r_right": self.c_r_right, "c_r_theory": self.c_r_theory, "half_cycles": rows,
                "alpha": self.alpha, "p_sd": self.p_sd, "p_theory": self.p_theory,
                "c_r_theory_equation": self.c_r_theory_equation,
                "energy_loss_per_impact": 1.0 - self.c_r, "energy_loss_per_impact_theory": 1.0 - self.c_r_theory,
                "offset": self.offset, "offset_source": self.offset_source, "noise": self.noise,
                "warnings": list(self.warnings)}


def frequency_parameter_from_period(half_period: float, theta0: float, alpha: float) -> float:
    """p [rad/s] from Eq 2.8 inverted: p = (4/T_R) acosh(1/(1 − θ0/α)), T_R = 2 × half-period [s]."""
    if not 0.0 < theta0 < alpha:
        raise ValueError("Eq 2.8 needs 0 < θ0 < α")
    return 4.0 / (2.0 * half_period) * math.acosh(1.0 / (1.0 - theta0 / alpha))


def peak_potential_energy(theta0, alpha: float):
    """E_p/(W R) = cos(α − θ0) − cos α [-] at a peak tilt θ0 [rad] (Eq 2.10)."""
    return np.cos(alpha - np.asarray(theta0)) - math.cos(alpha)


def with_mass_distribution(system: RockingSystem, lam: float) -> RockingSystem:
    """The system with the columns' λ = I_C/(m_C R²) replaced."""
    return replace(system, column=replace(system.column, mass_distribution=float(lam)))


def mass_distribution_from_p(system: RockingSystem, p: float) -> float:
    """λ [-] such that the system's frequency parameter (Eq 3.13 / 3.76) equals ``p`` [rad/s]."""
    def f(lam):
        return system_frequency_parameter(with_mass_distribution(system, lam))[0] - p
    lo, hi = -0.95, 1e3
    if f(lo) * f(hi) > 0:
        p_lo, p_hi = f(hi) + p, f(lo) + p
        raise ExperimentError("the measured frequency parameter does not fit the geometry", key="p",
                              expected=f"p between {p_lo:.4g} and {p_hi:.4g} 1/s", found=f"{p:.4g} 1/s")
    return float(brentq(f, lo, hi, xtol=1e-12))


def theoretical_restitution(system: RockingSystem) -> tuple[float, str]:
    """(c_r, equation) of CoAM for ``system`` even if the project sets a measured value."""
    rule = system.restitution_rule if system.restitution_rule != "measured" else "theory"
    return coefficient_of_restitution(replace(system, restitution=None, restitution_rule=rule))


def _side_polynomial(half_cycles: list[HalfCycle]) -> np.ndarray:
    """θ0 per half-cycle from polynomial regressions θ0(t), one per side (thesis Sec 6.3.5)."""
    fit = np.array([hc.theta0 for hc in half_cycles], dtype=float)
    for side in (1, -1):
        idx = [k for k, hc in enumerate(half_cycles) if hc.side == side]
        if len(idx) < 3:
            continue
        t = np.array([half_cycles[k].peak_time for k in idx])
        y = fit[idx]
        deg = min(3, len(idx) - 2)
        fit[idx] = np.polynomial.Polynomial.fit(t, y, deg)(t)
    return fit


def calibrate(system: RockingSystem, history: TiltHistory, *, max_half_cycles: int | None = 20,
              min_amplitude: float = 0.05) -> Calibration:
    """p, λ, c_r (all, left, right) of ``system`` from the measured free-rocking ``history``.

    Args:
        system: the project's system (geometry and g; its λ and c_r are what is calibrated).
        history: the measurement.
        max_half_cycles: use at most this many half-cycles from the first impact (thesis: ~15–20).
        min_amplitude: ignore half-cycles with θ0 below this fraction of α.
    """
    if not (math.isfinite(min_amplitude) and 0.0 <= min_amplitude < 1.0):
        raise ExperimentError("out of range", key="min_amplitude", expected="a fraction of α, 0 ≤ value < 1 "
                              "(e.g. 0.05)", found=repr(min_amplitude))
    geo = rocking_geometry(system.column)
    alpha = geo.alpha
    warnings = []
    if system.column.extension == "curved":
        warnings.append("Eq 2.8 and Eq 2.10 assume a flat base: with curved extensions p and c_r are approximate")
    if system.has_elastic_superstructure:
        warnings.append("the elastic superstructure is ignored (rigid-body Eq 2.8)")
    p = system_frequency_parameter(system)[0]
    seg = find_half_cycles(history, alpha, p, min_amplitude=min_amplitude, max_half_cycles=max_half_cycles)
    impacts, half_cycles = seg.impacts, seg.half_cycles
    theta0_fit = _side_polynomial(half_cycles)
    p_each = np.array([frequency_parameter_from_period(hc.duration, min(th, alpha * (1 - 1e-9)), alpha)
                       for hc, th in zip(half_cycles, theta0_fit)])
    p = float(np.mean(p_each))
    energy = peak_potential_energy([hc.theta0 for hc in half_cycles], alpha)
    c_each = energy[1:] / energy[:-1]
    sides = np.array([hc.side for hc in half_cycles[:-1]])
    c_right = float(np.mean(c_each[sides > 0])) if np.any(sides > 0) else None
    c_left = float(np.mean(c_each[sides < 0])) if np.any(sides < 0) else None
    lam = mass_distribution_from_p(system, p)
    if lam < 0.0:
        warnings.append(f"λ = {lam:.3g} < 0 is not physical: check the geometry (R, α) or the record")
    c_th, eq = theoretical_restitution(system)
    return Calibration(p=p, p_sd=float(np.std(p_each, ddof=1)) if p_each.size > 1 else 0.0, lam=lam,
                       c_r=float(np.mean(c_each)), c_r_left=c_left, c_r_right=c_right,
                       c_r_theory=c_th, c_r_theory_equation=eq, p_theory=system_frequency_parameter(system)[0],
                       alpha=alpha, offset=seg.offset, offset_source=seg.offset_source, noise=seg.noise,
                       half_cycles=half_cycles, theta0_fit=theta0_fit,
                       p_per_half_cycle=p_each, c_r_per_impact=c_each, impacts=impacts, warnings=warnings)


def simulated_history(system: RockingSystem, cal: Calibration, history: TiltHistory, model: str = "auto"):
    """(t [s], θ [rad]) of the engine with the calibrated λ and c_r, released at rest from the first
    measured half-cycle's peak, on the measurement's time axis (thesis Figs 6.12, 6.24)."""
    from ..dynamics.simulate import simulate
    calibrated = with_mass_distribution(system, cal.lam).with_restitution(min(1.0, cal.c_r))
    first = cal.half_cycles[0]
    t_end = float(history.t[-1] - first.peak_time)
    r = simulate(calibrated, None, model=model, theta0=first.side * first.theta0, t_end=t_end,
                 output_dt=history.dt)
    return first.peak_time + r.t, r.theta
