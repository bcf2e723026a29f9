"""What every kind's calculation report shares: the project's inputs as the user wrote them (units as
given), the software versions and the report date."""
from __future__ import annotations

import os
import platform
import re
from datetime import datetime, timezone
from importlib import metadata

from .. import __version__
from ..kernel_cache import sources_digest


SOFTWARE = ("rockdesign", "numpy", "scipy", "numba", "matplotlib", "weasyprint", "jinja2", "pint")
"""Packages whose versions the report lists (besides Python)."""


_E_NOTATION = re.compile(r"(?<![\w.])(\d+(?:\.\d+)?)e([+-]?)0*(\d+)\b")


_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def pretty_exponents(text: str) -> str:
    """``2.9e+05`` → ``2.9·10⁵`` in formula text (the report's way of writing powers of ten)."""
    def repl(m):
        sign = "-" if m.group(2) == "-" else ""
        return f"{m.group(1)}·10{(sign + m.group(3)).translate(_SUPERSCRIPT)}"
    return _E_NOTATION.sub(repl, text or "")


_SI_UNIT = {"mass": "kg", "length": "m"}
"""Input dimensions whose values the substituted formulas print in SI (mass, length)."""


def _si_texts(value: float, unit: str) -> list[str]:
    """The ways the design quantities print an SI input inside a substituted formula (5 significant
    digits, powers of ten as ``2.9·10^5`` or ``2.9e+05``), with the unit."""
    plain = f"{value:.5g}"
    out = [f"{plain} {unit}"]
    if "e" in plain:
        mant, exp = plain.split("e")
        out.append(f"{mant}·10^{int(exp)} {unit}")
    return out


def inputs_as_given(project) -> dict[str, str]:
    """SI text → the project file's own text, for every mass and length the project gives in other
    units (``"2.9·10^5 kg"`` → ``"290 t"``): the report echoes inputs in the units of the input."""
    from ..units import QuantityParseError, parse_quantity
    g = getattr(project.system, "g", 9.81)
    out: dict[str, str] = {}
    for table in (project.raw or {}).values():
        if not isinstance(table, dict):
            continue
        for text in table.values():
            if not isinstance(text, str):
                continue
            for dimension, unit in _SI_UNIT.items():
                try:
                    value = parse_quantity(text, dimension, gravity=g)
                except (QuantityParseError, KeyError):
                    continue
                given = " ".join(text.split())
                if given.split(" ", 1)[-1] != unit:
                    for si in _si_texts(value, unit):
                        out[si] = given
                break
    return out


def as_given(text: str, given: dict[str, str]) -> str:
    """``text`` with every SI rendering of an input (see :func:`inputs_as_given`) replaced by the input."""
    for si, raw in sorted(given.items(), key=lambda kv: -len(kv[0])):
        text = re.sub(rf"(?<![\w.·^]){re.escape(si)}(?!\w)", raw, text)
    return text


def given_value(project, table: str, key: str) -> str | None:
    """The project file's text of ``[table] key`` (whitespace normalised), None if absent or not text."""
    value = ((project.raw or {}).get(table) or {}).get(key)
    return " ".join(value.split()) if isinstance(value, str) else None


def software_versions() -> list[tuple[str, str]]:
    """(name, version) of Python and the packages of :data:`SOFTWARE` that are installed, and, after
    rockdesign, the SHA-256 of its numerical kernels' sources (:func:`rockdesign.kernel_cache.sources_digest`,
    in full in results.json as ``project.kernels_sha256``)."""
    out = [("python", platform.python_version())]
    for name in SOFTWARE:
        if name == "rockdesign":
            out += [(name, __version__), ("rockdesign numerical kernels (SHA-256)", sources_digest()[:12] + "…")]
            continue
        try:
            out.append((name, metadata.version(name)))
        except metadata.PackageNotFoundError:
            continue
    return out


def report_date() -> str:
    """The report date (UTC, ISO); ``SOURCE_DATE_EPOCH`` fixes it for reproducible builds."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    when = datetime.fromtimestamp(int(epoch), tz=timezone.utc) if epoch else datetime.now(timezone.utc)
    return when.strftime("%Y-%m-%d")


def quality_note(project, data: dict) -> str:
    """Where the FEMA P695 quality ratings of a check's collapse margin come from (the project's
    ``[analysis] quality`` or the default), "" without a collapse margin."""
    if not data.get("collapse_margin"):
        return ""
    given = ((project.raw or {}).get("analysis") or {}).get("quality")
    if given:
        return "ratings from the project's [analysis] quality"
    return ("default ratings B ('good', β = 0.20 each; FEMA P695 Tables 3-1, 3-2 and 5-3): the project gives no "
            "[analysis] quality")
