"""design.json and design.csv of ``rockdesign design`` (CONTRACT §6.3; SI units, keys stable)."""
from __future__ import annotations

import csv
import json
from pathlib import Path

from ..jsonable import json_ready

CSV_COLUMNS = ("analysed", "verdict", "robust", "draws_n", "draws_failed", "acmr", "acmr_required", "p_collapse_design",
               "flip_margin", "flip_margin_is_lower_bound", "flip_governing", "n_unacceptable", "allowed_unacceptable",
               "n_ground_motions", "superstructure_shear_p84", "superstructure_drift_p84",
               "median_theta_max_over_theta_c", "decided_at_design_level", "analyses", "analyses_saved", "reason")
"""The shared columns of design.csv (every kind's cells have them), ``reason`` last."""
RULE_COLUMNS = ("acceptance", "p_overturn_bound", "binomial_limit")
"""Columns after :data:`CSV_COLUMNS` when some cell has the number: the binomial rule's bound and limit
(``[analysis] acceptance = "binomial"``)."""
CSV_UNITS = {"superstructure_drift_p84": "m", "p_collapse_design": "-", "acmr": "-", "acmr_required": "-",
             "flip_margin": "-", "superstructure_shear_p84": "-", "median_theta_max_over_theta_c": "-",
             "p_overturn_bound": "-", "binomial_limit": "-"}


def presentation(kind) -> dict:
    """What a kind says of its design cells, as design.json holds it: ``columns`` (its own cell numbers,
    :attr:`~rockdesign.kinds.base.StructureKind.design_columns`, as ``{"key", "heading", "unit"}``), ``response``
    (``{"symbol", "meaning"}`` of the median response ratio) and ``plane`` (the figure of two of its numbers, or
    None)."""
    return {"columns": [{"key": key, "heading": heading, "unit": unit} for key, heading, unit in kind.design_columns],
            "response": dict(zip(("symbol", "meaning"), kind.design_response)),
            "plane": dict(kind.design_plane) if kind.design_plane else None}


def design_json(project, grid, recommendation, *, settings: dict | None = None, presentation: dict | None = None
                ) -> dict:
    """design.json: the project, the variables, one entry per cell, the recommended design, the analyses
    run and the (lower bound of the) analyses the shared work and early stopping saved; ``presentation``: what the
    kind says of its cells (:func:`presentation`)."""
    shown = presentation or {}
    columns = list(shown.get("columns") or [])
    return json_ready({
        "project": {"name": project.name, "file": project.path, "sha256": project.sha256, "kind": project.system.kind},
        "variables": [v.as_json() for v in grid.variables],
        "cells": [{**dict.fromkeys(c["key"] for c in columns), **cell} for cell in grid.cells],  # every cell: every column
        "recommended": recommendation,
        "analyses_run": grid.analyses_run,
        "analyses_saved": grid.analyses_saved,
        "analyses_saved_is_lower_bound": True,
        "variants_resumed": grid.resumed,
        "settings": settings or {},
        "columns": columns,
        "response": shown.get("response"),
        "plane": shown.get("plane"),
        "units": {"values": "SI (m, kg, s)", "superstructure_drift_p84": "m",
                  **{c["key"]: c["unit"] for c in columns if c["unit"] not in ("", "-")}},
    })


def write_design_json(data: dict, path: Path) -> Path:
    path.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return path


def write_design_csv(data: dict, path: Path) -> Path:
    """design.csv: one row per cell, the variables' SI values first; units in the header ("acmr [-]");
    ``analysed``, ``verdict`` (empty for a cell not analysed), ``robust`` (empty unless PASS) and the
    perturbation draws run and failed (``draws_n``, ``draws_failed``); the binomial rule's numbers when a cell has
    them (:data:`RULE_COLUMNS`) and the kind's own columns (design.json ``columns``) before ``reason``."""
    keys = [v["key"] for v in data["variables"]]
    units = {v["key"]: _si_unit(v["unit"]) for v in data["variables"]}
    own = data.get("columns") or []
    column_units = dict(CSV_UNITS, **{c["key"]: c["unit"] for c in own if c["unit"]})
    rule = [c for c in RULE_COLUMNS if any(cell.get(c) is not None for cell in data["cells"])]
    columns = list(CSV_COLUMNS[:-1]) + rule + [c["key"] for c in own] + [CSV_COLUMNS[-1]]
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow([f"{k} [{units[k]}]" for k in keys]
                   + [f"{c} [{column_units[c]}]" if c in column_units else c for c in columns])
        for cell in data["cells"]:
            row = dict(cell, draws_n=(cell.get("draws") or {}).get("n"),
                       draws_failed=(cell.get("draws") or {}).get("failed"))
            w.writerow([cell["values"][k] for k in keys] + ["" if row.get(c) is None else row.get(c)
                                                           for c in columns])
    return path


def _si_unit(unit: str) -> str:
    if unit in ("", "1"):
        return "-"
    from ..units import registry
    q = registry().Quantity(1.0, unit).to_base_units()
    return f"{q.units:~}".replace(" ", "") or "-"
