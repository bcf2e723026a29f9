"""The columns of a planar check's results.csv (CONTRACT §4): one row per record, SI units in the header
(written by :func:`rockdesign.report.results.write_results_csv`, declared through the planar kind)."""
from __future__ import annotations

CSV_COLUMNS = ("id", "suite", "event", "station", "rsn", "component", "scale", "pga", "sd_max", "sd_max_period",
               "polyakov_ratio", "theta_max_over_alpha", "theta_max_over_theta_c", "u_B_max", "u_B_max_over_2B",
               "impacts", "uplift_time", "overturned", "overturn_mode", "class", "overturn_scale", "polyakov_scale",
               "ensemble_overturn_fraction", "outcome_robust", "status", "analysis_failed",
               "superstructure_acceleration_max", "superstructure_shear_coefficient_max", "superstructure_drift_max",
               "fixed_base_acceleration_max", "force_ratio")

CSV_NESTED = {"superstructure_acceleration_max": ("superstructure", "acceleration_max"),
              "superstructure_shear_coefficient_max": ("superstructure", "shear_coefficient_max"),
              "superstructure_drift_max": ("superstructure", "drift_max"),
              "fixed_base_acceleration_max": ("superstructure", "fixed_base_acceleration_max"),
              "force_ratio": ("superstructure", "force_ratio")}
"""results.csv columns read from a record's ``superstructure`` dict (CONTRACT §6.2; empty where it is null)."""

CSV_UNITS = {"scale": "-", "pga": "m/s^2", "sd_max": "m", "sd_max_period": "s", "polyakov_ratio": "-",
             "theta_max_over_alpha": "-", "theta_max_over_theta_c": "-", "u_B_max": "m", "u_B_max_over_2B": "-",
             "uplift_time": "s", "overturn_scale": "-", "polyakov_scale": "-", "ensemble_overturn_fraction": "-",
             "superstructure_acceleration_max": "m/s^2", "superstructure_shear_coefficient_max": "-",
             "superstructure_drift_max": "m", "fixed_base_acceleration_max": "m/s^2", "force_ratio": "-"}
"""Units of the results.csv columns (header "pga [m/s^2]"); the others are counts, ids or words."""
