"""The work-precision runner: every method over a tolerance sweep on every problem (bench.json).

For each problem: build the reference (:mod:`rockdesign.bench.reference`); for each method and
tolerance: one untimed run (warm-up, and the run whose output is scored), then timed runs of the
same call, reporting the median (:mod:`rockdesign.bench.timing`).  A scored run that alone takes
longer than the timing budget (quick 0.4 s, full 3 s) is not repeated: its own time is the point's
time (``repeats`` = 1; everything it needs was loaded by then).  scipy is asked for every accepted
step in the scored run of pulse and free-vibration problems (it otherwise reports only events);
records are scored on the default output (every sample and event), like our engine.

A method that raises is recorded under ``failures`` with the message (LSODA's event location
does, see docs/stability.md); it is not a point of the chart.
"""
from __future__ import annotations

import math
import time
from typing import Callable

import numpy as np

from ..planar.dynamics import metrics
from .methods import ATOL_OVER_RTOL, CLOSED_FORM_TOLERANCE, METHODS, Method, RunOutput, is_finite_run
from .problems import Problem, make_problem, problem_set
from .reference import ReferenceSolution, build_reference
from .timing import FULL, QUICK, TimingPolicy, machine_info, time_call


TOLERANCES_FULL = tuple(10.0 ** -k for k in range(3, 13))
"""The sweep of the full study: rtol = 1e-3 … 1e-12 (atol = 0.01 rtol)."""
TOLERANCES_QUICK = (1e-3, 1e-6, 1e-9)
ACCURACY_TARGETS = (1e-6, 1e-9)
"""Targets [rad] of the "cost at equal accuracy" summary (on error_theta)."""
HISTORY_PROBLEM = "record-30s/housner-block"
"""Problem whose error-versus-time curves are kept for the thesis Fig B.3 analogue."""
HISTORY_TOLERANCES = (1e-6, 1e-9, 1e-12)


def warm_up() -> float:
    """Load/compile every numba kernel the study uses (cached on disk); returns the seconds spent."""
    t0 = time.perf_counter()
    for excitation, system in (("ricker-anti", "housner-block"), ("ricker-anti", "curved-block"),
                               ("free-vibration", "podium-2dof")):
        for equations in ("exact", "linear"):
            if system == "podium-2dof" and equations == "linear":
                continue
            p = make_problem(excitation, system, equations)
            for m in METHODS[:2]:
                if m.applies(p):
                    m.run(p, 1e-6)
    from .reference import engine_history_at
    p = make_problem("ricker-anti", "housner-block", "exact")
    engine_history_at(p, np.linspace(0.0, 1.0, 5))
    engine_history_at(p, np.linspace(0.0, 1.0, 5), model="linear-exact")
    return time.perf_counter() - t0


def score(out: RunOutput, ref: ReferenceSolution) -> dict:
    """The CONTRACT §4 error keys (plus overturning agreement) of one run against the reference."""
    return {"error_theta": metrics.max_abs_difference(out.theta, ref.theta_at(out.t)),
            "error_theta_max": metrics.theta_max_error(out.theta_max, ref.theta_max),
            "error_impact_times": metrics.impact_time_error(out.impact_times, ref.impact_times, ref.problem.t_end),
            "overturn_agrees": metrics.overturn_agreement(out.overturn_mode, ref.overturn_mode)}


def run_point(method: Method, problem: Problem, ref: ReferenceSolution, rtol: float,
              policy: TimingPolicy) -> dict:
    """One point of a work-precision line: scored run, then the median of timed runs.

    Raises whatever the method raises (the caller records failures).
    """
    atol = rtol * ATOL_OVER_RTOL
    detailed = method.family == "scipy" and not problem.motion.is_record
    t0 = time.perf_counter()
    out = method.run(problem, rtol, atol, detailed=detailed)
    first = time.perf_counter() - t0
    errors = score(out, ref)
    if not detailed and first > policy.budget:
        # a run longer than the whole budget is timed once: the scored run is that timing (everything
        # it needs is loaded; warm-up effects are below a millisecond)
        seconds, repeats = first, 1
    else:
        if detailed:
            method.run(problem, rtol, atol, detailed=False)   # warm the timed call path too
        seconds, repeats, _ = time_call(lambda: method.run(problem, rtol, atol, detailed=False), policy)
    point = {"tolerance": rtol if method.has_tolerance else CLOSED_FORM_TOLERANCE,
             "atol": atol if method.has_tolerance else None, "seconds": seconds, "repeats": repeats}
    point.update(errors)
    point.update({"overturn_mode": out.overturn_mode, "impacts": out.impacts, "nfev": out.nfev,
                  "steps": out.steps, "status": out.status, "finite": is_finite_run(out)})
    return point


def run_problem(problem: Problem, methods=METHODS, tolerances=TOLERANCES_FULL, policy: TimingPolicy = FULL,
                progress: Callable[[str], None] | None = None, histories: dict | None = None) -> dict:
    """The bench.json entry of one problem (reference, methods with their points and failures).

    Args:
        problem: the problem.
        methods: :class:`Method` objects to run (those that do not apply are skipped).
        tolerances: rtol sweep (atol = 0.01 rtol).
        policy: timing policy.
        progress: optional callback receiving one line per point.
        histories: if given, error-versus-time curves of :data:`HISTORY_PROBLEM` are stored in it,
            keyed by (method name, rtol).
    """
    say = progress or (lambda s: None)
    ref = build_reference(problem)
    say(f"{problem.key}: reference ({ref.kind}) θ_max = {ref.theta_max:.6g} rad, {ref.impacts} impacts, "
        f"bound {ref.error_bound.get('theta', math.nan):.1e} rad, {ref.seconds:.1f} s")
    entry = {"name": problem.name, "system": problem.system_name, "equations": problem.equations,
             "description": problem.description, "t_end": problem.t_end, "structure": problem.structure,
             "reference": ref.as_json(), "methods": []}
    keep = histories is not None and problem.key == HISTORY_PROBLEM
    history_tolerances = set(tolerances) if len(tolerances) <= 3 else set(HISTORY_TOLERANCES)
    for m in methods:
        if not m.applies(problem):
            continue
        item = {"name": m.name, "family": m.family, "description": m.description, "points": [], "failures": []}
        for rtol in (tolerances if m.has_tolerance else (CLOSED_FORM_TOLERANCE,)):
            try:
                point = run_point(m, problem, ref, rtol, policy)
            except Exception as exc:  # a solver crash is a result of the study, not an error of the bench
                item["failures"].append({"tolerance": rtol, "error": f"{type(exc).__name__}: {exc}"})
                say(f"  {m.name:24s} rtol={rtol:.0e}  FAILED {type(exc).__name__}: {exc}")
                continue
            item["points"].append(point)
            say(f"  {m.name:24s} rtol={rtol:.0e}  {point['seconds'] * 1e3:9.2f} ms  "
                f"err θ {point['error_theta']:.2e}  θmax {point['error_theta_max']:.2e}  "
                f"t_imp {point['error_impact_times']:.2e}")
            if keep and (rtol in history_tolerances or not m.has_tolerance):
                out = m.run(problem, rtol, detailed=m.family == "scipy")
                t, err = metrics.error_history(out.t, out.theta, ref.theta_at(out.t))
                histories[(m.name, rtol)] = (t, err)
        entry["methods"].append(item)
    entry["summary"] = problem_summary(entry)
    return entry


def problem_summary(entry: dict) -> dict:
    """Cost at equal accuracy: per target [rad], each method's cheapest time reaching error_theta ≤ target,
    and its ratio to rockdesign's."""
    out = {}
    for target in ACCURACY_TARGETS:
        costs = {m["name"]: metrics.cost_at_accuracy(m["points"], target) for m in entry["methods"]}
        ours = costs.get("rockdesign")
        out[f"seconds_to_error_theta_{target:.0e}"] = costs
        out[f"ratio_to_rockdesign_{target:.0e}"] = {
            k: (v / ours if (v is not None and ours) else None) for k, v in costs.items()}
    return out


def run_study(quick: bool = False, problems: list[Problem] | None = None, methods=METHODS,
              tolerances=None, policy: TimingPolicy | None = None,
              progress: Callable[[str], None] | None = None, histories: dict | None = None,
              step: Callable[[int, int], None] | None = None) -> dict:
    """Run the work-precision study and return the bench.json object (CONTRACT §4, extra keys added).

    Args:
        quick: 3 tolerances (1e-3, 1e-6, 1e-9), fewer repeats, 12-s record (CI scale).
        problems: problems to run (default: :func:`~rockdesign.bench.problems.problem_set`).
        methods: methods to run (default: all).
        tolerances: rtol sweep (default 1e-3…1e-12, quick: 1e-3, 1e-6, 1e-9).
        policy: timing policy (default FULL, quick: QUICK).
        progress: callback for progress lines.
        histories: dict to receive error-versus-time curves (see :func:`run_problem`).
        step: ``step(done, total)`` after each problem (the CLI's progress bar).
    """
    t0 = time.perf_counter()
    tolerances = tolerances or (TOLERANCES_QUICK if quick else TOLERANCES_FULL)
    policy = policy or (QUICK if quick else FULL)
    problems = problems if problems is not None else problem_set(quick=quick)
    warm = warm_up()
    study = {"machine": machine_info(), "quick": quick, "tolerances": list(tolerances),
             "atol_over_rtol": ATOL_OVER_RTOL,
             "timing": {"statistic": "median", "max_repeats": policy.max_repeats,
                        "min_repeats": policy.min_repeats, "budget_seconds": policy.budget,
                        "warm_up": "one untimed run of the same call before timing; numba kernels loaded "
                                   f"once per process ({warm:.1f} s)"},
             "metrics": {"error_theta": "max |θ − θ_ref| [rad] over the points the method reports (events "
                                        "included)",
                         "error_theta_max": "|θ_max − θ_max,ref| [rad]",
                         "error_impact_times": f"max |t_k − t_k,ref| [s] over the first {metrics.IMPACTS_COMPARED} "
                                               "impacts (a missed impact counts at t_end)",
                         "overturn_agrees": "same overturning mode as the reference (none/exceeded/dynamic)",
                         "seconds": "median wall time of the public call [s]"},
             "methods": [{"name": m.name, "family": m.family, "description": m.description} for m in methods],
             "problems": []}
    for k, p in enumerate(problems):
        study["problems"].append(run_problem(p, methods, tolerances, policy, progress, histories))
        if step is not None:
            step(k + 1, len(problems))
    study["seconds"] = time.perf_counter() - t0
    return study


def highlights(study: dict) -> list[dict]:
    """One row per problem: rockdesign's error at rtol 1e-10 (or nearest), its time, and the scipy
    cost ratios at equal accuracy (:data:`ACCURACY_TARGETS`)."""
    rows = []
    for prob in study["problems"]:
        ours = next((m for m in prob["methods"] if m["name"] == "rockdesign"), None)
        if ours is None or not ours["points"]:
            continue
        pt = min(ours["points"], key=lambda q: abs(math.log10(q["tolerance"]) + 10.0))
        row = {"problem": prob["name"], "system": prob["system"], "rtol": pt["tolerance"],
               "error_theta": pt["error_theta"], "error_impact_times": pt["error_impact_times"],
               "ms": pt["seconds"] * 1e3, "reference_bound": prob["reference"]["error_bound"].get("theta")}
        for target in ACCURACY_TARGETS:
            ratios = prob["summary"][f"ratio_to_rockdesign_{target:.0e}"]
            row[f"scipy_best_ratio_{target:.0e}"] = min(
                (v for k, v in ratios.items() if k.startswith("scipy") and v is not None), default=None)
        failures = sum(len(m["failures"]) for m in prob["methods"])
        row["failures"] = failures
        rows.append(row)
    return rows


