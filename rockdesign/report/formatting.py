"""How numbers and units are written in the calculation report (one place, used by the templates,
the figures and the tests that compare the PDF with results.json).

Numbers carry :data:`DIGITS` significant digits, trailing zeros dropped; magnitudes from 1e-3 to
below 1e6 are written positionally, others as ``m·10ⁿ``.  The minus sign is U+2212.
"""
from __future__ import annotations

import math

DIGITS = 4
"""Significant digits of every number in the report."""

_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")

UNIT_LABELS = {
    "m/s^2": "m/s²",
    "m/s2": "m/s²",
    "m^2": "m²",
    "1/s": "1/s",
    "rad/s": "rad/s",
    "-": "",
    "": "",
    None: "",
}
"""results.json unit names → report spelling (SI throughout)."""


def unit_label(unit: str | None) -> str:
    """Report spelling of a results.json unit (dimensionless → empty)."""
    return UNIT_LABELS.get(unit, unit)


def fmt(value, unit: str | None = None, digits: int = DIGITS) -> str:
    """A number as the report prints it, with its unit if given.

    Args:
        value: float, int, bool or None (None/NaN → "—", ±inf → "∞").
        unit: a results.json unit name (``"m"``, ``"m/s^2"``, ``"-"`` ...), appended after a space.
        digits: significant digits.

    Examples: ``fmt(0.14888994760949725, "rad")`` → ``"0.1489 rad"``; ``fmt(7290804.26, "N")`` →
    ``"7.291·10⁶ N"``; ``fmt(-0.5)`` → ``"−0.5"``; ``fmt(44)`` → ``"44"``.
    """
    text = number(value, digits)
    label = unit_label(unit)
    if label and text not in ("—",):
        return f"{text} {label}"
    return text


def number(value, digits: int = DIGITS) -> str:
    """A number with ``digits`` significant digits (see module docstring), without unit."""
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value).replace("-", "−")
    x = float(value)
    if math.isnan(x):
        return "—"
    if math.isinf(x):
        return "∞" if x > 0 else "−∞"
    if x == 0.0:
        return "0"
    # rounding can carry into the next decade (9.9996 → 10.00)
    rounded = float(f"{x:.{digits - 1}e}")
    exponent = math.floor(math.log10(abs(rounded)))
    if -3 <= exponent < 6:
        decimals = max(0, digits - 1 - exponent)
        text = f"{rounded:.{decimals}f}"
        if "." in text:
            text = text.rstrip("0").rstrip(".")
    else:
        mantissa = rounded / 10.0 ** exponent
        m = f"{mantissa:.{digits - 1}f}".rstrip("0").rstrip(".")
        text = f"{m}·10{str(exponent).translate(_SUPERSCRIPT)}"
    return text.replace("-", "−")


def plural(count: int, word: str, words: str | None = None) -> str:
    """``count`` and the noun in the number it needs: "1 ground motion", "2 ground motions", "0 records"
    (``words``: an irregular plural)."""
    return f"{number(count)} {word if count == 1 else (words or word + 's')}"
