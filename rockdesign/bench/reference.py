"""Reference solutions of the work-precision problems, evaluable at any time, with their error bounds.

Two kinds (``ReferenceSolution.kind``):

* ``closed-form`` (linearized SDOF problems): the exact event-driven solution of the linearized
  equations (SPEC §3.8, :mod:`rockdesign.planar.dynamics.linear_exact`).  Between events it is an explicit
  formula and every event is a bracketed root found to round-off, so its own error is round-off
  (~1e-15 rad).  As an independent check, our engine and scipy DOP853 at rtol 1e-13 are compared
  with it (``checks``).
* ``converged`` (exact equations; the 2DOF podium): our engine at rtol = 1e-13, atol = 1e-15.  Its
  error is bounded by comparing it with two other solutions: the same engine at rtol = 1e-12
  (self-convergence) and the independent scipy implementation (DOP853, rtol = 1e-13, atol = 1e-15,
  restarted at every event and sample; :mod:`rockdesign.bench.baseline`).  The stated bound per metric is
  the larger of the two differences.

Histories are evaluated at arbitrary times by re-running the kernel with those output times (its
dense output or closed form there), so no method's output is ever interpolated.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..planar.dynamics.accuracy import history_at
from ..planar.dynamics.simulate import simulate
from .baseline.scipy_engine import simulate_scipy
from ..planar.dynamics import metrics
from .problems import Problem

REFERENCE_RTOL = 1e-13
REFERENCE_ATOL = 1e-15
SELF_CHECK_RTOL = 1e-12


def engine_history_at(problem: Problem, times, *, model: str = "exact", rtol: float = REFERENCE_RTOL,
                      atol: float = REFERENCE_ATOL, scan_points: int = 8) -> np.ndarray:
    """θ(t) [rad] of our engine (or closed form) for ``problem`` at the given times [s]
    (:func:`rockdesign.planar.dynamics.accuracy.history_at` on the problem's system, motion and start)."""
    return history_at(problem.system, problem.motion, times, t_end=problem.t_end, structure=problem.structure,
                      theta0=problem.theta0, model=model, rtol=rtol, atol=atol, scan_points=scan_points)


@dataclass
class ReferenceSolution:
    """The reference of one problem.

    Attributes:
        kind: ``closed-form`` or ``converged``.
        how: how it is made (one sentence, for bench.json and the docs).
        model, rtol, atol: what :func:`engine_history_at` re-runs to evaluate θ at any time.
        theta_max: peak |θ| [rad]; impact_times [s]; overturn_mode; impacts.
        error_bound: estimated error of the reference per metric (``theta`` [rad], ``theta_max``
            [rad], ``impact_times`` [s]).
        checks: the comparisons behind the bound (name → metrics).
        seconds: wall time spent building the reference [s].
    """

    problem: Problem
    kind: str
    how: str
    model: str
    rtol: float
    atol: float
    theta_max: float
    impact_times: np.ndarray
    overturn_mode: str
    impacts: int
    error_bound: dict = field(default_factory=dict)
    checks: dict = field(default_factory=dict)
    seconds: float = 0.0

    def theta_at(self, times) -> np.ndarray:
        """θ_ref(t) [rad] at the given times [s]."""
        return engine_history_at(self.problem, times, model=self.model, rtol=self.rtol, atol=self.atol)

    def as_json(self) -> dict:
        return {"kind": self.kind, "how": self.how, "theta_max": self.theta_max, "impacts": self.impacts,
                "first_impact_times": [float(x) for x in self.impact_times[:metrics.IMPACTS_COMPARED]],
                "overturn_mode": self.overturn_mode, "error_bound": dict(self.error_bound),
                "checks": {k: dict(v) for k, v in self.checks.items()}, "seconds": self.seconds}


def _compare(ref: ReferenceSolution, t, theta, impact_times, theta_max, overturn_mode) -> dict:
    t = np.asarray(t, dtype=float)
    return {"theta": metrics.max_abs_difference(theta, ref.theta_at(t)),
            "theta_max": metrics.theta_max_error(theta_max, ref.theta_max),
            "impact_times": metrics.impact_time_error(impact_times, ref.impact_times, ref.problem.t_end),
            "overturn_agrees": metrics.overturn_agreement(overturn_mode, ref.overturn_mode)}


def build_reference(problem: Problem, independent_check: bool = True) -> ReferenceSolution:
    """Make the reference solution of ``problem`` and estimate its error (module docstring).

    Args:
        problem: the problem.
        independent_check: also run scipy DOP853 at rtol 1e-13 (the slow part; needed for the bound
            of ``converged`` references).
    """
    import time
    t0 = time.perf_counter()
    if problem.closed_form:
        r = simulate(problem.system, problem.motion, model="linear-exact", structure=problem.structure,
                     t_end=problem.t_end, theta0=problem.theta0)
        ref = ReferenceSolution(problem, "closed-form",
                                "closed-form solution of the linearized equations (docs/model.md §4): explicit formulas "
                                "between events, events as bracketed roots to round-off",
                                "linear-exact", REFERENCE_RTOL, REFERENCE_ATOL, float(r.theta_max),
                                r.impact_times, r.overturn_mode, int(r.impacts))
        ours = simulate(problem.system, problem.motion, model="linear", structure=problem.structure,
                        rtol=REFERENCE_RTOL, atol=REFERENCE_ATOL, t_end=problem.t_end, theta0=problem.theta0)
        ref.checks["rockdesign rtol=1e-13"] = _compare(ref, ours.t, ours.theta, ours.impact_times, ours.theta_max,
                                                      ours.overturn_mode)
        if independent_check:
            s = simulate_scipy(problem.system, problem.motion, method="DOP853", rtol=REFERENCE_RTOL,
                               atol=REFERENCE_ATOL, linear=True, linear_beta="exact", t_end=problem.t_end,
                               theta0=problem.theta0, record_every_step=True)
            ref.checks["scipy DOP853 rtol=1e-13"] = _compare(ref, s.t, s.theta, _impacts(s), s.theta_max,
                                                            s.overturn_mode)
        ref.error_bound = {"theta": 1e-15, "theta_max": 1e-15, "impact_times": 1e-15,
                           "note": "round-off of the closed form; the checks show other solvers converging to it"}
    else:
        model = "linear" if problem.equations == "linear" else "exact"
        r = simulate(problem.system, problem.motion, model=model, structure=problem.structure, rtol=REFERENCE_RTOL,
                     atol=REFERENCE_ATOL, t_end=problem.t_end, theta0=problem.theta0)
        ref = ReferenceSolution(problem, "converged",
                                "rockdesign engine at rtol = 1e-13, atol = 1e-15; error bounded by its distance "
                                "to itself at rtol = 1e-12 and to scipy DOP853 at rtol = 1e-13 (independent code)",
                                model, REFERENCE_RTOL, REFERENCE_ATOL, float(r.theta_max), r.impact_times,
                                r.overturn_mode, int(r.impacts))
        coarse = simulate(problem.system, problem.motion, model=model, structure=problem.structure,
                          rtol=SELF_CHECK_RTOL, atol=SELF_CHECK_RTOL * 1e-2, t_end=problem.t_end,
                          theta0=problem.theta0)
        ref.checks["rockdesign rtol=1e-12"] = _compare(ref, coarse.t, coarse.theta, coarse.impact_times,
                                                      coarse.theta_max, coarse.overturn_mode)
        if independent_check:
            s = simulate_scipy(problem.system, problem.motion, method="DOP853", rtol=REFERENCE_RTOL,
                               atol=REFERENCE_ATOL, linear=problem.equations == "linear", linear_beta="exact",
                               t_end=problem.t_end, theta0=problem.theta0, record_every_step=True)
            ref.checks["scipy DOP853 rtol=1e-13"] = _compare(ref, s.t, s.theta, _impacts(s), s.theta_max,
                                                            s.overturn_mode)
        ref.error_bound = {key: max(c[key] for c in ref.checks.values())
                           for key in ("theta", "theta_max", "impact_times")}
    ref.seconds = time.perf_counter() - t0
    return ref


def _impacts(result) -> np.ndarray:
    return np.array([e.t for e in result.events if e.kind == "impact"])
