"""GroundMotion: one horizontal ground acceleration history, as the engine consumes it (SI)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .excitation import (CYCLOIDAL_C1_PHASE, EXC_CYCLOIDAL_A, EXC_CYCLOIDAL_B, EXC_CYCLOIDAL_C,
                         EXC_NONE, EXC_RICKER_ANTI, EXC_RICKER_SYM, EXC_SAMPLES, EXC_SINE,
                         excitation_end, ground_acceleration_array)

PULSE_KINDS = {
    "ricker-sym": EXC_RICKER_SYM,
    "ricker-anti": EXC_RICKER_ANTI,
    "sine": EXC_SINE,
    "cycloidal-a": EXC_CYCLOIDAL_A,
    "cycloidal-b": EXC_CYCLOIDAL_B,
    "cycloidal-c": EXC_CYCLOIDAL_C,
}
_EMPTY = np.zeros(0)


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """A ground acceleration ü_g(t) [m/s²] ready for the dynamics engine.

    Attributes:
        name: identifier shown in reports (record id, pulse description).
        kind: excitation code of :mod:`rockdesign.motions.excitation`.
        params: float64 parameter array of that kind.
        samples: float64 accelerations [m/s²] for records (unscaled; ``params[0]`` is the scale).
        meta: free-form metadata (event, station, RSN, component, source, units as read...).
    """

    name: str
    kind: int
    params: np.ndarray
    samples: np.ndarray = field(default_factory=lambda: _EMPTY)
    meta: dict = field(default_factory=dict)

    @property
    def duration(self) -> float:
        """Time [s] after which the excitation is zero."""
        return float(excitation_end(self.kind, self.params, self.samples))

    @property
    def is_record(self) -> bool:
        return self.kind == EXC_SAMPLES

    @property
    def dt(self) -> float:
        """Sample spacing [s] of a record (0 for analytic pulses)."""
        return float(self.params[1]) if self.kind == EXC_SAMPLES else 0.0

    @property
    def scale(self) -> float:
        return float(self.params[0]) if self.kind == EXC_SAMPLES else 1.0

    def scaled(self, factor: float) -> "GroundMotion":
        """The same motion with amplitudes multiplied by ``factor`` (no copy of the samples)."""
        params = self.params.copy()
        params[0] *= factor
        return GroundMotion(self.name, self.kind, params, self.samples, dict(self.meta, scale=float(
            params[0]) if self.kind == EXC_SAMPLES else self.meta.get("scale", 1.0) * factor))

    def acceleration(self, t) -> np.ndarray:
        """ü_g at times t [s] (m/s²), exactly as the engine sees it."""
        return ground_acceleration_array(np.atleast_1d(np.asarray(t, dtype=float)), self.kind,
                                         self.params, self.samples)

    @property
    def pga(self) -> float:
        """Peak |ü_g| [m/s²] (of the samples, or of the analytic pulse = a_p)."""
        if self.kind == EXC_SAMPLES:
            return float(abs(self.params[0]) * np.max(np.abs(self.samples))) if self.samples.size else 0.0
        if self.kind == EXC_NONE:
            return 0.0
        return abs(float(self.params[0]))

    def sampled(self, dt: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(t, ü_g) on a uniform grid: the record's own samples, or the pulse sampled at ``dt``."""
        if self.kind == EXC_SAMPLES:
            t = np.arange(self.samples.size) * self.dt
            return t, self.params[0] * self.samples
        end = self.duration
        if dt is None:
            dt = self.params[1] / 200.0 if self.kind != EXC_NONE else 0.01
        t = np.arange(0.0, end + dt / 2, dt)
        return t, self.acceleration(t)


def record_motion(name: str, samples_si: np.ndarray, dt: float, scale: float = 1.0,
                  meta: dict | None = None) -> GroundMotion:
    """A record (accelerations in m/s² at spacing dt [s], starting at t = 0)."""
    samples = np.ascontiguousarray(samples_si, dtype=np.float64)
    return GroundMotion(name, EXC_SAMPLES, np.array([float(scale), float(dt)]), samples,
                        dict(meta or {}, dt=float(dt), npts=int(samples.size), scale=float(scale)))


def pulse_motion(pulse: str, a_p: float, T_p: float, t_m: float | None = None,
                 t_0: float = 0.0, n_cycles: int = 1) -> GroundMotion:
    """An analytic pulse (SPEC §4).

    Args:
        pulse: ``ricker-sym`` | ``ricker-anti`` | ``sine`` | ``cycloidal-a`` | ``cycloidal-b`` |
            ``cycloidal-c``.
        a_p: amplitude [m/s²] (peak |ü_g|; for Eq 2.20 the sine amplitude).
        T_p: pulse period [s] (= 2π/ω_p).
        t_m: centre of a Ricker wavelet [s]; default 1.5 T_p (inferred from Table 3.4).
        t_0: start time of a sine or cycloidal pulse [s].
        n_cycles: n of Makris' type-C_n pulse (only C1 has its phase tabulated here).
    """
    if pulse not in PULSE_KINDS:
        raise KeyError(pulse)
    kind = PULSE_KINDS[pulse]
    if kind in (EXC_RICKER_SYM, EXC_RICKER_ANTI):
        tm = 1.5 * T_p if t_m is None else t_m
        params = np.array([a_p, T_p, tm])
        meta = {"a_p": a_p, "T_p": T_p, "t_m": tm}
    elif kind == EXC_SINE:
        params = np.array([a_p, T_p, t_0])
        meta = {"a_p": a_p, "T_p": T_p, "t_0": t_0}
    else:
        if kind == EXC_CYCLOIDAL_A:
            phi, span = 0.0, T_p
        elif kind == EXC_CYCLOIDAL_B:
            phi, span = 0.0, T_p
        else:
            phi = cycloidal_c_phase(n_cycles)
            span = (n_cycles + 0.5 - phi / math.pi) * T_p
        params = np.array([a_p, T_p, t_0, phi, span])
        meta = {"a_p": a_p, "T_p": T_p, "t_0": t_0, "phi": phi, "n": n_cycles}
    return GroundMotion(f"{pulse}(a_p={a_p:.6g} m/s2, T_p={T_p:.6g} s)", kind, params, _EMPTY,
                        dict(meta, pulse=pulse))


def cycloidal_c_phase(n: int) -> float:
    """Phase φ [rad] of Makris' type-C_n pulse: 2 cos φ = sin φ ((2n+1)π − 2φ) (zero final displacement)."""
    from scipy.optimize import brentq
    return float(brentq(lambda p: 2 * math.cos(p) - math.sin(p) * ((2 * n + 1) * math.pi - 2 * p), 1e-9, 1.5))


def no_motion() -> GroundMotion:
    """Zero ground acceleration (free vibration)."""
    return GroundMotion("free vibration", EXC_NONE, np.zeros(0), _EMPTY, {})

