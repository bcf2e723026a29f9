"""A design quantity as every kind of structure reports it: SI value, unit, symbol, thesis equation, its
formula and the formula with the numbers substituted (what the calculation report prints)."""
from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Quantity:
    """One design quantity: SI value with unit, its equation and how it was computed."""

    name: str
    symbol: str
    description: str
    value: float
    unit: str
    equation: str
    formula: str = ""
    substituted: str = ""
    note: str = ""

    def as_json(self) -> dict:
        return {"value": self.value, "unit": self.unit, "equation": self.equation}


def format_number(x: float) -> str:
    """A number for substituted formulas: 5 significant digits, powers of ten written out."""
    if math.isinf(x):
        return "∞"
    text = f"{x:.5g}"
    if "e" in text:
        mant, exp = text.split("e")
        text = f"{mant}·10^{int(exp)}"
    return text
