"""Quantities at the boundary: pint parsing of user strings into plain SI floats.

Inside rockdesign every number is an SI float; pint is used only here, when reading project
files, motion strings and CLI options, and when formatting numbers for display.

In accelerations the token ``g`` means the gravitational acceleration of the project (CONTRACT §1),
never gram: ``"0.35 g"`` with g = 9.81 m/s² is 3.4335 m/s².
"""
from __future__ import annotations

import re
from functools import lru_cache

import pint

G_DEFAULT = 9.81
"""Default gravitational acceleration [m/s²] (SPEC §0)."""

DIMENSIONS = {
    "length": "[length]",
    "mass": "[mass]",
    "time": "[time]",
    "frequency": "1 / [time]",
    "acceleration": "[length] / [time] ** 2",
    "velocity": "[length] / [time]",
    "density": "[mass] / [length] ** 3",
    "dimensionless": "",
    "angle": "",
}

_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")
_G_TOKEN = re.compile(r"(?<![A-Za-z_])g(?![A-Za-z_0-9])")
_POWER_SUFFIX = re.compile(r"(?<=[A-Za-z])(\d+)")


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    """The single pint registry used by rockdesign."""
    ureg = pint.UnitRegistry()
    ureg.define("project_gravity = 9.81 m/s^2")  # placeholder, replaced by value at parse time
    return ureg


class QuantityParseError(ValueError):
    """Raised by :func:`parse_quantity`; callers wrap it into a ProjectError/MotionError."""


def _normalise_unit_text(unit_text: str, gravity: float) -> str:
    # "m/s2" -> "m/s^2" (pint does not read a bare power suffix)
    unit_text = _POWER_SUFFIX.sub(r"^\1", unit_text)
    return _G_TOKEN.sub(f"({gravity!r} m/s^2)", unit_text)


def parse_quantity(text, dimension: str, *, gravity: float = G_DEFAULT) -> float:
    """Parse ``text`` (a string with units, or a plain number for dimensionless values) to SI.

    Args:
        text: e.g. ``"3.0 m"``, ``"190 t"``, ``"0.35 g"``, ``"1 %"`` or a bare number.
        dimension: one of :data:`DIMENSIONS` (``"length"``, ``"acceleration"``...).
        gravity: value of ``g`` in m/s² used for accelerations.

    Returns:
        The value in SI base units (m, kg, s, rad, m/s², kg/m³...).

    Raises:
        QuantityParseError: with a message saying what was expected and found.
    """
    if dimension not in DIMENSIONS:
        raise KeyError(dimension)
    if isinstance(text, bool):
        raise QuantityParseError(f"{_a(_describe(dimension))}, got the boolean {text!r}")
    if isinstance(text, (int, float)):
        if dimension in ("dimensionless", "angle"):
            return float(text)
        raise QuantityParseError(
            f"{_a(_describe(dimension))} with units (e.g. {_example(dimension)}), got the plain number {text!r}")
    if not isinstance(text, str):
        raise QuantityParseError(f"{_a(_describe(dimension))} as a string with units, got {text!r}")
    match = _NUMBER.match(text)
    if not match:
        raise QuantityParseError(f"{_a(_describe(dimension))} like {_example(dimension)}, got '{text}'")
    number, unit_text = match.groups()
    ureg = registry()
    try:
        unit = ureg.parse_expression(_normalise_unit_text(unit_text, gravity)) if unit_text else 1.0
    except Exception as exc:  # pint raises several error types
        raise QuantityParseError(
            f"{_a(_describe(dimension))} like {_example(dimension)}, got '{text}' (unknown unit: {exc})") from None
    q = float(number) * unit
    if not isinstance(q, pint.Quantity):
        q = ureg.Quantity(q, "")
    want = ureg.get_dimensionality(DIMENSIONS[dimension]) if DIMENSIONS[dimension] else ureg.Quantity(1).dimensionality
    if q.dimensionality != want:
        raise QuantityParseError(f"{_a(_describe(dimension))}, got '{text}' ({_a(_name_of(q))})")
    return float(q.to_base_units().magnitude)


def parse_angular_frequency(text, *, plain_is_cyclic: bool) -> float:
    """A frequency key as an angular frequency ω [rad/s]: ``"16.5 rad/s"``, ``"100 rpm"``, ``"90 deg/s"``,
    ``"1 cycle/s"`` carry their angle (pint's base value is already ω); ``"2 Hz"`` (any hertz) is cyclic,
    ω = 2π f; a unit without either (``"2 /s"``) is cyclic when ``plain_is_cyclic`` (the superstructure's
    ``frequency``, CONTRACT §1 ``frequency = "2 Hz"``), angular otherwise (a cylinder's ``contact_frequency``,
    ω_n of Eq 5.32).

    Raises:
        QuantityParseError: not a frequency (as :func:`parse_quantity`).
    """
    import math
    value = parse_quantity(text, "frequency")
    unit_text = _NUMBER.match(text).group(2) if isinstance(text, str) else ""
    unit = registry().parse_expression(_normalise_unit_text(unit_text, G_DEFAULT)) if unit_text else None
    if unit is not None and "radian" in str((1.0 * unit).to_base_units().units):
        return value                                    # rad/s, rpm, deg/s, cycle/s: already ω
    if unit is not None and "hertz" in str(getattr(unit, "units", "")):
        return 2.0 * math.pi * value
    return 2.0 * math.pi * value if plain_is_cyclic else value


def _a(noun: str) -> str:
    """The noun with its indefinite article ("an acceleration", "a length")."""
    return ("an " if noun[:1].lower() in "aeiou" else "a ") + noun


def _describe(dimension: str) -> str:
    return {"dimensionless": "dimensionless number", "angle": "angle"}.get(dimension, dimension)


def _example(dimension: str) -> str:
    return {
        "length": "'3.0 m'", "mass": "'190 t'", "time": "'0.5 s'", "frequency": "'2 Hz'",
        "acceleration": "'0.35 g' or '3.4 m/s^2'", "velocity": "'0.5 m/s'",
        "density": "'2.5 t/m^3'", "dimensionless": "0.02 or '2 %'", "angle": "'0.05 rad'",
    }[dimension]


def _name_of(q: pint.Quantity) -> str:
    ureg = registry()
    for name, dim in DIMENSIONS.items():
        if name in ("angle",):
            continue
        target = ureg.get_dimensionality(dim) if dim else ureg.Quantity(1).dimensionality
        if q.dimensionality == target:
            return name
    return f"quantity of dimension {q.dimensionality}"


