"""A record for a small-scale specimen on a shake table (thesis Sec 6.1.3, 6.2.2).

* Time scaling by similitude (Eq 6.5): Δt_m = Δt_p √(R_m/R_p); accelerations unchanged (same g).
* Baseline correction (mean removed, 5 % Tukey taper) and a zero-phase Butterworth band-pass
  (scipy.signal ``butter`` as second-order sections, ``sosfiltfilt``); the default corners are the
  usual prototype corners 0.1 Hz and 25 Hz moved by the time scale (f_m = f_p/√(R_m/R_p)), the
  upper one kept below 0.8 × Nyquist.
* Velocity and displacement by the trapezoidal rule (scipy.integrate ``cumulative_trapezoid``); a
  polynomial displacement baseline (degree 2–6, v = d = 0 imposed at the end) is removed so the
  table ends at rest at its origin (the acceleration is corrected consistently, by p'').
* Peaks against the table's limits (thesis Fig 6.2b: stroke 250 mm, velocity 220 mm/s).
* The scaled, corrected record written as a PEER AT2 file (units of g) that
  :func:`rockdesign.motions.records.read_record_file` reads back.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import signal
from scipy.integrate import cumulative_trapezoid

from ..errors import MotionError
from ..units import QuantityParseError, parse_quantity

PROTOTYPE_CORNERS = (0.1, 25.0)
"""Band-pass corners [Hz] at prototype time scale (moved by Eq 6.5 for the model)."""
FILTER_ORDER = 4
LIMIT_DIMENSIONS = {"d": ("length", "m"), "v": ("velocity", "m/s"), "a": ("acceleration", "m/s²")}


@dataclass
class ScaledRecord:
    """A record prepared for the table (SI, model time): t [s], acceleration [m/s²] (corrected),
    velocity [m/s], displacement [m]; ``time_factor`` = √(R_m/R_p); ``corners`` [Hz]."""

    name: str
    dt: float
    time_factor: float
    corners: tuple[float, float]
    acceleration: np.ndarray
    velocity: np.ndarray
    displacement: np.ndarray
    raw_pga: float
    limits: dict = field(default_factory=dict)

    @property
    def t(self) -> np.ndarray:
        return np.arange(self.acceleration.size) * self.dt

    @property
    def duration(self) -> float:
        """(npts − 1)·Δt_m [s]."""
        return (self.acceleration.size - 1) * self.dt

    @property
    def peaks(self) -> dict:
        """Peak |a| [m/s²], |v| [m/s], |d| [m] after correction."""
        return {"a": float(np.max(np.abs(self.acceleration))), "v": float(np.max(np.abs(self.velocity))),
                "d": float(np.max(np.abs(self.displacement)))}

    @property
    def exceeded(self) -> list[str]:
        """The quantities whose peak exceeds the table's limit."""
        peaks = self.peaks
        return [k for k, limit in self.limits.items() if limit is not None and peaks[k] > limit]

    def as_json(self) -> dict:
        return {"id": self.name, "dt": self.dt, "time_factor": self.time_factor, "duration": self.duration,
                "corners": list(self.corners), "filter_order": FILTER_ORDER, "pga_raw": self.raw_pga,
                "peaks": self.peaks, "limits": self.limits, "exceeded": self.exceeded}


def time_scaled_dt(dt_prototype: float, length_ratio: float) -> float:
    """Δt_m = Δt_p √(R_m/R_p) [s] (Eq 6.5)."""
    if not (length_ratio > 0.0 and math.isfinite(length_ratio)):
        raise MotionError("invalid length ratio", key="length_ratio", expected="R_m/R_p > 0 (e.g. 0.025)",
                          found=repr(length_ratio))
    return dt_prototype * math.sqrt(length_ratio)


def parse_limits(text: str | None, gravity: float) -> dict:
    """``d=0.125m,v=0.22m/s,a=1.5g`` → {"d": m, "v": m/s, "a": m/s²} (keys optional)."""
    limits: dict = {}
    if not text:
        return limits
    for part in text.split(","):
        key, sep, value = part.partition("=")
        key = key.strip().lower()
        if not sep or key not in LIMIT_DIMENSIONS:
            raise MotionError("invalid table limit", key="table", expected="d=<length>,v=<velocity>,a=<acceleration>",
                              found=repr(part.strip()))
        if key in limits:
            raise MotionError("table limit given twice (only one value would be used)", key=f"table.{key}",
                              expected=f"{key}=… once", found=repr(text))
        try:
            limits[key] = parse_quantity(value.strip(), LIMIT_DIMENSIONS[key][0], gravity=gravity)
        except QuantityParseError as exc:
            raise MotionError("invalid table limit", key=f"table.{key}", expected=str(exc),
                              found=repr(value.strip())) from None
        if limits[key] <= 0.0:
            raise MotionError("invalid table limit", key=f"table.{key}", expected="a positive limit",
                              found=repr(value.strip()))
    return limits


def default_corners(time_factor: float, dt_model: float) -> tuple[float, float]:
    """Prototype corners 0.1/25 Hz moved to model time (÷ √(R_m/R_p)), the upper ≤ 0.8 Nyquist [Hz]."""
    low = PROTOTYPE_CORNERS[0] / time_factor
    high = min(PROTOTYPE_CORNERS[1] / time_factor, 0.8 * 0.5 / dt_model)
    return low, high


def band_pass(accel: np.ndarray, dt: float, corners: tuple[float, float], order: int = FILTER_ORDER) -> np.ndarray:
    """Baseline-corrected (mean removed, 5 % Tukey taper), zero-phase Butterworth band-pass [m/s²]."""
    low, high = corners
    nyquist = 0.5 / dt
    if not 0.0 < low < high < nyquist:
        raise MotionError("invalid filter corners", key="band", expected=f"0 < low < high < Nyquist = {nyquist:.4g} Hz",
                          found=f"{low:g}:{high:g} Hz")
    a = np.asarray(accel, dtype=float)
    a = (a - a.mean()) * signal.windows.tukey(a.size, 0.05)
    sos = signal.butter(order, [low, high], btype="bandpass", fs=1.0 / dt, output="sos")
    pad = int(min(10 * a.size, math.ceil(1.5 * order / low / dt)))   # Boore (2005) transient length
    padded = np.concatenate([np.zeros(pad), a, np.zeros(pad)])
    return signal.sosfiltfilt(sos, padded)[pad:pad + a.size]


def end_at_rest(accel: np.ndarray, dt: float, degree: int = 6) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(a, v, d) with a polynomial baseline p(t) = Σ_{k=2..degree} c_k t^k removed from the displacement so
    that the table starts and ends at rest at its origin: least squares of d − p with v(T) = d(T) = 0
    imposed; a − p'' and v − p' stay consistent with d − p. Integration: ``cumulative_trapezoid``."""
    t = np.arange(accel.size) * dt
    v = cumulative_trapezoid(accel, dx=dt, initial=0.0)
    d = cumulative_trapezoid(v, dx=dt, initial=0.0)
    if accel.size < 3 * degree:
        return accel, v, d
    T = t[-1]
    tau = t / T
    powers = np.arange(2, degree + 1)
    basis = tau[:, None] ** powers                       # d-basis, in units of T^k
    weight = 1e3 * math.sqrt(accel.size)
    rows = np.vstack([basis, weight * np.ones(powers.size), weight * powers / T])
    rhs = np.concatenate([d, [weight * d[-1], weight * v[-1]]])
    coef, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
    p = basis @ coef
    dp = (tau[:, None] ** (powers - 1) * powers) @ coef / T
    ddp = (tau[:, None] ** (powers - 2) * powers * (powers - 1)) @ coef / T ** 2
    return accel - ddp, v - dp, d - p


def scale_record(motion, length_ratio: float, *, corners: tuple[float, float] | None = None,
                 limits: dict | None = None) -> ScaledRecord:
    """The record ``motion`` prepared for a model of length ratio R_m/R_p (Eq 6.5), corrected and integrated."""
    t_p, accel = motion.sampled()
    dt_m = time_scaled_dt(motion.dt, length_ratio)
    factor = math.sqrt(length_ratio)
    corners = corners or default_corners(factor, dt_m)
    corrected, velocity, displacement = end_at_rest(band_pass(accel, dt_m, corners), dt_m)
    return ScaledRecord(motion.name, dt_m, factor, tuple(float(c) for c in corners), corrected, velocity,
                        displacement, float(np.max(np.abs(accel))), dict(limits or {}))


def write_at2(record: ScaledRecord, path, gravity: float = 9.81, meta: dict | None = None) -> Path:
    """Write the corrected, scaled acceleration as a PEER AT2 file in units of g."""
    meta = meta or {}
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    values = record.acceleration / gravity
    when = meta.get("date") or meta.get("year")
    fields = [meta.get("event") or record.name] + ([str(when)] if when else []) + \
        [meta.get("station") or "", meta.get("component") or ""]
    station = ", ".join(str(f) for f in fields)
    lines = [f"PEER NGA STRONG MOTION DATABASE RECORD (rockdesign scale-model of {record.name}: "
             f"dt x {record.time_factor:.6g}, band-pass {record.corners[0]:.4g}-{record.corners[1]:.4g} Hz)",
             station,
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {values.size:7d}, DT= {record.dt:.8E} SEC"]
    for start in range(0, values.size, 5):
        lines.append("".join(f"{v:16.7E}" for v in values[start:start + 5]))
    path.write_text("\n".join(lines) + "\n", encoding="ascii")
    return path
