"""Construction tolerance of the varied keys of a design chart (SPEC §15, CONTRACT §8.1, docs/design.md
"Construction tolerance").

A design variable is built to a tolerance — a column's width to a few millimetres, a curved base's curvature
to a few per cent — and the §16.4.1.1 count is a step function of it, so the recommended design must pass at
each varied key ± its tolerance, the other keys nominal (its *neighbourhood*).  Every varied key has one:

- the defaults (:func:`default_tolerance`): ±1 % of a length, ±2 % of a dimensionless key (a shape key such as
  ``curvature`` or ``slenderness``, a damping ratio) and of any other quantity (a mass, a period); a whole
  number (``columns``) is built exactly (no neighbours);
- the project file's ``[design.tolerance]`` table, ``"podium.width" = "2 mm"`` or ``podium.width = "1 %"``;
- ``--tolerance KEY=VALUE`` (the library's ``tolerance={KEY: VALUE}``), which wins over the project file.

A VALUE is relative (``"1%"``, ``"0.5 %"``) or absolute in the key's units (``"2 mm"``; a plain number for a
dimensionless key).  Zero is allowed and means "built exactly".
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

from ..errors import ProjectError, RockdesignError

LENGTH_TOLERANCE = 0.01
"""Default relative tolerance of a length (a column width built to ±1 %: ±4 mm of 0.40 m)."""
OTHER_TOLERANCE = 0.02
"""Default relative tolerance of a dimensionless key (curvature, slenderness) and of any other quantity."""
MAX_RELATIVE = 0.5
"""A relative tolerance of 50 % or more is not a construction tolerance."""


@dataclass(frozen=True)
class Tolerance:
    """The tolerance of one varied key: ``relative`` (a fraction) or ``absolute`` (in SI), and where it came from
    (``"default"``, ``"project"`` — ``[design.tolerance]`` —, or ``"option"``)."""

    key: str
    relative: float | None = None
    absolute: float | None = None
    source: str = "default"
    text: str = ""

    def plus_minus(self, si_value: float) -> float:
        """The tolerance at a value of the key, in SI (≥ 0)."""
        return abs(si_value) * self.relative if self.relative is not None else float(self.absolute)

    def as_json(self) -> dict:
        """design.json ``settings.tolerances[key]`` (CONTRACT §8.1): ``{"relative" | "absolute": value}`` and its
        source; an absolute value in SI."""
        out = {"relative": self.relative} if self.relative is not None else {"absolute": self.absolute}
        out["source"] = self.source
        if self.text:
            out["given"] = self.text
        return out

    def words(self, unit: str) -> str:
        """"±1 %", "±2 mm" — how the report states it."""
        if self.relative is not None:
            return f"±{100 * self.relative:g} %"
        return f"±{self.text}" if self.text else f"±{self.absolute:g}" + (f" {unit}" if unit else "")


def default_tolerance(variable) -> Tolerance:
    """The default tolerance of a varied key (module docstring): by the key's dimension."""
    if variable.integer:
        return Tolerance(variable.key, absolute=0.0)
    if variable.unit and not variable.plain and _dimension(variable.unit) == "[length]":
        return Tolerance(variable.key, relative=LENGTH_TOLERANCE)
    return Tolerance(variable.key, relative=OTHER_TOLERANCE)


def _dimension(unit: str) -> str:
    from ..units import registry
    return str(registry().Quantity(1.0, unit).dimensionality)


def project_tolerances(raw: dict, file: str | None) -> dict[str, str]:
    """The ``[design.tolerance]`` entries of a project's TOML document as ``{"table.key": VALUE text}`` (dotted
    keys written as nested tables are flattened); the table's shape is validated when the project is loaded
    (:func:`rockdesign.project_tables.parse_design_table`)."""
    table = ((raw.get("design") or {}).get("tolerance") or {})
    out = {}
    for k, v in table.items():
        if isinstance(v, dict):
            for name, value in v.items():
                out[f"{k}.{name}"] = value
        else:
            out[k] = v
    return out


def parse_tolerance(text, variable, *, key: str, file: str | None = None, source: str) -> Tolerance:
    """One VALUE (module docstring) for a varied key.

    Raises:
        RockdesignError (``key``: the parameter or the project file's key): not a relative or absolute value in
        the key's units, negative, not finite, or a relative tolerance of 50 % or more.
    """
    err = ProjectError if file is not None else RockdesignError
    kw = {"file": file} if file is not None else {}
    plain_key = not variable.unit or variable.plain
    example = "" if plain_key else ("4 mm" if _dimension(variable.unit) == "[length]" else f"0.1 {variable.unit}")
    expected = (f"a relative tolerance such as \"1%\" or an absolute one in the units of {variable.key}"
                + (f" (e.g. \"{example}\")" if example else " (a plain number)"))
    if isinstance(text, bool) or not isinstance(text, (str, int, float)):
        raise err("cannot read the tolerance", key=key, expected=expected, found=repr(text), **kw)
    shown = str(text).strip()
    m = re.fullmatch(r"([-+]?[\d.eE+-]+)\s*%", shown)
    if m:
        try:
            rel = float(m.group(1)) / 100.0
        except ValueError:
            rel = math.nan
        if not math.isfinite(rel) or rel < 0 or rel >= MAX_RELATIVE:
            raise err("tolerance out of range", key=key,
                      expected=f"a relative tolerance from 0 % to below {100 * MAX_RELATIVE:g} %",
                      found=f"{variable.key}: {shown}", **kw)
        return Tolerance(variable.key, relative=rel, source=source, text=shown)
    from ..units import registry
    try:
        q = registry()(shown.replace(" ", "")) if isinstance(text, str) else registry().Quantity(float(text), "")
    except Exception:          # pint raises several unrelated types for unreadable text
        raise err("cannot read the tolerance", key=key, expected=expected, found=f"{variable.key}: {shown}",
                  **kw) from None
    if not hasattr(q, "magnitude"):
        q = registry().Quantity(float(q), "")
    if plain_key:
        if not q.dimensionless:
            raise err("the tolerance has the wrong units", key=key, expected=expected,
                      found=f"{variable.key}: {shown}", **kw)
        si = float(q.to("").magnitude)
    else:
        want = registry().Quantity(1.0, variable.unit)
        if q.dimensionless and str(q.units) in ("", "dimensionless") or q.dimensionality != want.dimensionality:
            raise err("the tolerance has the wrong units", key=key, expected=expected,
                      found=f"{variable.key}: {shown}", **kw)
        si = float(q.to_base_units().magnitude)
    if not math.isfinite(si) or si < 0:
        raise err("tolerance out of range", key=key, expected="a finite tolerance ≥ 0",
                  found=f"{variable.key}: {shown}", **kw)
    return Tolerance(variable.key, absolute=si, source=source, text=shown)


def tolerances(variables, given: dict | None, raw: dict, *, file: str | None, option: str = "tolerance") \
        -> tuple[dict[str, Tolerance], list[str]]:
    """The tolerance of every varied key and the notes on the project file's entries not used by this chart.

    Args:
        variables: the chart's :class:`~rockdesign.design_space.variants.Variable` list.
        given: ``{KEY: VALUE}`` (or ``["KEY=VALUE", …]``) of ``--tolerance`` / the library's ``tolerance``; a key
            that is not varied is an input error naming ``option``.
        raw: the project's TOML document (its ``[design.tolerance]``).

    Raises:
        RockdesignError / ProjectError: a value that cannot be read, or a given key the chart does not vary.
    """
    by_key = {v.key: v for v in variables}
    out = {v.key: default_tolerance(v) for v in variables}
    if isinstance(given, (list, tuple)):
        given = parse_tolerance_options(given, option=option)
    notes = []
    for k, value in project_tolerances(raw, file).items():
        if k not in by_key:
            notes.append(f"[design.tolerance] {k} = {value!r} is not used: the chart does not vary {k}")
            continue
        out[k] = parse_tolerance(value, by_key[k], key=f"design.tolerance.{k}", file=file, source="project")
    for k, value in (given or {}).items():
        if not isinstance(k, str) or k not in by_key:
            raise RockdesignError("a tolerance of a key the chart does not vary", key=option,
                                  expected="KEY=VALUE with KEY one of the varied keys: " + ", ".join(by_key),
                                  found=f"{k}={value}")
        out[k] = parse_tolerance(value, by_key[k], key=option, source="option")
    return out, notes


def parse_tolerance_options(specs, *, option: str = "tolerance") -> dict[str, str]:
    """``["podium.width=2mm", …]`` (``--tolerance``, repeatable) as ``{KEY: VALUE}``.

    Raises:
        RockdesignError: a spec without ``=``, or a key given twice.
    """
    out: dict[str, str] = {}
    for spec in specs or ():
        if not isinstance(spec, str) or "=" not in spec:
            raise RockdesignError("cannot read the tolerance", key=option,
                                  expected="KEY=VALUE, e.g. podium.width=1% or podium.width=2mm", found=repr(spec))
        k, v = (s.strip() for s in spec.split("=", 1))
        if k in out:
            raise RockdesignError("the same key twice", key=option, expected="one tolerance per key", found=k)
        out[k] = v
    return out


__all__ = ["Tolerance", "default_tolerance", "tolerances", "parse_tolerance", "parse_tolerance_options",
           "project_tolerances", "LENGTH_TOLERANCE", "OTHER_TOLERANCE"]
