"""``simulate(system, motion, ...)``: one nonlinear time-history analysis (the engine's public API)."""
from __future__ import annotations

import math

import numpy as np

from ..design.geometry import displacement_capacity, rocking_geometry, slenderness_angle
from ...errors import ModelError
from ...motions.excitation import EXC_NONE
from ...motions.motion import GroundMotion, no_motion
from ..system import RockingSystem
from .layout import (D_EVENTS, D_EVENTS_STORED, D_NFEV, D_REFINE, D_REJECTED, D_REST, D_STATUS, D_STEPS, EVENT_NAMES,
                     O_T_END, STATUS_NAMES, S_DRIFT_MAX, S_IMPACTS, S_THETA_MAX, S_T_END, S_T_THETA_MAX, S_T_UPLIFT,
                     S_UB_MAX, S_UPLIFT_TIME, S_FS_MAX, S_T_FS_MAX, S_CAP_ACC_MAX, S_CAP_DV_MAX)
from .model import REST_VELOCITY, ModelChoice, resolve_structure, system_parameters
from .eom import P_OMEGA, P_THETA_C, P_TWO_DOF
from .overturning import classify
from .response import Event, Response, SolverStats
from ..design.quantities import RIGID_SUPERSTRUCTURE_RATIO

DEFAULT_RTOL = 1e-10
"""Default relative tolerance of the integrator (CONTRACT §1 ``[analysis] rtol``)."""
DEFAULT_ATOL = 1e-12
"""Default absolute tolerance [rad, rad/s, m, m/s]."""
FREE_VIBRATION = 10.0
"""Free-vibration time [s] simulated after the excitation ends (unless at rest earlier)."""
MODELS = ("auto", "exact", "linear", "linear-exact")


def simulate(system: RockingSystem, motion: GroundMotion | None = None, *, model: str = "auto",
             structure: str = "auto", rtol: float = DEFAULT_RTOL, atol: float = DEFAULT_ATOL,
             t_end: float | None = None, theta0: float = 0.0, thetadot0: float = 0.0,
             overturn: str = "static", rest_velocity: float = REST_VELOCITY, output_dt: float | None = None,
             energy_stop: bool = False, stop_at_capacity: bool = False, max_steps: int = 20_000_000,
             scan_points: int = 8, max_events: int = 1_000_000, event_capacity: int = 100_000,
             record_history: bool = True, rigid_ratio: float = RIGID_SUPERSTRUCTURE_RATIO, method: str = "auto") -> Response:
    """Time-history response of ``system`` to ``motion`` (SPEC §3).

    Args:
        system: the rocking system (SI).
        motion: ground acceleration; None for free vibration (give ``theta0``/``thetadot0``).
        model: ``exact`` (nonlinear EOM), ``linear`` (linearized EOM, same integrator),
            ``linear-exact`` (closed-form solution of the linearized SDOF equations, SPEC §3.8) or
            ``auto`` (exact equations; the check's model selection decides more).
        structure: ``auto`` | ``block`` | ``frame`` | ``rigid-superstructure`` | ``podium-2dof``.
        rtol, atol: integrator tolerances (defaults 1e-10 and 1e-12).
        t_end: end time [s]; default: excitation end + 10 s of free vibration.
        theta0, thetadot0: initial tilt [rad] and rate [rad/s].
        overturn: ``static`` (θ_max ≥ θc counts as overturning) or ``dynamic`` (|θ| = π/2).
        rest_velocity: |θ̇⁺| [rad/s] below which an impact ends in rest (SPEC §3.6).
        output_dt: output interval [s] for pulses (records output at their samples).
        energy_stop: stop once the remaining energy cannot raise θ_max (docs/early_termination.md).
        stop_at_capacity: stop when |θ| first reaches θc.
        method: Runge–Kutta pair — ``auto`` (DOP853 for the 2DOF podium at rtol < 5e-8, DP5(4) otherwise; chosen by
            the work-precision data, docs/engine.md), ``dp5`` or ``dop853``.
    """
    motion = motion if motion is not None else no_motion()
    structure, t_end = check_request(system, motion, model=model, structure=structure, t_end=t_end, overturn=overturn,
                                     output_dt=output_dt, record_history=record_history, rigid_ratio=rigid_ratio)
    equations = "linear" if model in ("linear", "linear-exact") else "exact"
    choice = ModelChoice(structure, equations)
    sp = system_parameters(system, choice, rest_velocity=rest_velocity)
    t_out = _output_times(motion, t_end, output_dt) if record_history else np.zeros(0)
    y0, side0 = initial_state(system, structure, theta0, thetadot0)
    if model == "linear-exact":
        from .linear_exact import integrate_linear_exact, sampled_pulse
        motion = sampled_pulse(motion)
        out_y = np.zeros((t_out.size, 4))
        ev_t, ev_kind, ev_y = _event_buffers(event_capacity)
        summary, diag, n_written = integrate_linear_exact(sp, motion.kind, motion.params, motion.samples, y0,
                                                          side0, 0.0, t_end, t_out, out_y, ev_t, ev_kind, ev_y,
                                                          max_events, stop_at_capacity, energy_stop)
    else:
        from .batch import batch_options, run_history
        opts = batch_options(rtol, atol, energy_stop=energy_stop, stop_at_capacity=stop_at_capacity,
                             max_steps=max_steps, max_events=max_events, scan_points=scan_points, method=method)
        opts[O_T_END] = t_end
        out_y = np.zeros((t_out.size, 4))
        ev_t, ev_kind, ev_y = _event_buffers(event_capacity)
        summary, diag, n_written = run_history(sp, motion.kind, motion.params, motion.samples, y0, side0, opts,
                                               t_out, out_y, ev_t, ev_kind, ev_y)
    label = f"{structure}/{model if model != 'auto' else 'exact'}"
    response = _build_response(system, motion, sp, model, label, summary, diag, t_out[:n_written], out_y[:n_written],
                           ev_t, ev_kind, ev_y, overturn)
    if model == "linear-exact" and "sampled_dt" in motion.meta:
        response.diagnostics["input"] = (f"analytic pulse sampled every {motion.meta['sampled_dt']:.3g} s (piecewise "
                                         "linear; see rockdesign.planar.dynamics.linear_exact.PULSE_SAMPLES_PER_PERIOD)")
    return response


def _event_buffers(capacity: int):
    # uninitialised: the integrator writes the rows it reports (diag[D_EVENTS_STORED]), nothing else is read
    return np.empty(capacity), np.empty(capacity, dtype=np.int64), np.empty((capacity, 4))


BYTES_PER_OUTPUT_SAMPLE = 8 * 24
"""Memory [bytes] per output time of a history: the integrator's buffers (t, 4 states) and the
Response's arrays (t, θ, θ̇, u_B, u_T, u_T − u_B, ü_g) with their temporary copies, 8-byte floats."""
MEMORY_FRACTION = 0.5
"""A history may use at most this fraction of the machine's physical memory ..."""
MEMORY_CAP = 4e9
"""... and at most this many bytes (a 60-s record needs ~2 MB, a 1-s pulse with 10 s of free
vibration at T_p/200 ~ 0.4 MB)."""


def _output_dt(motion: GroundMotion, output_dt: float | None) -> float:
    if motion.is_record and output_dt is None:
        return motion.dt
    return output_dt if output_dt is not None else (min(0.01, motion.params[1] / 200.0)
                                                    if motion.kind not in (0, 7) else 0.01)


def _physical_memory() -> float:
    try:
        import os
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):  # pragma: no cover - non-POSIX
        return 8e9


def check_request(system: RockingSystem, motion: GroundMotion, *, model: str = "auto", structure: str = "auto",
                  t_end: float | None = None, overturn: str = "static", output_dt: float | None = None,
                  record_history: bool = True, rigid_ratio: float = RIGID_SUPERSTRUCTURE_RATIO) -> tuple[str, float]:
    """Validate a :func:`simulate` request (same arguments) without analysing anything.

    No numba kernel runs, so the CLI reports bad input *before* a first run compiles the engine
    (≈ 30 s) instead of after.  Returns (the resolved structure, the end time [s]); raises
    :class:`~rockdesign.errors.ModelError` naming the key, what was expected and what was found.
    """
    if model not in MODELS:
        raise ModelError("unknown model", key="model", expected=" | ".join(MODELS), found=f"'{model}'")
    if overturn not in ("static", "dynamic"):
        raise ModelError("unknown overturning criterion", key="overturn", expected="static | dynamic",
                         found=f"'{overturn}'")
    structure = resolve_structure(system, structure, rigid_ratio)
    if t_end is None:
        t_end = motion.duration + FREE_VIBRATION
    if not (math.isfinite(t_end) and t_end > 0.0):
        raise ModelError("invalid end time", key="t_end", expected="a finite time > 0 s", found=repr(t_end))
    if record_history:
        check_memory(motion, t_end, output_dt)
    if model == "linear-exact" and system.has_elastic_superstructure and structure == "podium-2dof":
        raise ModelError("the closed-form model solves SDOF systems only", key="model",
                         expected="exact or linear for the 2DOF podium (or the rigid-superstructure model)",
                         found="'linear-exact'")
    return structure, t_end


def check_memory(motion: GroundMotion, t_end: float, output_dt: float | None = None) -> float:
    """Estimated memory [bytes] of a time history; raises ModelError (before allocating anything)
    when it exceeds :data:`MEMORY_FRACTION` of the physical memory (e.g. a pulse with T_p = 1e-6 s, whose
    output interval is T_p/200, or ``--t-end 1e7``)."""
    dt = _output_dt(motion, output_dt)
    n = t_end / dt + 2.0
    need = n * BYTES_PER_OUTPUT_SAMPLE
    avail = min(MEMORY_CAP, MEMORY_FRACTION * _physical_memory())
    if not need <= avail:
        raise ModelError("the time history would need too much memory",
                         expected=f"at most {avail / 1e9:.3g} GB: a shorter end time (t_end) or a longer pulse "
                                  "period (the output interval is T_p/200)",
                         found=f"{n:.3g} output times (t_end = {t_end:g} s every {dt:.3g} s) ≈ {need / 1e9:.3g} GB")
    return need


def _output_times(motion: GroundMotion, t_end: float, output_dt: float | None) -> np.ndarray:
    dt = _output_dt(motion, output_dt)
    n = int(math.floor(t_end / dt + 1e-9)) + 1
    t = np.arange(n) * dt
    if t[-1] < t_end - 1e-12:
        t = np.append(t, t_end)
    return t


def initial_state(system: RockingSystem, structure: str, theta0: float = 0.0,
                  thetadot0: float = 0.0) -> tuple[np.ndarray, float]:
    """(y0 = (θ, θ̇, u_T, u̇_T), side) at the start of a run from tilt θ0 [rad] and rate θ̇0 [rad/s]: a
    tilted 2DOF podium released from rest has its superstructure undeformed on the tilted frame."""
    y0 = np.array([theta0, thetadot0, 0.0, 0.0])
    if theta0 != 0.0 and structure == "podium-2dof":
        from ..design.kinematics import top_displacement
        geo = rocking_geometry(system.column)
        y0[2] = math.copysign(top_displacement(abs(theta0), 1.0, 2 if geo.radius > 0 and abs(theta0) > geo.beta
                                               else 1, geo.R, geo.alpha, geo.radius, geo.beta), theta0)
    side0 = 1.0 if (theta0 > 0 or (theta0 == 0 and thetadot0 >= 0)) else -1.0
    return y0, side0


def _build_response(system, motion, sp, model, label, summary, diag, t_out, out_y, ev_t, ev_kind, ev_y,
                    overturn) -> Response:
    from .transitions import top_displacements
    n_ev = int(diag[D_EVENTS_STORED])
    events = Event.many([EVENT_NAMES[k] for k in ev_kind[:n_ev].tolist()], ev_t[:n_ev].tolist(), ev_y[:n_ev].tolist())
    # merge event rows into the output series
    t = np.concatenate([t_out, ev_t[:n_ev]])
    y = np.concatenate([out_y, ev_y[:n_ev]])
    order = np.argsort(t, kind="stable")
    t, y = t[order], y[order]
    theta = y[:, 0]
    u_b = top_displacements(np.ascontiguousarray(theta), sp)
    u_t = y[:, 2] if sp[P_TWO_DOF] != 0.0 else u_b.copy()
    ag = motion.acceleration(t) if t.size else np.zeros(0)
    alpha = slenderness_angle(system.column.half_width, system.column.half_height)
    theta_c = float(sp[P_THETA_C])
    outcome = classify(summary, theta_c, overturn)
    mode, overturned, before = outcome.mode, outcome.overturned, outcome.impacts_before
    t_up = float(summary[S_T_UPLIFT])
    diagnostics = {"steps": int(diag[D_STEPS]), "rejected_steps": int(diag[D_REJECTED]),
                   "function_evaluations": int(diag[D_NFEV]), "events": int(diag[D_EVENTS]),
                   "rest_entries": int(diag[D_REST]), "event_refinements": int(diag[D_REFINE]),
                   "status": STATUS_NAMES[int(diag[D_STATUS])],
                   "events_stored": n_ev}
    demand = _demand(system, motion, sp, summary, y) if label.split("/")[1] != "linear-exact" else {}
    if n_ev < int(diag[D_EVENTS]):
        diagnostics["warning"] = (f"only the first {n_ev} of {int(diag[D_EVENTS])} events are listed "
                                  "(event_capacity); counts and maxima include all")
    return Response(t=t, theta=theta, thetadot=y[:, 1], u_B=u_b, u_T=u_t, u_rel=u_t - u_b, ground_acceleration=ag,
                    events=events, theta_max=float(summary[S_THETA_MAX]), t_theta_max=float(summary[S_T_THETA_MAX]),
                    alpha=alpha, theta_c=theta_c, u_B_max=float(summary[S_UB_MAX]),
                    u_capacity=displacement_capacity(system.column), impacts=int(summary[S_IMPACTS]),
                    uplift_time=None if math.isnan(t_up) else t_up, time_uplifted=float(summary[S_UPLIFT_TIME]),
                    overturn_mode=mode, overturned=bool(overturned), overturn_criterion=overturn,
                    impacts_before_overturn=before, drift_max=float(summary[S_DRIFT_MAX]),
                    t_end=float(summary[S_T_END]), model=label, status=STATUS_NAMES[int(diag[D_STATUS])],
                    diagnostics=diagnostics, status_code=int(diag[D_STATUS]),
                    solver=SolverStats.from_diagnostics(diag), **demand)


def _demand(system, motion, sp, summary, y) -> dict:
    """The superstructure-demand fields of a :class:`Response` (SPEC §13): the 2DOF podium's a_T_abs history,
    its peak and the fixed-base reference; a rigid mass's cap-beam acceleration and velocity jump."""
    if sp[P_TWO_DOF] != 0.0:
        from .demand import force_history
        from ...motions.spectra import fixed_base_acceleration, motion_samples
        a_t = -force_history(*(np.ascontiguousarray(y[:, i]) for i in range(4)), sp)
        fixed = None
        if motion.is_record or (motion.kind != EXC_NONE and motion.params.size >= 2):
            accel, dt = motion_samples(motion)
            # the building as the user gave it: ζ_s, not the model's pre-uplift ζ_s/S_r under the damping
            # correction (Eq 4.27, a device of the 2DOF model; SPEC §13)
            fixed = fixed_base_acceleration(accel, dt, 2.0 * math.pi / sp[P_OMEGA], system.superstructure.damping)
        return {"a_T_abs": a_t, "superstructure_acceleration_max": float(summary[S_FS_MAX]),
                "t_superstructure_acceleration_max": float(summary[S_T_FS_MAX]), "fixed_base_acceleration_max": fixed}
    if system.kind == "podium":
        return {"cap_acceleration_max": float(summary[S_CAP_ACC_MAX]),
                "cap_velocity_jump_max": float(summary[S_CAP_DV_MAX])}
    return {}
