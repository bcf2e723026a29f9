"""Target spectra for ASCE 7-22 §16.2 record scaling: the MCE_R spectrum, two-period or tabulated (SPEC §16).

* :class:`MCERSpectrum`: the two-period MCE_R response spectrum from S_MS, S_M1 and T_L — the shape of
  ASCE 7-22 §11.4.5.2 (Fig 11.4-1) at the MCE_R level (§11.4.6: 1.5 × the design spectrum, i.e.
  S_MS = 1.5 S_DS, S_M1 = 1.5 S_D1):

      T < T0:        Sa = S_MS (0.4 + 0.6 T/T0),   T0 = 0.2 S_M1/S_MS
      T0 ≤ T ≤ TS:   Sa = S_MS,                     TS = S_M1/S_MS
      TS < T ≤ TL:   Sa = S_M1/T
      T > TL:        Sa = S_M1 T_L/T²

* :class:`TabulatedSpectrum`: a site-specific or multi-period MCE_R spectrum (ASCE 7-22 §11.4.5.1,
  Chapter 21) given as a table of (period, spectral acceleration), interpolated linearly in
  log(T)–log(Sa) between its rows and never extrapolated.  :func:`read_target_spectrum` reads it from a
  two-column file whose header names the units: ``period [s], Sa [g]``.

All values are SI: periods in s, pseudo-accelerations in m/s², 5 % damping.  EN 1998-1 and ASCE 7-16
design spectra stay in :mod:`rockdesign.motions.design_spectra`.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ProjectError
from ..units import QuantityParseError, parse_quantity


@dataclass(frozen=True)
class MCERSpectrum:
    """ASCE 7-22 two-period MCE_R response spectrum (5 % damping; §11.4.5.2 shape, §11.4.6 level).

    Attributes:
        SMS: MCE_R short-period spectral acceleration S_MS [m/s²].
        SM1: MCE_R 1-s spectral acceleration S_M1 [m/s²·s] (given like an acceleration, "0.30 g").
        TL: long-period transition period T_L [s].
        TL_default: T_L was not given (the default was used); reports say so.
    """

    SMS: float
    SM1: float
    TL: float = 8.0
    TL_default: bool = False

    @property
    def T0(self) -> float:
        """T0 = 0.2 S_M1/S_MS [s]."""
        return 0.2 * self.SM1 / self.SMS

    @property
    def TS(self) -> float:
        """TS = S_M1/S_MS [s]."""
        return self.SM1 / self.SMS

    @property
    def corner_periods(self) -> tuple[float, ...]:
        """The periods [s] where the shape changes branch (T0, TS, TL)."""
        return (self.T0, self.TS, self.TL)

    def psa(self, periods) -> np.ndarray:
        """Sa(T) [m/s²] at periods T [s] (module docstring; ASCE 7-22 §11.4.5.2 shape at MCE_R level)."""
        T = np.asarray(periods, dtype=float)
        T_safe = np.maximum(T, 1e-12)
        long_period = np.where(T <= self.TL, self.SM1 / T_safe, self.SM1 * self.TL / T_safe ** 2)
        return np.where(T < self.T0, self.SMS * (0.4 + 0.6 * T / self.T0),
                        np.where(T <= self.TS, self.SMS, long_period))

    def covers(self, lo: float, hi: float) -> bool:
        """Defined over every period [s] (the closed form has no end)."""
        return True

    def describe(self, gravity: float = 9.81) -> str:
        """One line naming the spectrum and its parameters (for reports)."""
        tl = f"T_L = {self.TL:g} s" + (" (default; give TL for the site)" if self.TL_default else "")
        return (f"ASCE 7-22 two-period MCE_R spectrum (S_MS = {self.SMS / gravity:.4g} g, "
                f"S_M1 = {self.SM1 / gravity:.4g} g, T0 = {self.T0:.3g} s, TS = {self.TS:.3g} s, {tl}, 5 % damping)")


@dataclass(frozen=True, eq=False)
class TabulatedSpectrum:
    """A target spectrum given as a table (5 % damping), log-log interpolated between its rows.

    Attributes:
        periods: increasing periods [s] of the rows (a first row at T = 0, the PGA, is kept but not
            used by the log-log interpolation, which starts at the first positive period).
        values: spectral accelerations [m/s²] of the rows (> 0).
        source: where the table came from (the file), for reports.
    """

    periods: np.ndarray
    values: np.ndarray
    source: str = "table"

    @property
    def _positive(self) -> tuple[np.ndarray, np.ndarray]:
        keep = self.periods > 0.0
        return self.periods[keep], self.values[keep]

    @property
    def corner_periods(self) -> tuple[float, ...]:
        """The rows' positive periods [s] (where the interpolated shape may change slope)."""
        return tuple(float(t) for t in self._positive[0])

    def covers(self, lo: float, hi: float) -> bool:
        """Whether the rows with T > 0 span the periods [lo, hi] [s] (no extrapolation)."""
        T, _ = self._positive
        return bool(T.size >= 2 and T[0] <= lo * (1 + 1e-12) and hi <= T[-1] * (1 + 1e-12))

    def psa(self, periods) -> np.ndarray:
        """Sa(T) [m/s²]: linear interpolation of ln Sa in ln T between the rows.

        Raises:
            ValueError: a period outside the positive periods of the table (no extrapolation).
        """
        T = np.asarray(periods, dtype=float)
        rows_T, rows_Sa = self._positive
        lo, hi = rows_T[0], rows_T[-1]
        if np.any(T < lo * (1 - 1e-12)) or np.any(T > hi * (1 + 1e-12)):
            raise ValueError(f"periods outside the table's {lo:g}–{hi:g} s (no extrapolation)")
        T_in = np.clip(T, lo, hi)
        return np.exp(np.interp(np.log(T_in), np.log(rows_T), np.log(rows_Sa)))

    def describe(self, gravity: float = 9.81) -> str:
        """One line naming the table (for reports)."""
        T, Sa = self._positive
        return (f"tabulated MCE_R spectrum from {self.source} ({T.size} periods {T[0]:g}–{T[-1]:g} s, "
                f"Sa {Sa.min() / gravity:.3g}–{Sa.max() / gravity:.3g} g, log-log interpolated, 5 % damping)")


_UNIT_GROUP = re.compile(r"[\[(]\s*([^\])]+?)\s*[\])]")
_SEPARATORS = re.compile(r"[,;\s]+")


def read_target_spectrum(path, *, gravity: float = 9.81, key: str = "excitation.scale.target") -> TabulatedSpectrum:
    """Read a two-column target spectrum file (period, spectral acceleration) into SI.

    Layout: ``#`` comments and blank lines anywhere; one header line naming the two columns with their
    units in brackets or parentheses, period first (``period [s], Sa [g]``, ``T (s); Sa (m/s^2)``); then
    rows of two numbers separated by commas, semicolons, tabs or blanks, periods strictly increasing,
    spectral accelerations positive.  A first row at T = 0 (the PGA) is allowed.  ``g`` is the project's
    gravity.

    Args:
        path: the file.
        gravity: g [m/s²].
        key: the project key that named the file (for messages).

    Raises:
        ProjectError: naming the file, the line, what was expected and found.
    """
    file = str(path)

    def fail(message, line=None, expected=None, found=None):
        return ProjectError(message, file=file, line=line, key=key, expected=expected, found=found)

    path = Path(path)
    if not path.is_file():
        raise fail("target spectrum file not found", expected="a two-column file: period [s], Sa [g]",
                   found="no such file")
    try:
        lines = path.read_text(encoding="utf-8-sig").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise fail(f"cannot read the target spectrum ({exc})") from None
    header = None
    rows: list[tuple[int, float, float]] = []
    for lineno, raw in enumerate(lines, start=1):
        text = raw.split("#", 1)[0].strip()
        if not text:
            continue
        if header is None:
            units = _UNIT_GROUP.findall(text)
            if len(units) != 2:
                raise fail("the header must name both columns with units", line=lineno,
                           expected="a header like 'period [s], Sa [g]' before the numbers", found=repr(raw.strip()))
            header = (lineno, units)
            continue
        fields = [f for f in _SEPARATORS.split(text) if f]
        if len(fields) != 2:
            raise fail("a row needs two numbers", line=lineno, expected="period, spectral acceleration",
                       found=repr(raw.strip()))
        try:
            period, value = float(fields[0]), float(fields[1])
        except ValueError:
            raise fail("a row needs two numbers", line=lineno, expected="period, spectral acceleration",
                       found=repr(raw.strip())) from None
        if not (math.isfinite(period) and math.isfinite(value)):
            raise fail("non-finite value", line=lineno, expected="finite numbers", found=repr(raw.strip()))
        rows.append((lineno, period, value))
    if header is None:
        raise fail("empty target spectrum", expected="a header 'period [s], Sa [g]' and rows", found="no content")
    lineno, (t_unit, a_unit) = header
    try:
        t_factor = parse_quantity(f"1 {t_unit}", "time", gravity=gravity)
    except QuantityParseError:
        raise fail("the first column must be the period, with time units", line=lineno,
                   expected="e.g. 'period [s]'", found=f"units [{t_unit}]") from None
    try:
        a_factor = parse_quantity(f"1 {a_unit}", "acceleration", gravity=gravity)
    except QuantityParseError:
        raise fail("the second column must be the spectral acceleration, with acceleration units", line=lineno,
                   expected="e.g. 'Sa [g]' or 'Sa [m/s^2]'", found=f"units [{a_unit}]") from None
    positive = [r for r in rows if r[1] > 0.0]
    if len(positive) < 2:
        raise fail("too few rows", line=rows[-1][0] if rows else lineno,
                   expected="at least two rows with a positive period", found=f"{len(positive)}")
    previous = None
    for line, period, value in rows:
        if period < 0.0 or (previous is not None and period <= previous):
            raise fail("periods must increase", line=line,
                       expected=f"a period > {previous:g}" if previous is not None else "a period ≥ 0",
                       found=f"{period:g}")
        if value <= 0.0:
            raise fail("spectral accelerations must be positive", line=line, expected="Sa > 0", found=f"{value:g}")
        previous = period
    periods = np.array([r[1] for r in rows]) * t_factor
    values = np.array([r[2] for r in rows]) * a_factor
    return TabulatedSpectrum(periods, values, source=path.name)
