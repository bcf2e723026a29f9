"""``results.json`` and ``results.csv`` of a design check (CONTRACT §3, §4; SI units).

``results.json`` is :meth:`CheckResult.as_json` written by :func:`json_text` — the same bytes
``rockdesign check --json`` prints; ``results.csv`` has one row per record.
"""
from __future__ import annotations

import csv
import json
from pathlib import Path

CSV_COLUMNS = ["id", "suite", "event", "station", "rsn", "component", "scale", "pga", "sd_max", "sd_max_period",
               "polyakov_ratio", "theta_max_over_alpha", "theta_max_over_theta_c", "u_B_max", "u_B_max_over_2B",
               "impacts", "uplift_time", "overturned", "overturn_mode", "class", "overturn_scale", "polyakov_scale",
               "ensemble_overturn_fraction", "outcome_robust", "status", "analysis_failed",
               "superstructure_acceleration_max", "superstructure_shear_coefficient_max", "superstructure_drift_max",
               "fixed_base_acceleration_max", "force_ratio"]

DEMAND_COLUMNS = {"superstructure_acceleration_max": "acceleration_max",
                  "superstructure_shear_coefficient_max": "shear_coefficient_max",
                  "superstructure_drift_max": "drift_max", "fixed_base_acceleration_max": "fixed_base_acceleration_max",
                  "force_ratio": "force_ratio"}
"""results.csv columns read from a record's ``superstructure`` dict (empty where it is null)."""

CSV_UNITS = {"scale": "-", "pga": "m/s^2", "sd_max": "m", "sd_max_period": "s", "polyakov_ratio": "-",
             "theta_max_over_alpha": "-", "theta_max_over_theta_c": "-", "u_B_max": "m", "u_B_max_over_2B": "-",
             "uplift_time": "s", "overturn_scale": "-", "polyakov_scale": "-", "ensemble_overturn_fraction": "-",
             "resultant_pga": "m/s^2", "planar_theta_max_over_alpha": "-", "polyakov_ratio_x": "-",
             "polyakov_ratio_y": "-", "min_contact_force_over_weight": "-",
             "superstructure_acceleration_max": "m/s^2", "superstructure_shear_coefficient_max": "-",
             "superstructure_drift_max": "m", "fixed_base_acceleration_max": "m/s^2", "force_ratio": "-"}
"""Units of the results.csv columns (header "pga [m/s^2]"); the others are counts, ids or words."""


def csv_header(column: str) -> str:
    """results.csv header of a column, with its unit in brackets when it has one."""
    return f"{column} [{CSV_UNITS[column]}]" if column in CSV_UNITS else column


def json_text(data: dict) -> str:
    """The JSON text of a check's results (indented, UTF-8 symbols kept, one trailing newline)."""
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


def write_results_json(data: dict, path: Path) -> Path:
    """Write ``results.json`` (the ``check --json`` text)."""
    path = Path(path)
    path.write_text(json_text(data), encoding="utf-8")
    return path


def write_results_csv(data: dict, path: Path, *, columns: list[str] | None = None) -> Path:
    """Write ``results.csv``: one row per record (per record pair of a cylinder), the ``columns`` (default
    :data:`CSV_COLUMNS`; SI units, named in the header)."""
    path = Path(path)
    columns = CSV_COLUMNS if columns is None else columns
    with open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow([csv_header(c) for c in columns])
        for row in data["records"]:
            demand = row.get("superstructure") or {}
            values = [demand.get(DEMAND_COLUMNS[c]) if c in DEMAND_COLUMNS else row.get(c) for c in columns]
            w.writerow(["" if v is None else v for v in values])
    return path
