"""The methods compared in the work-precision study, behind one calling convention.

* ``rockdesign`` — our event-driven engine (:func:`rockdesign.planar.dynamics.simulate.simulate`) solving the
  problem's equations (exact, or linearized for the linearized problems) with the stepper it picks per
  system and tolerance (``method="auto"``: DOP853 for the 2DOF podium at rtol < 5e-8, DP5(4) otherwise).
* ``rockdesign DP5(4)`` and ``rockdesign DOP853`` — the same engine with one stepper forced: the
  work-precision data that the automatic choice rests on.
* ``rockdesign linear-exact`` — our closed-form solution of the linearized SDOF equations (SPEC §3.8).
  It has no tolerance; on the exact-equation problems its error is the linearization (model) error.
* ``scipy RK45 | DOP853 | LSODA | Radau`` — ``scipy.integrate.solve_ivp`` with the same equations and
  events, restarted at every impact and record sample
  (:func:`rockdesign.bench.baseline.scipy_engine.simulate_scipy`): what a Python engineer would write.

Every method is run as ``method.run(problem, rtol, atol, detailed)`` and returns a :class:`RunOutput`.
``detailed`` asks scipy for every accepted step (for the error metrics; timed runs use the default
output: stretch ends and events).  Our engine always reports its output grid and every event.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..planar.dynamics.simulate import simulate
from .baseline.scipy_engine import simulate_scipy
from .problems import Problem

ATOL_OVER_RTOL = 1e-2
"""Every method runs at atol = 0.01 · rtol [rad, rad/s, m, m/s] (the engine's default ratio)."""
CLOSED_FORM_TOLERANCE = float(np.finfo(float).eps)
"""Tolerance recorded for the closed form: its roots are found to round-off (it has no tolerance)."""
SCIPY_METHODS = ("RK45", "DOP853", "LSODA", "Radau")


@dataclass
class RunOutput:
    """What one run of one method reports (SI units, radians).

    Attributes:
        t, theta: the points where the method reports θ [s, rad] (sorted; events included).
        impact_times: times of the impacts [s].
        theta_max: peak |θ| [rad] reported by the method.
        overturn_mode: ``none`` | ``exceeded`` (θ_max ≥ θc) | ``dynamic`` (|θ| reached π/2).
        impacts: number of impacts.
        nfev: right-hand-side evaluations.
        steps: accepted steps (our engine; −1 when the method does not report them).
        status: the method's final status text.
    """

    t: np.ndarray
    theta: np.ndarray
    impact_times: np.ndarray
    theta_max: float
    overturn_mode: str
    impacts: int
    nfev: int
    steps: int = -1
    status: str = "completed"
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Method:
    """A method of the study.

    Attributes:
        name: identifier used in bench.json and figures.
        family: ``rockdesign`` | ``closed-form`` | ``scipy``.
        solver: scipy method name (scipy family) or the rockdesign model.
        description: one line for the docs.
    """

    name: str
    family: str
    solver: str
    description: str

    @property
    def has_tolerance(self) -> bool:
        """False for the closed form (one point per problem, no sweep)."""
        return self.family != "closed-form"

    def applies(self, problem: Problem) -> bool:
        """Whether the method can solve ``problem`` (closed form: SDOF and exact-equation problems;
        on the linearized problems it is the reference itself)."""
        if self.family == "closed-form":
            return problem.equations == "exact" and problem.structure != "podium-2dof"
        return True

    def run(self, problem: Problem, rtol: float, atol: float | None = None, detailed: bool = True) -> RunOutput:
        """Solve ``problem`` at relative tolerance ``rtol`` (atol default 0.01·rtol)."""
        atol = rtol * ATOL_OVER_RTOL if atol is None else atol
        if self.family == "scipy":
            return _run_scipy(problem, self.solver, rtol, atol, detailed)
        model = "linear-exact" if self.family == "closed-form" else (
            "linear" if problem.equations == "linear" else "exact")
        return _run_engine(problem, model, rtol, atol, ENGINE_STEPPERS.get(self.solver, "auto"))


ENGINE_STEPPERS = {"auto-events": "auto", "dp54-events": "dp5", "dop853-events": "dop853"}
"""``Method.solver`` of the engine's methods → the ``method`` argument of ``simulate``."""

METHODS = (
    Method("rockdesign", "rockdesign", "auto-events",
           "rockdesign engine: numba DP5(4), or DOP853 for the 2DOF podium at rtol < 5e-8; dense-output event search, "
           "exact event refinement"),
    Method("rockdesign linear-exact", "closed-form", "linear-exact",
           "rockdesign closed form of the linearized SDOF equations (docs/model.md §4); no tolerance"),
    Method("rockdesign DP5(4)", "rockdesign", "dp54-events",
           "rockdesign engine with the Dormand–Prince 5(4) stepper forced (4th-order dense output)"),
    Method("rockdesign DOP853", "rockdesign", "dop853-events",
           "rockdesign engine with the DOP853 stepper forced (Hairer's 8(5,3), 7th-order dense output)"),
) + tuple(Method(f"scipy {m}", "scipy", m, f"scipy.integrate.solve_ivp(method='{m}'), restarted at events "
                                                 "and record samples") for m in SCIPY_METHODS)


def method(name: str) -> Method:
    """The :class:`Method` called ``name`` (e.g. ``"scipy DOP853"``)."""
    for m in METHODS:
        if m.name == name:
            return m
    raise KeyError(f"unknown method {name!r}; expected one of {[m.name for m in METHODS]}")


def _run_engine(problem: Problem, model: str, rtol: float, atol: float, stepper: str = "auto") -> RunOutput:
    r = simulate(problem.system, problem.motion, model=model, structure=problem.structure, rtol=rtol, atol=atol,
                 t_end=problem.t_end, theta0=problem.theta0, method=stepper)
    d = r.diagnostics
    return RunOutput(t=r.t, theta=r.theta, impact_times=r.impact_times, theta_max=r.theta_max,
                     overturn_mode=r.overturn_mode, impacts=r.impacts, nfev=int(d.get("function_evaluations", 0)),
                     steps=int(d.get("steps", -1)), status=r.status,
                     extra={"events": int(d.get("events", 0)), "rest_entries": int(d.get("rest_entries", 0)),
                            "rejected_steps": int(d.get("rejected_steps", 0))})


def _run_scipy(problem: Problem, solver: str, rtol: float, atol: float, detailed: bool) -> RunOutput:
    r = simulate_scipy(problem.system, problem.motion, method=solver, rtol=rtol, atol=atol,
                       linear=problem.equations == "linear", linear_beta="exact", t_end=problem.t_end,
                       theta0=problem.theta0, record_every_step=detailed)
    order = np.argsort(r.t, kind="stable")
    impacts = np.array([e.t for e in r.events if e.kind == "impact"])
    return RunOutput(t=r.t[order], theta=r.theta[order], impact_times=impacts, theta_max=float(r.theta_max),
                     overturn_mode=r.overturn_mode, impacts=int(r.n_impacts), nfev=int(r.nfev),
                     status="overturned" if r.dynamic else "completed",
                     extra={"solver_calls": int(r.n_solver_calls), "events": len(r.events)})


def is_finite_run(out: RunOutput) -> bool:
    """True when the run produced a usable history (no NaN in θ)."""
    return bool(out.t.size) and bool(np.all(np.isfinite(out.theta))) and math.isfinite(out.theta_max)
