"""The engine's accuracy on a closed-form case, for the appendix of the check report (issue item 4).

:func:`engine_accuracy` runs our integrator on a fixed linearized problem whose exact solution is
known (SPEC §3.8) and returns its errors at the requested tolerance: the report can then state
"at rtol = …, θ(t) agrees with the closed form to … rad and the impact times to … s".
"""
from __future__ import annotations

import math
import time

from ..dynamics.linear_exact import sampled_pulse
from ..dynamics.simulate import DEFAULT_ATOL, simulate
from ..motions.motion import pulse_motion
from ..systems import Column, RockingSystem
from . import metrics
from .problems import G, Problem
from .reference import engine_history_at

ACCURACY_CASE = ("thesis Table 3.4 B1 (2H = 3 m, tan α = 0.1, λ = 1/3) under the antisymmetric Ricker pulse "
                 "(a_p = 0.38 g, T_p = 0.95 s, t_m = 1.5 T_p) sampled at T_p/200, linearized equations (Eq 3.15), "
                 "10 s")


def accuracy_problem() -> Problem:
    """The fixed closed-form case of :func:`engine_accuracy` (see :data:`ACCURACY_CASE`)."""
    system = RockingSystem("B1", "column", Column(1.5, 0.15, 1000.0, 1 / 3), g=G)
    motion = sampled_pulse(pulse_motion("ricker-anti", 0.38 * G, 0.95), 200)
    return Problem("accuracy-b1-ricker", "table-3.4-B1", system, "block", motion, "linear", 10.0, 0.0, ACCURACY_CASE)


def engine_accuracy(rtol: float = 1e-10, atol: float | None = None) -> dict:
    """Errors of our engine against the closed-form solution at tolerance ``rtol``.

    The engine (``model="linear"``, the same integrator and events as the exact model) and the
    closed form (``model="linear-exact"``) solve :func:`accuracy_problem`; the closed form is
    evaluated at exactly the times the engine reports (its output grid and every event).

    Args:
        rtol: relative tolerance of the integrator (the project's ``[analysis] rtol``).
        atol: absolute tolerance [rad, rad/s]; default the engine's (1e-12).

    Returns:
        dict with ``case`` (text), ``rtol``, ``atol``, ``max_abs_dtheta_rad`` (max |θ − θ_exact| over
        the history [rad]), ``theta_max_error_rad`` [rad], ``max_impact_time_error_s`` (max over all
        impacts [s]), ``impacts`` and ``impacts_reference`` (counts), ``theta_max_rad``,
        ``theta_max_over_alpha``, ``reference`` (text), ``seconds`` (engine run time).
    """
    atol = DEFAULT_ATOL if atol is None else float(atol)
    prob = accuracy_problem()
    t0 = time.perf_counter()
    run = simulate(prob.system, prob.motion, model="linear", rtol=rtol, atol=atol, t_end=prob.t_end)
    seconds = time.perf_counter() - t0
    exact = simulate(prob.system, prob.motion, model="linear-exact", t_end=prob.t_end)
    theta_exact = engine_history_at(prob, run.t, model="linear-exact")
    n_ref = exact.impacts
    return {
        "case": ACCURACY_CASE,
        "reference": "closed-form solution of the linearized equations (docs/model.md §4), events to round-off",
        "rtol": float(rtol), "atol": atol,
        "max_abs_dtheta_rad": metrics.max_abs_difference(run.theta, theta_exact),
        "theta_max_error_rad": metrics.theta_max_error(run.theta_max, exact.theta_max),
        "max_impact_time_error_s": metrics.impact_time_error(run.impact_times, exact.impact_times, prob.t_end,
                                                             count=max(n_ref, 1)),
        "impacts": int(run.impacts), "impacts_reference": int(n_ref),
        "theta_max_rad": float(exact.theta_max),
        "theta_max_over_alpha": float(exact.theta_max / math.atan(0.1)),
        "seconds": seconds,
        "status": run.status,
    }


def accuracy_sentence(acc: dict) -> str:
    """One sentence for the report appendix from an :func:`engine_accuracy` result."""
    return (f"Engine accuracy at the tolerance used (rtol = {acc['rtol']:.0e}, atol = {acc['atol']:.0e}): on "
            f"{acc['case']}, the integrator reproduces the closed-form solution (docs/model.md §4) to "
            f"{acc['max_abs_dtheta_rad']:.1e} rad in θ(t) over the whole history, "
            f"{acc['theta_max_error_rad']:.1e} rad "
            f"in θ_max and {acc['max_impact_time_error_s']:.1e} s in all {acc['impacts_reference']} impact times.")
