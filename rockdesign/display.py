"""Human-readable output: rich tables and display-unit conversion (pint at the boundary)."""
from __future__ import annotations

import math

from rich.console import Console
from rich.table import Table

from .errors import RockdesignError
from .units import registry

_SI_UNITS = {"m": "m", "rad": "rad", "1/s": "1/s", "m/s^2": "m/s^2", "N": "N", "s": "s", "kg": "kg", "-": ""}


def parse_display_units(spec: str | None, gravity: float) -> list[tuple[str, object]]:
    """Parse ``--units 'mm,deg,kN,g'`` into (label, pint unit) pairs; 'g' means the project's g."""
    if not spec:
        return []
    ureg = registry()
    out = []
    for token in (t.strip() for t in spec.split(",")):
        if not token:
            continue
        if token == "g":
            out.append(("g", ureg.Quantity(gravity, "m/s^2")))
            continue
        try:
            out.append((token, ureg.Quantity(1.0, ureg.parse_units(token.replace("^", "**")))))
        except Exception:
            raise RockdesignError("unknown display unit", key="--units", expected="pint units such as mm, deg, kN, g",
                                  found=f"'{token}'") from None
    return out


def convert_for_display(value: float, unit: str, targets) -> tuple[float, str]:
    """Convert an SI value to the first matching display unit of ``targets`` (else keep SI)."""
    if not targets or unit in ("-", "") or math.isinf(value):
        return value, unit
    ureg = registry()
    q = ureg.Quantity(value, ureg.parse_units(unit.replace("^", "**")))
    for label, ref in targets:
        if q.dimensionality == ref.dimensionality:
            return float((q / ref).to("").magnitude), label
    return value, unit


def format_value(value: float) -> str:
    if math.isinf(value):
        return "∞"
    if value == 0:
        return "0"
    a = abs(value)
    if 1e-3 <= a < 1e5:
        return f"{value:.5g}"
    return f"{value:.4e}"


def quantities_table(quantities: dict, console: Console, units: str | None, gravity: float, title: str,
                     warnings=()) -> None:
    """Print design quantities as a table: symbol, name, value, unit, equation."""
    targets = parse_display_units(units, gravity)
    table = Table(title=title, title_justify="left")
    for col in ("symbol", "quantity", "value", "unit", "equation"):
        table.add_column(col, justify="right" if col == "value" else "left")
    for q in quantities.values():
        v, u = convert_for_display(q.value, q.unit, targets)
        table.add_row(q.symbol, q.description + (f" ({q.note})" if q.note else ""), format_value(v), u or "-",
                      q.equation)
    console.print(table)
    for w in warnings:
        console.print(f"[yellow]warning:[/] {w}", highlight=False)
