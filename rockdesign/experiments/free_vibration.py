"""A measured free-rocking tilt history: reading the CSV, finding the impacts and the half-cycles.

A free-vibration test (thesis Sec 6.3.5, 6.4.3) records θ(t) of a specimen released from a tilt.
Between two impacts the body rocks on one corner (a half-cycle of duration T_R/2, Eq 2.8) and
reaches a peak tilt θ0; at an impact θ passes through zero with a kink (θ̇ drops by √c_r).

The measured signal carries noise, a constant offset (the sensor's zero is not the upright
position) and perhaps missing samples. The impacts are located by fitting, around each coarse zero
crossing, a curve with a kink — a cubic polynomial on each side joined at the impact time t_i at a
common level c_i — by linear least squares for each t_i and a scalar minimisation over t_i
(numpy ``lstsq``, scipy ``minimize_scalar``). The median of the levels c_i is the offset. Peak tilts
are the maxima of quartic fits around each extreme. Written here because no library fits a kinked
trajectory; the fits themselves are numpy/scipy.

Units: t [s], θ [rad] throughout.
"""
from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.signal import savgol_filter

from ..errors import RockdesignError


class ExperimentError(RockdesignError):
    """Unusable experimental data (a measured history, a results table)."""


_TIME_UNITS = {"s": 1.0, "sec": 1.0, "ms": 1e-3}
_ANGLE_UNITS = {"rad": 1.0, "mrad": 1e-3, "deg": math.pi / 180.0, "°": math.pi / 180.0}
_COLUMN = re.compile(r"^(?P<name>[a-zθ]+)\s*(?:[_ ]\s*(?P<u1>[a-z°]+)|[\[(]\s*(?P<u2>[^\])]+?)\s*[\])])?$")
TIME_NAMES = ("t", "time")
ANGLE_NAMES = ("theta", "θ", "tilt")


@dataclass(frozen=True)
class TiltHistory:
    """A measured tilt history: ``t`` [s] (increasing), ``theta`` [rad] as measured (offset included)."""

    t: np.ndarray
    theta: np.ndarray
    source: str
    dropped_rows: int = 0

    @property
    def dt(self) -> float:
        """Median sample spacing [s]."""
        return float(np.median(np.diff(self.t)))


@dataclass(frozen=True)
class Impact:
    """An impact found in the measurement: time [s], level [rad] of the kink (θ = 0 of the body in
    sensor coordinates), rates before/after [rad/s] and the side (+1/−1) of θ before the impact."""

    time: float
    level: float
    rate_before: float
    rate_after: float
    side: int


@dataclass(frozen=True)
class HalfCycle:
    """Rocking on one corner between two impacts: start/end [s], peak time [s], peak tilt θ0 [rad]
    (magnitude, offset removed) and the side (+1: θ > 0, −1: θ < 0)."""

    start: float
    end: float
    peak_time: float
    theta0: float
    side: int

    @property
    def duration(self) -> float:
        """T_R/2 [s]."""
        return self.end - self.start


def _parse_column(header: str) -> tuple[str, str | None]:
    m = _COLUMN.match(header.strip().lower())
    if not m:
        return header.strip().lower(), None
    return m.group("name"), m.group("u1") or m.group("u2")


def read_tilt_csv(path) -> TiltHistory:
    """Read a measured tilt history: columns ``t`` [s] and ``theta`` [rad] (or ``theta_deg``,
    ``theta [deg]``, ``t_ms``...). Rows with an empty or non-finite cell are dropped and counted.

    Raises:
        ExperimentError: missing file or column, unknown unit, too few rows, time not increasing.
    """
    path = Path(path)
    file = str(path)
    if not path.is_file():
        raise ExperimentError("measurement file not found", file=file, expected="a CSV file", found="no such file")
    lines = [ln for ln in path.read_text(errors="replace").splitlines()]
    first = next((i for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")), None)
    if first is None:
        raise ExperimentError("empty measurement file", file=file, expected="a header and samples", found="no rows")
    header_line = lines[first]
    delimiter = next((d for d in (",", ";", "\t") if d in header_line), None)
    rows = list(csv.reader(lines[first:], delimiter=delimiter) if delimiter else
                (ln.split() for ln in lines[first:]))
    header = [_parse_column(h) for h in rows[0]]
    t_col = next((i for i, (n, _) in enumerate(header) if n in TIME_NAMES), None)
    a_col = next((i for i, (n, _) in enumerate(header) if n in ANGLE_NAMES), None)
    if t_col is None or a_col is None:
        raise ExperimentError("missing column", file=file, line=first + 1,
                              expected="columns 't' [s] and 'theta' [rad] (or 'theta_deg')",
                              found=", ".join(rows[0]) or "an empty header")
    t_unit = header[t_col][1] or "s"
    a_unit = header[a_col][1] or "rad"
    if t_unit not in _TIME_UNITS:
        raise ExperimentError("unknown time unit", file=file, line=first + 1, key=rows[0][t_col],
                              expected=" | ".join(_TIME_UNITS), found=repr(t_unit))
    if a_unit not in _ANGLE_UNITS:
        raise ExperimentError("unknown angle unit", file=file, line=first + 1, key=rows[0][a_col],
                              expected=" | ".join(_ANGLE_UNITS), found=repr(a_unit))
    t, theta, lineno, dropped = [], [], [], 0
    for k, row in enumerate(rows[1:], start=first + 2):
        if not row or all(not c.strip() for c in row):
            continue
        try:
            tv, av = float(row[t_col]), float(row[a_col])
        except (ValueError, IndexError):
            tv = av = math.nan
        if not (math.isfinite(tv) and math.isfinite(av)):
            dropped += 1
            continue
        t.append(tv)
        theta.append(av)
        lineno.append(k)
    t_arr = np.asarray(t) * _TIME_UNITS[t_unit]
    if t_arr.size < 20:
        raise ExperimentError("too few samples", file=file, expected="a tilt history of at least 20 samples",
                              found=f"{t_arr.size} usable row(s)")
    steps = np.diff(t_arr)
    if np.any(steps <= 0.0):
        bad = int(np.argmax(steps <= 0.0)) + 1
        raise ExperimentError("time is not increasing", file=file, line=lineno[bad], key=rows[0][t_col],
                              expected="strictly increasing times",
                              found=f"t = {t[bad]:g} after t = {t[bad - 1]:g}")
    theta_arr = np.asarray(theta) * _ANGLE_UNITS[a_unit]
    beyond = np.abs(theta_arr) >= math.pi / 2
    if np.any(beyond):
        k = int(np.argmax(beyond))
        hint = " (the column may be in degrees: name it 'theta_deg' or 'theta [deg]')" if a_unit == "rad" else ""
        raise ExperimentError("tilt angle beyond π/2" + hint, file=file, line=lineno[k], key=rows[0][a_col],
                              expected="|θ| < π/2 rad = 90° (a rocking body lies flat at π/2)",
                              found=f"{theta[k]:g} {a_unit}")
    return TiltHistory(t_arr, theta_arr, file, dropped)


def noise_level(history: TiltHistory) -> float:
    """Robust noise standard deviation [rad]: MAD of second differences / √6 (white noise)."""
    d2 = np.diff(history.theta, 2)
    return float(1.4826 * np.median(np.abs(d2 - np.median(d2))) / math.sqrt(6.0))


def _uniform(history: TiltHistory) -> tuple[np.ndarray, np.ndarray]:
    dt = history.dt
    tg = np.arange(history.t[0], history.t[-1], dt)
    return tg, np.interp(tg, history.t, history.theta)


def _crossings(tg: np.ndarray, smooth: np.ndarray, level: float, hysteresis: float) -> list[tuple[float, int]]:
    """(time, side before) of the zero crossings of ``smooth − level`` with hysteresis: a crossing needs
    |·| > hysteresis on both sides."""
    s = smooth - level
    state = 0
    last_zero = None
    out = []
    for k in range(1, s.size):
        if (s[k - 1] > 0) != (s[k] > 0):
            last_zero = tg[k - 1] + (tg[k] - tg[k - 1]) * s[k - 1] / (s[k - 1] - s[k])
        if abs(s[k]) > hysteresis:
            sign = 1 if s[k] > 0 else -1
            if state and sign != state and last_zero is not None:
                out.append((float(last_zero), state))
            state = sign
    return out


def _impact_time(t: np.ndarray, y: np.ndarray, t_guess: float, half_window: float):
    """(t_i, rate before, rate after) where ``y`` (offset removed) crosses zero near ``t_guess``: the
    roots of quadratic fits on each side (numpy ``Polynomial.fit``), averaged; rates at t_i [rad/s]."""
    out = []
    for lo, hi in ((t_guess - half_window, t_guess), (t_guess, t_guess + half_window)):
        sel = (t >= lo) & (t <= hi)
        if sel.sum() < 4:
            return None
        poly = np.polynomial.Polynomial.fit(t[sel], y[sel], 2)
        roots = [r.real for r in poly.roots() if abs(r.imag) < 1e-12 and lo - half_window <= r.real <= hi + half_window]
        if not roots:
            return None
        out.append((min(roots, key=lambda r: abs(r - t_guess)), poly.deriv()))
    ti = 0.5 * (out[0][0] + out[1][0])
    return ti, float(out[0][1](ti)), float(out[1][1](ti))


def _arc_fit(t: np.ndarray, y: np.ndarray, segments, alpha: float, p: float, level: float, fixed_level: bool = False):
    """Least-squares fit of the linearized free-rocking arcs θ − c = s[α − (α − θ0,k) cosh(p(t − t_k))]
    (Eq 2.16 without excitation; each half-cycle k on side s, peak θ0,k at t_k) with one offset c and
    one p for all half-cycles (scipy ``least_squares``; c stays at ``level`` with ``fixed_level``).
    Returns (c, p, θ0 array, t_peak array)."""
    from scipy.optimize import least_squares
    idx, k_of, side_of = [], [], []
    for k, (a, b, side, t_pk, th0) in enumerate(segments):
        half = 0.5 * (b - a)
        sel = np.flatnonzero((t > a + 0.1 * half) & (t < b - 0.1 * half))
        idx.append(sel)
        k_of.append(np.full(sel.size, k))
        side_of.append(np.full(sel.size, side))
    idx, k_of, side_of = np.concatenate(idx), np.concatenate(k_of), np.concatenate(side_of).astype(float)
    tt, yy = t[idx], y[idx]
    n = len(segments)

    def residual(x):
        c, pp, th0, tpk = (level if fixed_level else x[0]), x[1], x[2:2 + n], x[2 + n:]
        return yy - c - side_of * (alpha - (alpha - th0[k_of]) * np.cosh(pp * (tt - tpk[k_of])))

    rows = np.arange(tt.size)

    def jacobian(x):
        pp, th0, tpk = x[1], x[2:2 + n], x[2 + n:]
        u = tt - tpk[k_of]
        amp = alpha - th0[k_of]
        sh = np.sinh(pp * u)
        jac = np.zeros((tt.size, x.size))
        jac[:, 0] = 0.0 if fixed_level else -1.0
        jac[:, 1] = side_of * amp * u * sh
        jac[rows, 2 + k_of] = -side_of * np.cosh(pp * u)
        jac[rows, 2 + n + k_of] = -side_of * amp * pp * sh
        return jac

    x0 = np.concatenate([[level, p], [seg[4] for seg in segments], [seg[3] for seg in segments]])
    lower = np.concatenate([[-np.inf, 0.2 * p], np.full(n, 1e-9), [seg[0] for seg in segments]])
    upper = np.concatenate([[np.inf, 5.0 * p], np.full(n, alpha * (1 - 1e-9)), [seg[1] for seg in segments]])
    x0 = np.clip(x0, lower + 1e-12, upper - 1e-12)
    fit = least_squares(residual, x0, jac=jacobian, bounds=(lower, upper), x_scale="jac", xtol=1e-12, ftol=1e-12)
    return (level if fixed_level else float(fit.x[0])), float(fit.x[1]), fit.x[2:2 + n], fit.x[2 + n:]


def _peak(t: np.ndarray, s: np.ndarray, side: int) -> tuple[float, float]:
    """(time, magnitude) of the extreme of side·s from a quartic fit over the top quarter."""
    v = side * s
    k = int(np.argmax(savgol_filter(v, min(v.size - (1 - v.size % 2), 11), 2) if v.size > 11 else v))
    top = v >= v[k] - 0.25 * abs(v[k])
    idx = np.flatnonzero(top)
    # the contiguous run around the maximum
    lo = hi = k
    while lo - 1 >= 0 and top[lo - 1]:
        lo -= 1
    while hi + 1 < v.size and top[hi + 1]:
        hi += 1
    if hi - lo < 6 or idx.size < 6:
        return float(t[k]), float(v[k])
    poly = np.polynomial.Polynomial.fit(t[lo:hi + 1], v[lo:hi + 1], 4)
    fine = np.linspace(t[lo], t[hi], 2001)
    values = poly(fine)
    j = int(np.argmax(values))
    return float(fine[j]), float(values[j])


REST_TAIL = 0.5
"""Minimum duration [s] of the still tail at the end of a record used as the zero of the tilt."""


def rest_level(history: TiltHistory, sigma: float) -> float | None:
    """Mean θ [rad] of the record's final still part (the specimen at rest) if it lasts at least
    ``REST_TAIL`` seconds, else None. "Still": the 20 ms running mean stays within 3 noise SDs."""
    tg, yg = _uniform(history)
    n = max(3, int(round(0.02 / history.dt)))
    if yg.size < 4 * n:
        return None
    mean = np.convolve(yg, np.ones(n) / n, mode="valid")
    end = float(np.median(mean[-n:]))
    moving = np.flatnonzero(np.abs(mean - end) > 3.0 * max(sigma, 1e-12))
    start = 0 if moving.size == 0 else int(moving[-1]) + n
    if tg[-1] - tg[min(start, tg.size - 1)] < REST_TAIL:
        return None
    return float(np.mean(history.theta[history.t >= tg[start]]))


@dataclass(frozen=True)
class Segmentation:
    """Impacts and half-cycles found in a measurement; ``offset`` [rad] is the body's θ = 0 in sensor
    coordinates, from the still tail (``offset_source = "rest"``) or the arc fit (``"arcs"``);
    ``noise`` [rad] the noise SD."""

    offset: float
    offset_source: str
    noise: float
    impacts: list
    half_cycles: list


def find_half_cycles(history: TiltHistory, alpha: float, p: float, *, min_amplitude: float = 0.05,
                     max_half_cycles: int | None = None) -> Segmentation:
    """Offset, noise, impacts and half-cycles of a measured free-rocking history.

    ``alpha`` [rad] and ``p`` [rad/s] (an estimate) shape the fit through each impact.

    Half-cycles (between consecutive impacts) are kept from the first impact on while their peak
    tilt exceeds ``min_amplitude``·α and ten noise SDs; at most ``max_half_cycles`` are returned.

    Raises:
        ExperimentError: no rocking (no impact) or fewer than two complete half-cycles.
    """
    sigma = noise_level(history)
    tg, yg = _uniform(history)
    dt = history.dt
    window = max(5, int(round(0.02 / dt)) | 1)
    smooth = savgol_filter(yg, window, 2) if yg.size > window else yg
    threshold = max(min_amplitude * alpha, 10.0 * sigma)
    t, theta = history.t, history.theta
    rest = rest_level(history, sigma)
    level = 0.0 if rest is None else rest
    for _ in range(1 if rest is not None else 2):   # segment, fit the arcs for the offset, segment again
        coarse = _crossings(tg, smooth, level, max(4.0 * sigma, 0.5 * threshold))
        if not coarse:
            raise ExperimentError("no rocking found in the measurement", file=history.source,
                                  expected="a free-rocking tilt history with impacts (θ passing through zero)",
                                  found=f"no zero crossing above the noise ({sigma:.2g} rad)")
        segments = []
        for (a, side_a), (b, _) in zip(coarse[:-1], coarse[1:]):
            sel = (t > a) & (t < b)
            if sel.sum() < 8:
                break
            side = -side_a
            t_pk, th0 = _peak(t[sel], theta[sel] - level, side)
            if th0 < threshold or th0 >= alpha:
                break
            segments.append((a, b, side, t_pk, th0))
            if max_half_cycles is not None and len(segments) >= max_half_cycles:
                break
        if len(segments) < 2:
            break
        level, p, _, _ = _arc_fit(t, theta, segments, alpha, p, level, fixed_level=rest is not None)
    impacts: list[Impact] = []
    for k, (tc, side) in enumerate(coarse[:len(segments) + 1]):
        before = tc - (coarse[k - 1][0] if k else t[0])
        after = (coarse[k + 1][0] if k + 1 < len(coarse) else t[-1]) - tc
        found = _impact_time(t, theta - level, tc, max(6 * dt, 0.15 * min(before, after)))
        if found is None:
            break
        impacts.append(Impact(found[0], level, found[1], found[2], side))
    half_cycles: list[HalfCycle] = []
    for a, b in zip(impacts[:-1], impacts[1:]):
        sel = (t > a.time) & (t < b.time)
        side = -a.side
        t_peak, theta0 = _peak(t[sel], theta[sel] - level, side)
        if theta0 < threshold or theta0 >= alpha:
            break
        half_cycles.append(HalfCycle(a.time, b.time, t_peak, theta0, side))
    if len(half_cycles) >= 2:   # peak tilts from the arcs (all samples of each half-cycle, common offset)
        segments = [(hc.start, hc.end, hc.side, hc.peak_time, hc.theta0) for hc in half_cycles]
        _, _, theta0s, t_peaks = _arc_fit(t, theta, segments, alpha, p, level, fixed_level=True)
        half_cycles = [HalfCycle(hc.start, hc.end, float(tp), float(th), hc.side)
                       for hc, th, tp in zip(half_cycles, theta0s, t_peaks)]
    if len(half_cycles) < 2:
        raise ExperimentError("too few rocking half-cycles in the measurement", file=history.source,
                              expected="at least 2 complete half-cycles (3 impacts) above "
                                       f"{threshold:.3g} rad", found=f"{len(half_cycles)}")
    return Segmentation(level, "arcs" if rest is None else "rest", sigma, impacts[:len(half_cycles) + 1],
                        half_cycles)
