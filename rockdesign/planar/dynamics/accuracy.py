"""The engine's accuracy on a closed-form case, for the appendix of the check report (issue item 4).

:func:`engine_accuracy` runs our integrator on a fixed linearized problem whose exact solution is
known (SPEC §3.8) and returns its errors at the requested tolerance: the report can then state
"at rtol = …, θ(t) agrees with the closed form to … rad and the impact times to … s".
"""
from __future__ import annotations

import math
import time

import numpy as np

from ...motions.motion import pulse_motion
from ..system import Column, RockingSystem
from . import metrics
from .layout import O_T_END
from .linear_exact import integrate_linear_exact, sampled_pulse
from .model import ModelChoice, resolve_structure, system_parameters
from .batch import batch_options, run_history
from .simulate import DEFAULT_ATOL, initial_state, simulate

G = 9.81
ACCURACY_T_END = 10.0

ACCURACY_CASE = ("thesis Table 3.4 B1 (2H = 3 m, tan α = 0.1, λ = 1/3) under the antisymmetric Ricker pulse "
                 "(a_p = 0.38 g, T_p = 0.95 s, t_m = 1.5 T_p) sampled at T_p/200, linearized equations (Eq 3.15), "
                 "10 s")


def accuracy_problem():
    """The fixed closed-form case of :func:`engine_accuracy` (see :data:`ACCURACY_CASE`): (system, motion)."""
    system = RockingSystem("B1", "column", Column(1.5, 0.15, 1000.0, 1 / 3), g=G)
    motion = sampled_pulse(pulse_motion("ricker-anti", 0.38 * G, 0.95), 200)
    return system, motion


def history_at(system, motion, times, *, t_end: float, structure: str = "auto", theta0: float = 0.0,
               model: str = "exact", rtol: float = 1e-13, atol: float = 1e-15, scan_points: int = 8) -> np.ndarray:
    """θ(t) [rad] of our engine (or the closed form, Eq 3.15 solved exactly) at the given times [s].

    Sets up the kernel exactly as :func:`rockdesign.planar.dynamics.simulate.simulate` does and passes
    ``times`` as output times, so the values come from the integrator's dense output (``exact``,
    ``linear``) or the closed form (``linear-exact``) at those very instants — never interpolated.

    Args:
        times: any times [s] in [0, t_end] (unsorted, duplicates allowed).
        structure: ``auto`` or a structural model name; theta0: initial tilt [rad].
        model: ``exact`` | ``linear`` | ``linear-exact``.
        rtol, atol: integrator tolerances (ignored by the closed form).

    Returns:
        θ at ``times`` (same shape).
    """
    times = np.asarray(times, dtype=np.float64)
    t_sorted, inverse = np.unique(times, return_inverse=True)
    structure = resolve_structure(system, structure)
    equations = "linear" if model in ("linear", "linear-exact") else "exact"
    sp = system_parameters(system, ModelChoice(structure, equations))
    y0, side0 = initial_state(system, structure, theta0)
    t_out = np.ascontiguousarray(np.clip(t_sorted, 0.0, t_end))
    out_y = np.zeros((t_out.size, 4))
    cap = 1
    ev_t, ev_kind, ev_y = np.zeros(cap), np.zeros(cap, dtype=np.int64), np.zeros((cap, 4))
    if model == "linear-exact":
        motion = sampled_pulse(motion)
        integrate_linear_exact(sp, motion.kind, motion.params, motion.samples, y0, side0, 0.0, t_end,
                               t_out, out_y, ev_t, ev_kind, ev_y, 1_000_000, False, False)
    else:
        opts = batch_options(rtol, atol, energy_stop=False, max_steps=50_000_000, scan_points=scan_points)
        opts[O_T_END] = t_end
        run_history(sp, motion.kind, motion.params, motion.samples, y0, side0, opts, t_out, out_y,
                    ev_t, ev_kind, ev_y)
    return out_y[:, 0][inverse].reshape(times.shape)


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
    system, motion = accuracy_problem()
    t_end = ACCURACY_T_END
    t0 = time.perf_counter()
    run = simulate(system, motion, model="linear", rtol=rtol, atol=atol, t_end=t_end)
    seconds = time.perf_counter() - t0
    exact = simulate(system, motion, model="linear-exact", t_end=t_end)
    theta_exact = history_at(system, motion, run.t, t_end=t_end, structure="block", model="linear-exact")
    n_ref = exact.impacts
    return {
        "case": ACCURACY_CASE,
        "reference": "closed-form solution of the linearized equations (docs/model.md §4), events to round-off",
        "rtol": float(rtol), "atol": atol,
        "max_abs_dtheta_rad": metrics.max_abs_difference(run.theta, theta_exact),
        "theta_max_error_rad": metrics.theta_max_error(run.theta_max, exact.theta_max),
        "max_impact_time_error_s": metrics.impact_time_error(run.impact_times, exact.impact_times, t_end,
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
