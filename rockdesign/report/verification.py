"""The verification statement of the calculation report: the engine's error on a closed-form case.

The linearized SDOF equations have an exact event-driven solution (SPEC §3.8,
:mod:`rockdesign.dynamics.linear_exact`).  The report runs the engine's integrator (the one that also
integrates the exact equations) on such a case at the tolerance of the check and states its error
against the closed form: the largest |Δθ| over the history and the largest difference of the impact
times.  ``rockdesign.bench.accuracy.engine_accuracy`` is used when it is available (one implementation
for the benchmark and the report); :func:`closed_form_accuracy` is the same measurement, kept as a
fallback.
"""
from __future__ import annotations

import functools
import math

import numpy as np

CASE = ("thesis Table 3.4 column B1 (2H = 3 m, tan α = 0.1, λ = 1/3), antisymmetric Ricker pulse "
        "a_p = 0.38 g, T_p = 0.95 s, t_m = 1.5 T_p, sampled at T_p/200, 10 s")
"""The closed-form case (description shown in the report)."""
T_END = 10.0
SAMPLES_PER_PERIOD = 200


def _bench_engine_accuracy():
    """``rockdesign.bench.accuracy.engine_accuracy`` if it is available, else None."""
    try:
        from ..bench.accuracy import engine_accuracy
    except Exception:  # a missing or half-written sibling module must not break the report
        return None
    return engine_accuracy


BENCH_KEYS = {"max_abs_dtheta_rad": "theta_error", "theta_max_error_rad": "theta_max_error",
              "max_impact_time_error_s": "impact_time_error", "impacts_reference": "impacts",
              "impacts": "impacts_engine"}
"""``engine_accuracy`` keys → the keys of :func:`closed_form_accuracy` (the report's)."""


def normalise(statement: dict) -> dict:
    """A statement of either implementation with the keys of :func:`closed_form_accuracy`; run times and
    other machine-dependent entries are dropped (the report must be reproducible)."""
    if "theta_error" in statement:
        return dict(statement)
    out = {"case": statement.get("case", CASE), "rtol": statement.get("rtol"), "atol": statement.get("atol"),
           "reference": statement.get("reference", "closed-form solution of the linearized equations (SPEC §3.8)"),
           "source": statement.get("source", "rockdesign.bench.accuracy.engine_accuracy")}
    for theirs, ours in BENCH_KEYS.items():
        if theirs in statement:
            out[ours] = statement[theirs]
    if "theta_error" in out:
        alpha = math.atan(0.1)
        if statement.get("theta_max_over_alpha") and statement.get("theta_max_rad"):
            alpha = statement["theta_max_rad"] / statement["theta_max_over_alpha"]
        out["theta_error_over_alpha"] = out["theta_error"] / alpha
    return out


def closed_form_accuracy(rtol: float, atol: float = 1e-12) -> dict:
    """Engine (DP5(4), linearized EOM) vs the closed-form solution on :data:`CASE` (SI).

    Args:
        rtol, atol: integrator tolerances [-], [rad, rad/s] (those of the check).

    Returns:
        dict with ``case``, ``rtol``, ``atol``, ``theta_error`` (max |Δθ| over the output times
        [rad]), ``theta_error_over_alpha`` [-], ``theta_max_error`` [rad], ``impact_time_error``
        (max difference of corresponding impact times [s]), ``impacts`` (closed form),
        ``impacts_engine``, ``reference`` and ``source``.
    """
    from ..dynamics.linear_exact import sampled_pulse
    from ..dynamics.simulate import simulate
    from ..motions.motion import pulse_motion
    from ..systems import Column, RockingSystem

    g = 9.81
    system = RockingSystem("B1", "column", Column(1.5, 0.15, 1000.0, 1.0 / 3.0), g=g)
    motion = sampled_pulse(pulse_motion("ricker-anti", 0.38 * g, 0.95), SAMPLES_PER_PERIOD)
    kw = dict(t_end=T_END, overturn="dynamic")
    ref = simulate(system, motion, model="linear-exact", **kw)
    eng = simulate(system, motion, model="linear", rtol=rtol, atol=atol, **kw)
    n = min(ref.t.size, eng.t.size)
    # both runs output at the record samples plus their own events: compare at the common sample times
    common, i_ref, i_eng = np.intersect1d(np.round(ref.t, 12), np.round(eng.t, 12), return_indices=True)
    if common.size:
        theta_error = float(np.max(np.abs(ref.theta[i_ref] - eng.theta[i_eng])))
    else:  # pragma: no cover
        theta_error = float(np.max(np.abs(ref.theta[:n] - eng.theta[:n])))
    ti_ref, ti_eng = ref.impact_times, eng.impact_times
    k = min(ti_ref.size, ti_eng.size)
    impact_error = float(np.max(np.abs(ti_ref[:k] - ti_eng[:k]))) if k else 0.0
    if ti_ref.size != ti_eng.size:
        impact_error = math.inf
    return {
        "case": CASE,
        "rtol": float(rtol),
        "atol": float(atol),
        "theta_error": theta_error,
        "theta_error_over_alpha": theta_error / ref.alpha,
        "theta_max_error": abs(eng.theta_max - ref.theta_max),
        "impact_time_error": impact_error,
        "impacts": int(ti_ref.size),
        "impacts_engine": int(ti_eng.size),
        "reference": "closed-form solution of the linearized equations (SPEC §3.8)",
        "source": "rockdesign.report.verification",
    }


@functools.lru_cache(maxsize=8)
def engine_accuracy_statement(rtol: float, atol: float = 1e-12) -> dict:
    """The verification statement at the check's tolerance (bench implementation if available)."""
    fn = _bench_engine_accuracy()
    if fn is not None:
        try:
            out = dict(fn(rtol, atol))
            out.setdefault("rtol", float(rtol))
            out.setdefault("source", f"{fn.__module__}.engine_accuracy")
            statement = normalise(out)
            if "theta_error" in statement and "impact_time_error" in statement:
                return statement
        except Exception:  # fall back to our own measurement
            pass
    return closed_form_accuracy(rtol, atol)
