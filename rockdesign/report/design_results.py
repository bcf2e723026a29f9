"""design.json and design.csv of ``rockdesign design`` (CONTRACT §6.3; SI units, keys stable)."""
from __future__ import annotations

import csv
import json
import math
from pathlib import Path

from ..jsonable import json_ready

CSV_COLUMNS = ("analysed", "verdict", "robust", "draws_n", "draws_failed", "acmr", "acmr_required", "p_collapse_design",
               "flip_margin", "flip_margin_is_lower_bound", "flip_governing", "n_unacceptable", "allowed_unacceptable",
               "n_ground_motions", "superstructure_shear_p84", "superstructure_drift_p84",
               "median_theta_max_over_theta_c", "uplift_acceleration", "uplift_shear_coefficient", "theta_c",
               "decided_at_design_level", "analyses", "analyses_saved", "reason")
EXTRA_COLUMNS = ("acceptance", "n_incremental_unacceptable", "p_overturn", "p_overturn_bound", "binomial_limit",
                 "median_theta_max_over_alpha", "alpha", "theta_overturn", "column_material")
"""Columns after :data:`CSV_COLUMNS` (before ``reason``) when some cell has the number: a cylinder's record-pair
numbers (design.json documents them in docs/design.md)."""
CSV_UNITS = {"superstructure_drift_p84": "m", "uplift_acceleration": "m/s^2", "theta_c": "rad", "p_collapse_design": "-",
             "acmr": "-", "acmr_required": "-", "flip_margin": "-", "superstructure_shear_p84": "-", "uplift_shear_coefficient": "-",
             "median_theta_max_over_theta_c": "-", "p_overturn": "-", "p_overturn_bound": "-", "binomial_limit": "-",
             "median_theta_max_over_alpha": "-", "alpha": "rad", "theta_overturn": "rad", "column_material": "kg"}


def design_json(project, grid, recommendation, *, settings: dict | None = None) -> dict:
    """design.json: the project, the variables, one entry per cell, the recommended design, the analyses
    run and the (lower bound of the) analyses the shared work and early stopping saved."""
    return json_ready({
        "project": {"name": project.name, "file": project.path, "sha256": project.sha256, "kind": project.system.kind},
        "variables": [v.as_json() for v in grid.variables],
        "cells": grid.cells,
        "recommended": recommendation,
        "analyses_run": grid.analyses_run,
        "analyses_saved": grid.analyses_saved,
        "analyses_saved_is_lower_bound": True,
        "variants_resumed": grid.resumed,
        "settings": settings or {},
        "units": {"values": "SI (m, kg, s)", "uplift_acceleration": "m/s^2", "theta_c": "rad",
                  "superstructure_drift_p84": "m", "column_material": "kg"},
    })


def write_design_json(data: dict, path: Path) -> Path:
    path.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return path


def write_design_csv(data: dict, path: Path) -> Path:
    """design.csv: one row per cell, the variables' SI values first; units in the header ("theta_c [rad]");
    ``analysed``, ``verdict`` (empty for a cell not analysed), ``robust`` (empty unless PASS) and the
    perturbation draws run and failed (``draws_n``, ``draws_failed``);
    a cylinder grid adds its record-pair columns (:data:`EXTRA_COLUMNS`) before ``reason``."""
    keys = [v["key"] for v in data["variables"]]
    units = {v["key"]: _si_unit(v["unit"]) for v in data["variables"]}
    extra = [c for c in EXTRA_COLUMNS if any(cell.get(c) is not None for cell in data["cells"])
             and any(cell.get("theta_overturn") is not None for cell in data["cells"])]
    columns = list(CSV_COLUMNS[:-1]) + extra + [CSV_COLUMNS[-1]]
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow([f"{k} [{units[k]}]" for k in keys]
                   + [f"{c} [{CSV_UNITS[c]}]" if c in CSV_UNITS else c for c in columns])
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
