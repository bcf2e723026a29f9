"""What a failed check points to: the ``rockdesign design`` run that finds a passing variant (SPEC §15).

A FAIL of the acceptance rule (too many ground motions overturn, or the collapse margin is short) is a
statement about the rocking demand against the capacity.  The thesis's design recommendation is stated in
two parameters (SPEC §15): the uplift force, through tan α — set by the contact width (a cylinder's diameter)
— and the rotation capacity θc, set by the extension's curvature.  :func:`design_hint` names the project
file's own key for each and a grid around its value, in the file's units (the command line writes it as the
``rockdesign design`` command to run).
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from ..kinds import kind_of

SPAN = (0.8, 1.4, 4)
"""The suggested grid: from 0.8× to 1.4× the project's value, 4 values (wider contacts uplift later)."""


def _slenderness_key(kind) -> str:
    """The key that sets tan α in the kind's tables: the partner of ``slenderness`` (``width``, ``diameter``)."""
    return next((k for k, v in kind.key_alternatives.items() if "slenderness" in tuple(v)), "width")


def _grid(value) -> str | None:
    """FROM:TO:N around ``value`` (a quantity string such as "0.45 m", or a plain number), in its units."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        number, unit = float(value), ""
    else:
        m = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\s].*?)?\s*", str(value))
        if not m:
            return None
        number, unit = float(m.group(1)), (m.group(2) or "").replace(" ", "")
    if not number > 0:
        return None
    lo, hi, n = SPAN
    return f"{number * lo:.3g}{unit}:{number * hi:.3g}{unit}:{n}"


@dataclass(frozen=True)
class DesignHint:
    """What a failed check points to: ``why`` (the keys that govern the rocking demand, with their equations),
    ``vary`` (one ``TABLE.KEY=FROM:TO:N`` per key, around the project's value) and whether the project needs an
    ``[excitation]`` table first; ``str()`` says it in the library's words (the command line writes the command)."""

    why: str
    vary: tuple[str, ...]
    needs_excitation: bool
    file: str

    def __str__(self) -> str:
        first = "give the project an [excitation] table, then " if self.needs_excitation else ""
        return (f"to find a design that passes, vary what governs the rocking demand ({self.why}): {first}a design "
                f"chart of {self.file} over " + " and ".join(self.vary))


def design_hint(project, data: dict) -> DesignHint | None:
    """After a FAIL: the parameters that govern the rocking demand and the design chart that varies them (None when
    the check passed, or the project has no such key to vary)."""
    if data.get("verdict") != "FAIL" or data.get("failed_records"):
        return None
    raw = project.raw or {}
    key = _slenderness_key(kind_of(project))
    table = next((t for t, body in raw.items() if isinstance(body, dict) and (key in body or "slenderness" in body)
                  and t != "analysis"), None)
    if table is None:
        return None
    name = key if key in raw[table] else "slenderness"
    grid = _grid(raw[table][name])
    if grid is None:
        return None
    varies = [f"{table}.{name}={grid}"]
    why = (f"{table}.{name} sets tan α, the uplift acceleration g·tan α (Eq 3.34) that every record must "
           "exceed to rock")
    for curve in ("curvature", "radius"):
        if curve in raw[table]:
            g2 = _grid(raw[table][curve])
            if g2 is not None:
                varies.append(f"{table}.{curve}={g2}")
                why += f"; {table}.{curve} sets the rotation capacity θc (Eq 3.56)"
            break
    return DesignHint(why, tuple(varies), project.excitation_raw is None, str(project.path))


__all__ = ["design_hint", "DesignHint"]
