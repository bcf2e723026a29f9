"""Spectrum axes: parsing ``AXIS:lo:hi:n`` and turning axis values into pulse periods and amplitudes.

Rocking spectra are plotted in the dimensionless plane of thesis Sec 3.3.2 (SPEC §4, CONTRACT §2):

* x — ``omega_p/p``: pulse frequency ω_p = 2π/T_p over the frequency parameter p of one column
  (Eq 3.13); ``omega_p/p_hat``: over the system's p̂ (Eqs 3.76, 3.94, 4.32); ``Tp``: T_p in s.
* y — ``ap/up``: pulse amplitude a_p over the exact uplift acceleration g tan α of the column
  (Eq 3.34, α = atan(B/H) of the flat contact width — columns with and without extensions share
  their axes, as in thesis Fig 3.21); ``ap/g``: a_p over g.

Grids are inclusive and linear: ``lo:hi:n`` gives ``numpy.linspace(lo, hi, n)``; ``AXIS:v`` is the
single value v.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..design.frequencies import frequency_parameter
from ..design.geometry import half_diagonal
from ..design.quantities import design_quantities, system_frequency_parameter
from ...errors import RockdesignError
from ..system import RockingSystem

X_AXES = {
    "omega_p/p": "ω_p/p: pulse frequency 2π/T_p over the frequency parameter p of one column (Eq 3.13)",
    "omega_p/p_hat": "ω_p/p̂: pulse frequency 2π/T_p over the system's frequency parameter p̂ (Eqs 3.76/3.94/4.32)",
    "Tp": "T_p: pulse period [s]",
}
Y_AXES = {
    "ap/up": "a_p/(g tan α): pulse amplitude over the exact uplift acceleration of the column (Eq 3.34)",
    "ap/g": "a_p/g: pulse amplitude in g",
}
LABELS = {"omega_p/p": "ω_p / p", "omega_p/p_hat": "ω_p / p̂", "Tp": "T_p [s]",
          "ap/up": "a_p / (g tan α)", "ap/g": "a_p / g"}
MAX_POINTS = 100_000
"""Largest number of points accepted on one axis (a guard against typos such as 0:12:4010000)."""


class AxisError(RockdesignError):
    """An invalid ``--x``/``--y`` axis specification."""


@dataclass(frozen=True)
class Axis:
    """One inclusive linear grid of a spectrum axis.

    Attributes:
        name: one of :data:`X_AXES` or :data:`Y_AXES`.
        lo, hi: first and last value (dimensionless, or seconds for ``Tp``).
        n: number of points (``n = 1`` requires ``lo == hi``).
    """

    name: str
    lo: float
    hi: float
    n: int

    @property
    def values(self) -> np.ndarray:
        """The grid values, ``numpy.linspace(lo, hi, n)``."""
        return np.linspace(self.lo, self.hi, self.n)

    @property
    def text(self) -> str:
        """The ``AXIS:lo:hi:n`` string that reproduces this axis."""
        return f"{self.name}:{self.lo:.17g}:{self.hi:.17g}:{self.n}"

    @property
    def label(self) -> str:
        return LABELS[self.name]

    def as_json(self) -> dict:
        definition = X_AXES.get(self.name) or Y_AXES[self.name]
        return {"name": self.name, "lo": self.lo, "hi": self.hi, "n": self.n, "definition": definition,
                "unit": "s" if self.name == "Tp" else "-"}


def parse_axis(text: str, which: str) -> Axis:
    """Parse ``AXIS:lo:hi:n`` (or ``AXIS:value``) for the ``x`` or ``y`` axis of a spectrum.

    Raises:
        AxisError: unknown axis name, malformed numbers, n < 1, lo > hi, non-positive frequencies or
            periods, negative amplitudes.
    """
    key = which
    names = X_AXES if which == "x" else Y_AXES
    example = "omega_p/p:0.5:12:801" if which == "x" else "ap/up:0:12:401"
    expected = f"AXIS:lo:hi:n with AXIS one of {', '.join(names)} (e.g. {example})"
    parts = [p.strip() for p in str(text).strip().split(":")]
    if len(parts) not in (2, 4):
        raise AxisError("malformed axis", key=key, expected=expected, found=repr(text))
    name = parts[0]
    if name not in names:
        other = Y_AXES if which == "x" else X_AXES
        hint = f"'{name}' is a {'y' if which == 'x' else 'x'} axis" if name in other else None
        raise AxisError("unknown axis", key=key, expected=expected, found=repr(name), hint=hint)
    try:
        lo = float(parts[1])
        hi = float(parts[2]) if len(parts) == 4 else lo
    except ValueError:
        raise AxisError("axis limits must be numbers", key=key, expected=expected, found=repr(text)) from None
    if len(parts) == 4:
        try:
            n = int(parts[3])
        except ValueError:
            raise AxisError("the number of points must be an integer", key=key, expected=expected,
                            found=repr(parts[3])) from None
    else:
        n = 1
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise AxisError("axis limits must be finite", key=key, expected=expected, found=repr(text))
    if n < 1 or n > MAX_POINTS:
        raise AxisError("invalid number of points", key=key, expected=f"1 ≤ n ≤ {MAX_POINTS}", found=str(n))
    if hi < lo:
        raise AxisError("axis limits reversed", key=key, expected="lo ≤ hi", found=repr(text))
    if n == 1 and hi != lo:
        raise AxisError("one point needs lo = hi", key=key, expected="n ≥ 2, or AXIS:value", found=repr(text))
    if n > 1 and hi == lo:
        raise AxisError("an axis of several points needs lo < hi", key=key, expected="lo < hi", found=repr(text))
    if which == "x" and lo <= 0.0:
        raise AxisError("pulse frequencies and periods must be positive", key=key, expected="lo > 0",
                        found=repr(text))
    if which == "y" and lo < 0.0:
        raise AxisError("pulse amplitudes must be non-negative", key=key, expected="lo ≥ 0", found=repr(text))
    return Axis(name, lo, hi, n)


@dataclass(frozen=True)
class SpectrumScales:
    """The normalisations of one system (SI).

    Attributes:
        p: frequency parameter of one column [rad/s] (Eq 3.13).
        p_hat: frequency parameter of the system [rad/s] (Eqs 3.76/3.94/4.32; = p for a block).
        uplift_acceleration: g tan α of the column [m/s²] (Eq 3.34), the unit of the ``ap/up`` axis.
        uplift_acceleration_model: the true uplift acceleration [m/s²] of the system (g tan α' with
            flat extensions), reported for reference.
        g: gravitational acceleration [m/s²].
        alpha: slenderness angle α [rad] of the column (θ_max is reported as θ_max/α).
        theta_c: rotation capacity θc [rad] (Eq 3.56).
        R: half-diagonal R [m] of one column (Eq 2.2).
        u_capacity: column-top displacement capacity [m] (Polyakov's 2B generalised, SPEC §5).
    """

    p: float
    p_hat: float
    uplift_acceleration: float
    uplift_acceleration_model: float
    g: float
    alpha: float
    theta_c: float
    R: float
    u_capacity: float

    def as_json(self) -> dict:
        return {k: getattr(self, k) for k in ("p", "p_hat", "uplift_acceleration", "uplift_acceleration_model",
                                              "g", "alpha", "theta_c", "R", "u_capacity")}


def spectrum_scales(system: RockingSystem) -> SpectrumScales:
    """The axis normalisations and reference values of ``system`` (SPEC §2)."""
    c = system.column
    q = design_quantities(system)
    R = half_diagonal(c.half_width, c.half_height)
    p = frequency_parameter(R, c.mass_distribution, system.g)
    p_hat = system_frequency_parameter(system)[0]
    return SpectrumScales(p=p, p_hat=p_hat, uplift_acceleration=system.g * c.tan_alpha,
                          uplift_acceleration_model=q["uplift_acceleration"].value, g=system.g,
                          alpha=q["alpha"].value, theta_c=q["theta_c"].value, R=R,
                          u_capacity=q["u_capacity"].value)


def pulse_periods(axis: Axis, scales: SpectrumScales) -> np.ndarray:
    """Pulse periods T_p [s] at the x-axis values: T_p = 2π/(x p) (or 2π/(x p̂), or x for ``Tp``)."""
    x = axis.values
    if axis.name == "Tp":
        return x.copy()
    p = scales.p if axis.name == "omega_p/p" else scales.p_hat
    return 2.0 * math.pi / (x * p)


def x_from_periods(name: str, periods, scales: SpectrumScales) -> np.ndarray:
    """The inverse of :func:`pulse_periods`: x-axis values of pulse periods T_p [s]."""
    T = np.asarray(periods, dtype=float)
    if name == "Tp":
        return T.copy()
    p = scales.p if name == "omega_p/p" else scales.p_hat
    with np.errstate(divide="ignore"):
        return 2.0 * math.pi / (T * p)


def pulse_amplitudes(axis: Axis, scales: SpectrumScales) -> np.ndarray:
    """Pulse amplitudes a_p [m/s²] at the y-axis values: y g tan α (``ap/up``) or y g (``ap/g``)."""
    unit = scales.uplift_acceleration if axis.name == "ap/up" else scales.g
    return axis.values * unit


def y_unit(name: str, scales: SpectrumScales) -> float:
    """The acceleration [m/s²] that one unit of the y axis ``name`` stands for."""
    return scales.uplift_acceleration if name == "ap/up" else scales.g


DEFAULT_X = Axis("omega_p/p", 0.5, 12.0, 801)
"""The thesis grid (Figs 3.19–3.20): 801 pulse frequencies ω_p/p from 0.5 to 12."""
DEFAULT_Y = Axis("ap/up", 0.0, 12.0, 401)
"""The thesis grid: 401 amplitudes a_p/(g tan α) from 0 to 12."""
