"""Design variants: ``--vary TABLE.KEY=FROM:TO:N`` parsed, and the project with those values (SPEC §15).

A variable names a numeric key of the project file with its table (``podium.width``,
``superstructure.period``, ``podium.columns``, ``cylinder.diameter`` …).  FROM and TO carry the key's
units (``0.36m``, ``6 s``; a dimensionless key takes plain numbers); N values are spaced evenly from
FROM to TO.  Each variant is the project's TOML document with the values written in, validated by the
normal project loader — an impossible variant (a curvature the extension does not allow, a width
wider than the extension) is an *invalid* cell with the loader's message, never a crash.
"""
from __future__ import annotations

import copy
import itertools
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass

from ..errors import ProjectError, RockdesignError

MAX_VALUES = 41
"""Values per variable (a chart of 41 × 41 = 1681 checks is already a cluster's afternoon)."""

_SPEC = re.compile(r"^\s*([A-Za-z_]+)\.([A-Za-z_]+)\s*=\s*([^:]+):([^:]+):\s*(\d+)\s*$")


@dataclass(frozen=True)
class Variable:
    """One varied key: ``key`` "table.name", its ``values`` in the user's ``unit`` ("" when dimensionless),
    the same values in SI (``si``), and ``integer`` (the key takes whole numbers, e.g. ``columns``)."""

    key: str
    unit: str
    values: tuple[float, ...]
    si: tuple[float, ...]
    integer: bool = False
    replaces: tuple[str, ...] = ()
    """Keys of the same table this key replaces when written in (its alternatives, e.g. ``curvature``)."""
    plain: bool = False
    """The values carry a dimensionless unit ("%", "deg"): the project file gets the plain SI number."""

    @property
    def table(self) -> str:
        return self.key.split(".")[0]

    @property
    def name(self) -> str:
        return self.key.split(".")[1]

    def toml_value(self, k: int):
        """The k-th value as the project file writes it ("0.42 m", 8, 0.125)."""
        v = self.values[k]
        if self.integer:
            return int(round(v))
        if self.plain:
            return float(f"{self.si[k]:.12g}")
        return f"{v:.10g} {self.unit}" if self.unit else float(v)

    def label(self, k: int) -> str:
        """The k-th value for tables and charts ("0.42 m")."""
        v = self.values[k]
        return (f"{int(round(v))}" if self.integer else f"{v:.4g}") + (f" {self.unit}" if self.unit else "")

    def as_json(self) -> dict:
        return {"key": self.key, "unit": self.unit or "1", "values": list(self.values), "values_si": list(self.si)}

    def user_value(self, si: float) -> float:
        """An SI value of the key in the user's unit (as :attr:`values` hold them)."""
        return si / registry_si(1.0, self.unit) if self.unit else si

    def toml_of(self, si: float):
        """Any SI value of the key as the project file writes it (a neighbour between grid values)."""
        if self.plain:
            return float(f"{si:.12g}")
        v = self.user_value(si)
        return f"{v:.10g} {self.unit}" if self.unit else float(f"{v:.12g}")

    def label_of(self, si: float) -> str:
        """Any SI value of the key for tables ("0.3967 m"), one digit finer than :meth:`label` so that a value ± its
        tolerance reads apart from the grid value."""
        return f"{self.user_value(si):.5g}" + (f" {self.unit}" if self.unit else "")


def _quantity(text: str, option: str, spec: str):
    from ..units import registry
    try:
        q = registry()(text.strip().replace(" ", ""))
    except Exception as exc:     # pint raises several unrelated types for unreadable text
        raise RockdesignError("cannot read the value", key=option, expected="FROM:TO:N with FROM and TO in the "
                              "key's units, e.g. podium.width=0.36m:0.60m:7", found=f"{spec!r} ({exc})") from None
    if not hasattr(q, "magnitude"):
        q = registry().Quantity(float(q), "")
    return q


def parse_vary(spec: str, raw: dict, *, option: str = "vary", alternatives: Mapping[str, tuple[str, ...]] = {},
               derived: frozenset[str] = frozenset()) -> Variable:
    """Read one ``TABLE.KEY=FROM:TO:N`` (``--vary``) against the project's TOML document ``raw``;
    ``alternatives``: key → the keys of the project file it replaces (the kind's
    :attr:`~rockdesign.kinds.base.StructureKind.key_alternatives`: keys that say the same thing two ways, CONTRACT
    §1; the replacement is listed in design.json's ``notes``); ``derived``: the names of the kind's design
    quantities (CONTRACT §3), refused as keys; ``option``: how the caller names the parameter in errors (``vary``
    for the library, ``--vary`` on the command line).

    FROM and TO keep their units: a dimensionless value in another unit (``0.5%``, ``5deg``) is written into
    the variant's project file as its plain SI number (0.005, 0.0873 rad) and labelled in the user's unit.

    Raises:
        RockdesignError: an unreadable spec, a table the project has not, a design quantity instead of a
            key, a key that is not numeric, FROM and TO of different or wrong dimensions, FROM > TO, N = 1
            with TO ≠ FROM, N outside 1…:data:`MAX_VALUES`, or a non-integer value of an integer key.
            Whether the key exists and takes these units is the project loader's answer
            (:func:`variants`).
    """
    m = _SPEC.match(spec)
    if not m:
        raise RockdesignError("cannot read the variable", key=option,
                              expected="TABLE.KEY=FROM:TO:N, e.g. podium.width=0.36m:0.60m:7 or podium.columns=6:10:3",
                              found=repr(spec))
    table, name, lo_text, hi_text, n_text = m.groups()
    key = f"{table}.{name}"
    n = int(n_text)
    if not 1 <= n <= MAX_VALUES:
        raise RockdesignError("number of values out of range", key=option, expected=f"N from 1 to {MAX_VALUES}",
                              found=f"{key}: N = {n}")
    if not isinstance(raw.get(table), dict):
        raise RockdesignError("the project has no such table", key=option,
                              expected="a table of the project file: " + ", ".join(
                                  f"[{t}]" for t, v in raw.items() if isinstance(v, dict)), found=f"[{table}] in {key}")
    if name in derived and name not in raw[table]:
        raise RockdesignError("a design quantity, not a key of the project file", key=option,
                              expected=f"a key of [{table}] that the quantity depends on (e.g. width, extended_width, "
                                       "curvature, height)", found=f"{key} in {spec!r}")
    replaces = tuple(alternatives.get(name, ()))
    current = raw[table].get(name, next((raw[table][o] for o in replaces if o in raw[table]), None))
    if isinstance(current, (bool, dict, list)) or (isinstance(current, str) and not re.match(r"^\s*[-+.\d]", current)):
        raise RockdesignError("not a numeric key", key=option, expected="a key whose value is a number or a quantity",
                              found=f"{key} = {current!r}")
    lo, hi = _quantity(lo_text, option, spec), _quantity(hi_text, option, spec)
    if _plain(lo) and not _plain(hi):
        lo = lo.magnitude * hi.units      # FROM without unit takes TO's unit
    if _plain(hi) and not _plain(lo):
        hi = hi.magnitude * lo.units      # and TO without unit FROM's
    if lo.dimensionality != hi.dimensionality:
        raise RockdesignError("FROM and TO have different dimensions", key=option,
                              expected="FROM and TO in units of the same kind", found=f"{lo} and {hi} in {spec!r}")
    unit = "" if _plain(hi) else f"{hi.units:~}"
    lo_v = float(lo.to(hi.units).magnitude)
    hi_v = float(hi.magnitude)
    if not (math.isfinite(lo_v) and math.isfinite(hi_v)):
        raise RockdesignError("values must be finite", key=option, expected="finite FROM and TO", found=spec)
    if n == 1 and lo_v != hi_v:
        raise RockdesignError("one value but two ends", key=option,
                              expected=f"N = 1 with TO = FROM (e.g. {key}={lo_text.strip()}:{lo_text.strip()}:1), "
                                       "or N ≥ 2 values from FROM to TO", found=spec)
    if lo_v > hi_v:
        raise RockdesignError("FROM is above TO", key=option, expected="FROM ≤ TO (values ascending)",
                              found=f"{lo_text.strip()} > {hi_text.strip()} in {spec!r}")
    values = [lo_v] if n == 1 else [float(f"{lo_v + (hi_v - lo_v) * k / (n - 1):.12g}") for k in range(n)]
    integer = isinstance(raw[table].get(name), int) and not isinstance(raw[table].get(name), bool)
    if integer:
        if unit or any(abs(v - round(v)) > 1e-9 for v in values):
            raise RockdesignError("the key takes whole numbers", key=option,
                                  expected=f"{key}=FROM:TO:N with whole-number steps and no unit, e.g. {name}=6:10:3",
                                  found=spec)
        values = [float(round(v)) for v in values]
    own = raw[table].get(name)      # (``current`` may be the alternative's value, in other units)
    if isinstance(own, float) and unit and not hi.dimensionless:
        raise RockdesignError("the key takes plain numbers", key=option,
                              expected=f"{key}=FROM:TO:N without a unit (the project gives {name} = {own!r})",
                              found=spec)
    if len(set(values)) != len(values):
        raise RockdesignError("repeated values", key=option, expected="N distinct values", found=spec)
    si = [float(registry_si(v, unit)) for v in values]
    return Variable(key, unit, tuple(values), tuple(si), integer, replaces, plain=bool(unit) and hi.dimensionless)


def _plain(q) -> bool:
    """A quantity without a unit (not "%" or "deg", which are dimensionless but units)."""
    return str(q.units) in ("", "dimensionless")


def refuse_overlaps(variables, *, option: str = "vary") -> None:
    """Refuse one key given twice, or two keys that say the same thing (``podium.width`` with
    ``podium.slenderness``, CONTRACT §1): the second would replace the first in every variant while the
    cells are labelled by both.

    Raises:
        RockdesignError: naming both keys (``option``).
    """
    for k, a in enumerate(variables):
        for b in variables[k + 1:]:
            if a.key == b.key:
                raise RockdesignError("the same key twice", key=option, expected="two different keys", found=a.key)
            if a.table == b.table and (b.name in a.replaces or a.name in b.replaces):
                raise RockdesignError("two keys that say the same thing", key=option,
                                      expected=f"one of {a.key} or {b.key} (each replaces the other in the project "
                                               "file), with another key as the second variable",
                                      found=f"{a.key} and {b.key}")

def registry_si(value: float, unit: str) -> float:
    """``value`` in ``unit`` as an SI magnitude (plain numbers stay as they are)."""
    if not unit:
        return value
    from ..units import registry
    return float(registry().Quantity(value, unit).to_base_units().magnitude)


@dataclass
class Variant:
    """One cell of the grid: the indices into each variable's values, the TOML document and the
    validated project (or the loader's message when the variant is impossible)."""

    index: tuple[int, ...]
    raw: dict
    project: object | None
    invalid: str | None
    notes: tuple[str, ...] = ()
    values: dict | None = None
    """A variant off the grid (a tolerance neighbour): its values {key: SI value}; None on the grid (the values
    are the variables' at ``index``)."""
    labels: dict | None = None


def neighbour_variant(raw: dict, variables, index, key: str, si: float, *, file: str) -> Variant:
    """The grid's variant at ``index`` with ``key`` set to the SI value ``si`` (off the grid: a tolerance
    neighbour, SPEC §15), validated by the project loader like every variant (an impossible one is INVALID)."""
    from ..kinds import parse_document
    doc, notes = variant_document(raw, variables, index)
    var = next(v for v in variables if v.key == key)
    doc[var.table][var.name] = var.toml_of(si)
    values = {v.key: (si if v.key == key else v.si[k]) for v, k in zip(variables, index)}
    labels = {v.key: (v.label_of(si) if v.key == key else v.label(k)) for v, k in zip(variables, index)}
    label = ", ".join(f"{k} = {t}" for k, t in labels.items())
    try:
        proj = parse_document(doc, file=f"{file} [{label}]", text=variant_toml(doc))
        return Variant(tuple(index), doc, proj, None, tuple(notes), values, labels)
    except ProjectError as exc:
        return Variant(tuple(index), doc, None, str(exc), tuple(notes), values, labels)


def variant_document(raw: dict, variables, index) -> tuple[dict, list[str]]:
    """The project's TOML document with the variables' values at ``index`` written in (a deep copy) and
    the replacements it made ("podium.radius replaces podium.curvature")."""
    doc = copy.deepcopy(raw)
    notes = []
    for var, k in zip(variables, index):
        t = doc[var.table]
        for other in var.replaces:
            if other in t:
                del t[other]
                notes.append(f"{var.key} replaces {var.table}.{other}")
        t[var.name] = var.toml_value(k)
    return doc, notes


KEY_ERRORS = ("unknown key", "wrong type", "invalid value", "expects", "conflicting alternatives", "must be a table")
"""The loader's words for a key it cannot take at all (not a value out of its range): a ``--vary`` naming such
a key is an input error, not a grid of INVALID cells."""


def variants(raw: dict, variables, *, file: str, option: str = "vary") -> list[Variant]:
    """Every variant of the grid (row-major over the variables), each validated by the project loader.

    A variant the project rules do not allow (a contact width as wide as the extension) is an INVALID cell
    with the loader's message; the key itself refused by the loader (unknown, a key of another kind, the
    wrong type or units) and a grid without one valid variant are input errors (SPEC §15, docs/design.md).

    Raises:
        RockdesignError: naming ``option``, the key, what the loader expected and the value it found.
    """
    from ..kinds import parse_document
    out = []
    keys = {v.key for v in variables}
    for index in itertools.product(*(range(len(v.values)) for v in variables)):
        doc, notes = variant_document(raw, variables, index)
        label = ", ".join(f"{v.key} = {v.label(k)}" for v, k in zip(variables, index))
        try:
            proj = parse_document(doc, file=f"{file} [{label}]", text=variant_toml(doc))
            out.append(Variant(index, doc, proj, None, tuple(notes)))
        except ProjectError as exc:
            if exc.key in keys and exc.detail.startswith(KEY_ERRORS):
                what = ("the project file has no such key" if exc.detail == "unknown key"
                        else f"the values do not fit the key: {exc.detail}")
                raise RockdesignError(what, key=option, expected=exc.expected or "values in the key's units",
                                      found=f"{exc.key} ({label})" + (f"; {exc.found}" if exc.found else ""),
                                      hint=exc.hint) from None
            out.append(Variant(index, doc, None, str(exc), tuple(notes)))
    if out and all(v.project is None for v in out):
        raise RockdesignError("no variant of the grid is a valid project", key=option,
                              expected="values the project file allows for at least one variant",
                              found=f"{len(out)} invalid variant(s), e.g. {out[0].invalid}")
    return out


def variant_toml(doc: dict) -> str:
    """A project's TOML document as the text of a project file (top-level tables as ``[table]``, nested
    tables inline): what the variant's own project file holds, so that ``rockdesign check`` of that
    file analyses the same variant."""
    lines = []
    for table, body in doc.items():
        if not isinstance(body, dict):
            lines.insert(0, f"{_bare(table)} = {_value(body)}")
            continue
        lines += ["", f"[{_bare(table)}]"] + [f"{_bare(k)} = {_value(v)}" for k, v in body.items()]
    return "\n".join(lines).lstrip("\n") + "\n"


def _bare(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else _value(key)


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("nan" if math.isnan(v) else ("inf" if v > 0 else "-inf"))
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_bare(k)} = {_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")
