"""The verification statement of the calculation report: the engine's error on a closed-form case.

The linearized SDOF equations have an exact event-driven solution (SPEC §3.8,
:mod:`rockdesign.planar.dynamics.linear_exact`).  The check runs the engine's integrator (the one that also
integrates the exact equations) on such a case at its own tolerance, and the report states its error
against the closed form: the largest |Δθ| over the history and the largest difference of the impact
times, measured by ``rockdesign.planar.dynamics.accuracy.engine_accuracy`` when the check runs (one
implementation for the benchmark and the check; results.json ``settings.engine_accuracy``).  The report
only words what the check recorded: it runs no analysis.
"""
from __future__ import annotations

import math


CASE = ("thesis Table 3.4 column B1 (2H = 3 m, tan α = 0.1, λ = 1/3), antisymmetric Ricker pulse "
        "a_p = 0.38 g, T_p = 0.95 s, t_m = 1.5 T_p, sampled at T_p/200, 10 s")
"""The closed-form case (description shown in the report)."""
T_END = 10.0
SAMPLES_PER_PERIOD = 200


BENCH_KEYS = {"max_abs_dtheta_rad": "theta_error", "theta_max_error_rad": "theta_max_error",
              "max_impact_time_error_s": "impact_time_error", "impacts_reference": "impacts",
              "impacts": "impacts_engine"}
"""``engine_accuracy`` keys → the report's keys."""


def normalise(statement: dict) -> dict:
    """An ``engine_accuracy`` statement with the report's keys (theta_error, impact_time_error, impacts...);
    run times and other machine-dependent entries are dropped (the report must be reproducible)."""
    if "theta_error" in statement:
        return dict(statement)
    out = {"case": statement.get("case", CASE), "rtol": statement.get("rtol"), "atol": statement.get("atol"),
           "reference": statement.get("reference", "closed-form solution of the linearized equations (docs/model.md §4)"),
           "source": statement.get("source", "rockdesign.planar.dynamics.accuracy.engine_accuracy")}
    for theirs, ours in BENCH_KEYS.items():
        if theirs in statement:
            out[ours] = statement[theirs]
    if "theta_error" in out:
        alpha = math.atan(0.1)
        if statement.get("theta_max_over_alpha") and statement.get("theta_max_rad"):
            alpha = statement["theta_max_rad"] / statement["theta_max_over_alpha"]
        out["theta_error_over_alpha"] = out["theta_error"] / alpha
    return out
