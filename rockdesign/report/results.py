"""``results.json`` and ``results.csv`` of a design check (CONTRACT §3, §4; SI units).

``results.json`` is :meth:`CheckResult.as_json` written by :func:`json_text` — the same bytes
``rockdesign check --json`` prints; ``results.csv`` has one row per record, in the columns and units the
check's kind declares (:attr:`~rockdesign.kinds.base.StructureKind.csv_columns`, ``csv_units``, ``csv_nested``).
"""
from __future__ import annotations

import csv
import json
from collections.abc import Mapping, Sequence
from pathlib import Path

def csv_header(column: str, units: Mapping[str, str] | None = None) -> str:
    """results.csv header of a column, with its unit (``units``: column → unit) in brackets when it has one."""
    units = units or {}
    return f"{column} [{units[column]}]" if column in units else column


def json_text(data: dict) -> str:
    """The JSON text of a check's results (indented, UTF-8 symbols kept, one trailing newline)."""
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


def write_results_json(data: dict, path: Path) -> Path:
    """Write ``results.json`` (the ``check --json`` text)."""
    path = Path(path)
    path.write_text(json_text(data), encoding="utf-8")
    return path


def write_results_csv(data: dict, path: Path, *, columns: Sequence[str],
                      units: Mapping[str, str] | None = None,
                      nested: Mapping[str, tuple[str, str]] | None = None) -> Path:
    """Write ``results.csv``: one row per record of ``data["records"]`` (per record pair of a cylinder), the
    ``columns`` the check's kind names, each with its unit from ``units`` in the header (SI); a column of
    ``nested`` (column → (section, key)) is read from a dict of the row (empty where that is null).
    """
    path = Path(path)
    nested = nested or {}
    with open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow([csv_header(c, units) for c in columns])
        for row in data["records"]:
            values = [(row.get(nested[c][0]) or {}).get(nested[c][1]) if c in nested else row.get(c) for c in columns]
            w.writerow(["" if v is None else v for v in values])
    return path
