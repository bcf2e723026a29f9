"""Reference rocking integrator: scipy ``solve_ivp`` restarted at every event (SPEC §3).

A straightforward, clearly-correct implementation of the event-driven rocking problem, independent
of :mod:`rockdesign.planar.dynamics`.  It is the accuracy cross-check of the numba engine and the scipy
baseline of the speed benchmarks ("the same equations and events, restarted at impacts").

Event loop (one ``solve_ivp`` call per event-free stretch; records split at samples, SPEC §9):

* rest → uplift: rigid systems jump to the time where ü_g crosses ∓g tan α (exact inside a record's
  linear segment); a podium integrates its fixed-base superstructure (Eq 4.3) with a terminal event
  on the uplift criterion Eq 4.7.  The side s = ±1 is set here from the sign of ü_g (SPEC §0).
* impact at θ = 0 (moving toward zero): θ̇⁺ = √c_r θ̇⁻, u̇_T unchanged (Eqs 2.15, 4.21), s flips;
  with |θ̇⁺| < ``rest_velocity`` and the uplift criterion not met the body rests until the
  criterion is crossed afresh, with a 1e-9 g hysteresis against chatter (SPEC §3.6).
* phase change at |θ| = β (curved bases, SPEC §3.5), dynamic overturn at |θ| = ``overturn_angle``.
* θ̇ = 0 (non-terminal) locates every extremum, so θ_max is exact to the integration accuracy.
"""
from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from rockdesign.motions.motion import GroundMotion
from rockdesign.planar.system import RockingSystem

from .equations import cap_beam_state, fixed_base_rhs, phase_of, rocking_rhs
from .ground import GroundInput
from .parameters import ModelParameters, model_parameters, uplift_thresholds
from .result import Event, ReferenceResult

REST, ROCK = "rest", "rock"
HYSTERESIS_G = 1e-9
"""Re-uplift after a rest needs a crossing of the threshold by this many g (SPEC §3.6)."""
MAX_SAME_TIME_EVENTS = 200


def simulate_scipy(system: RockingSystem, motion: GroundMotion, *, method: str = "DOP853",
                   rtol: float = 1e-10, atol: float = 1e-12, linear: bool = False,
                   t_end: float | None = None, theta0: float = 0.0, thetadot0: float = 0.0,
                   rest_velocity: float = 5e-4, overturn_angle: float = math.pi / 2,
                   split_at_samples: bool = True, restitution_formula: str | float | None = None,
                   max_step: float = math.inf, record_every_step: bool = False,
                   linear_beta: str = "linearized") -> ReferenceResult:
    """Time-history analysis of a planar rocking system with scipy (reference implementation).

    Args:
        system: block, flat/curved-extended column, frame or podium (SPEC §1).  A rigid
            superstructure (ω_s = inf) is modelled as a frame with γ̂ = γ(1+η) (SPEC §3.3).
        motion: ground acceleration ü_g(t) [m/s²].
        method, rtol, atol, max_step: passed to ``scipy.integrate.solve_ivp``.
        linear: the linearized equations of SPEC §3.2 (uplift at g α, linearized β).
        t_end: end of the analysis [s]; default max(10 s, motion duration + 5 s).
        theta0, thetadot0: initial tilt [rad] and rate [rad/s] (free vibration; side = sign).
        rest_velocity: |θ̇⁺| [rad/s] below which an impact ends in rest (SPEC §3.6; must be > 0).
        overturn_angle: |θ| [rad] of dynamic overturning (SPEC §3.7).
        split_at_samples: one ``solve_ivp`` call per record sample interval (SPEC §9).
        restitution_formula: None (system's measured c_r or rule), ``"theory"``,
            ``"thesis-eq-3.39"`` or an imposed c_r (SPEC §2).
        record_every_step: output every accepted solver step (default: stretch ends and events).
        linear_beta: β of a linearized curved base, ``"linearized"`` (SPEC §3.2) or ``"exact"``
            (thesis Code B.2; reproduces the linear values quoted for Table 3.4 B3/B4).

    Returns:
        :class:`ReferenceResult`.
    """
    if rest_velocity <= 0.0:
        raise ValueError("rest_velocity must be > 0 (a free rocking body makes infinitely many impacts)")
    if system.superstructure is not None and system.superstructure.rigid:
        system = system.with_rigid_superstructure()
    params = model_parameters(system, linear=linear, restitution=restitution_formula, linear_beta=linear_beta)
    ground = GroundInput(motion, split_at_samples)
    if t_end is None:
        t_end = max(10.0, ground.duration + 5.0)
    run = _Run(params, ground, float(t_end), dict(method=method, rtol=rtol, atol=atol, max_step=max_step),
               rest_velocity, overturn_angle, record_every_step)
    wall0 = time.perf_counter()
    run.start(theta0, thetadot0)
    run.loop()
    wall = time.perf_counter() - wall0
    return run.result(wall, dict(method=method, rtol=rtol, atol=atol, linear=linear,
                                 split_at_samples=split_at_samples, rest_velocity=rest_velocity,
                                 overturn_angle=overturn_angle, max_step=max_step, linear_beta=linear_beta))


def _event(fun, terminal: bool, direction: float):
    fun.terminal = terminal
    fun.direction = direction
    return fun


class _Run:
    """Mutable state of one run: mode (rest/rock), side, phase, state vector and accumulators."""

    def __init__(self, params: ModelParameters, ground: GroundInput, t_end: float, solver: dict,
                 rest_velocity: float, overturn_angle: float, record_every_step: bool):
        self.p = params
        self.ground = ground
        self.t_end = t_end
        self.solver = solver
        self.rest_velocity = rest_velocity
        self.overturn_angle = overturn_angle
        self.every_step = record_every_step
        self.sqrt_cr = math.sqrt(params.c_r)
        self.hysteresis = HYSTERESIS_G * params.g
        self.t = 0.0
        self.mode, self.side, self.phase = REST, 1, 1
        self.y = np.zeros(2)
        self.fresh = False
        self.first_step = None
        self.done = False
        self.theta_max = self.u_B_max = self.rel_max = 0.0
        self.n_impacts = 0
        self.uplift_time = None
        self.dynamic = False
        self.impacts_before_overturn = -1
        self.events: list[Event] = []
        self.nfev = self.n_calls = 0
        self.rows: list[tuple] = []
        self._last_event_t, self._same_t = math.nan, 0

    # ---------------------------------------------------------------- state helpers
    def full_state(self, y=None, side=None, phase=None) -> tuple:
        """(θ, θ̇, u_T, u̇_T) of state vector ``y`` in the current mode."""
        y = self.y if y is None else y
        if self.mode == REST:
            return (0.0, 0.0, float(y[0]), float(y[1])) if self.p.elastic else (0.0, 0.0, 0.0, 0.0)
        if self.p.elastic:
            return float(y[0]), float(y[1]), float(y[2]), float(y[3])
        side = self.side if side is None else side
        phase = phase_of(y[0], side, self.p) if phase is None else phase
        u, ud = cap_beam_state(float(y[0]), float(y[1]), side, phase, self.p)
        return float(y[0]), float(y[1]), u, ud

    def record(self, t: float, state: tuple) -> None:
        """Append one output row (t, θ, θ̇, u_T, u̇_T, u_B)."""
        theta = state[0]
        if self.mode == REST:
            u_b = 0.0
        elif self.p.elastic:
            u_b = cap_beam_state(theta, 0.0, self.side, phase_of(theta, self.side, self.p), self.p)[0]
        else:
            u_b = state[2]
        self.rows.append((t, *state, u_b))

    def add_event(self, kind: str, t: float, before: tuple, after: tuple) -> None:
        if t == self._last_event_t:
            self._same_t += 1
            if self._same_t > MAX_SAME_TIME_EVENTS:
                raise RuntimeError(f"event chatter at t = {t!r} s ({kind}); docs/model.md §4")
        else:
            self._last_event_t, self._same_t = t, 0
        self.events.append(Event(kind, t, before, after, self.side, self.phase))
        self.record(t, after)

    def shear(self, u_T: float, u_T_dot: float) -> float:
        """f = ω_s² u_T + 2ζ_s ω_s u̇_T of the superstructure on the podium at rest (Eq 4.7)."""
        om = self.p.omega_s
        return om * om * u_T + 2.0 * self.p.zeta * om * u_T_dot

    def thresholds(self, u_T: float = 0.0, u_T_dot: float = 0.0) -> tuple[float, float]:
        return uplift_thresholds(self.p, self.shear(u_T, u_T_dot) if self.p.elastic else 0.0)

    # ---------------------------------------------------------------- main loop
    def start(self, theta0: float, thetadot0: float) -> None:
        """Initial state: rest, or rocking from (θ0, θ̇0) with an undeformed superstructure."""
        if theta0 != 0.0 or thetadot0 != 0.0:
            self.mode = ROCK
            self.side = int(math.copysign(1.0, theta0 if theta0 != 0.0 else thetadot0))
            self.phase = phase_of(theta0, self.side, self.p)
            if self.p.elastic:
                u, ud = cap_beam_state(theta0, thetadot0, self.side, self.phase, self.p)
                self.y = np.array([theta0, thetadot0, u, ud])
            else:
                self.y = np.array([theta0, thetadot0], dtype=float)
            self.theta_max = abs(theta0)
        elif self.p.elastic:
            self.y = np.zeros(2)
        self.record(0.0, self.full_state())

    def loop(self) -> None:
        tiny = 1e-13 * max(1.0, self.t_end)
        while not self.done and self.t_end - self.t > tiny:
            if self.mode == REST:
                if self.p.elastic:
                    self.rest_podium()
                else:
                    self.rest_rigid()
            else:
                self.rock()

    def uplift(self, t: float, side: int, u_T: float = 0.0, u_T_dot: float = 0.0) -> None:
        """Start rocking on ``side`` from θ = θ̇ = 0 (superstructure state carried over)."""
        before = (0.0, 0.0, u_T, u_T_dot)
        self.mode, self.side, self.phase, self.fresh = ROCK, side, 1, False
        self.y = np.array([0.0, 0.0, u_T, u_T_dot]) if self.p.elastic else np.zeros(2)
        self.t = t
        if self.uplift_time is None:
            self.uplift_time = t
        self.add_event("uplift", t, before, before)

    def rest_rigid(self) -> None:
        """Jump to the next uplift (ü_g crossing ∓g tan α; afresh after a rest) or to t_end."""
        lower, upper = self.thresholds()
        if self.fresh:
            lower, upper = lower - self.hysteresis, upper + self.hysteresis
        found = self.ground.find_uplift(self.t, lower, upper, self.t_end, immediate=not self.fresh)
        if found is None:
            self.t = self.t_end
            self.record(self.t, self.full_state())
            return
        self.uplift(*found)

    def rest_podium(self) -> None:
        """Integrate the fixed-base superstructure (Eq 4.3) until the Eq 4.7 criterion is met."""
        if not self.fresh:
            lower, upper = self.thresholds(*self.y)
            a = self.ground.accel(self.t)
            if a <= lower or a >= upper:
                self.uplift(self.t, 1 if a <= lower else -1, *self.y)
                return
        h = self.hysteresis if self.fresh else 0.0
        t_stop, accel = self.ground.stretch(self.t, self.t_end)

        def below(t, y):
            return accel(t) - (self.thresholds(y[0], y[1])[0] - h)

        def above(t, y):
            return accel(t) - (self.thresholds(y[0], y[1])[1] + h)

        sol = self.integrate(fixed_base_rhs(self.p, accel), t_stop,
                             [_event(below, True, -1.0), _event(above, True, 1.0)])
        self.rel_max = max(self.rel_max, float(np.max(np.abs(sol.y[0]))))
        self.record_steps(sol)
        if sol.status == 1:
            side = 1 if len(sol.t_events[0]) else -1
            y_e = sol.y[:, -1]
            self.uplift(float(sol.t[-1]), side, float(y_e[0]), float(y_e[1]))
        else:
            self.t, self.y = t_stop, sol.y[:, -1].copy()
            self.record(self.t, self.full_state())

    def integrate(self, fun, t_stop: float, events: list):
        """One ``solve_ivp`` call from the current state to ``t_stop``."""
        kwargs = dict(self.solver)
        if self.first_step is not None:
            kwargs["first_step"] = min(self.first_step, t_stop - self.t)
            self.first_step = None
        sol = solve_ivp(fun, (self.t, t_stop), self.y, events=events, **kwargs)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {self.t} s: {sol.message}")
        self.nfev += sol.nfev
        self.n_calls += 1
        return sol

    def record_steps(self, sol) -> None:
        """Output the interior solver steps of ``sol`` (``record_every_step`` only)."""
        if self.every_step:
            for j in range(1, sol.t.size - 1):
                self.record(float(sol.t[j]), self.full_state(sol.y[:, j]))

    def rock(self) -> None:
        """Integrate the uplifted body over one stretch and handle the terminal event, if any."""
        t_stop, accel = self.ground.stretch(self.t, self.t_end)
        if t_stop - self.t <= 1e-14 * max(1.0, self.t):
            self.t = t_stop
            return
        s, p = self.side, self.p
        events = [_event(lambda t, y: s * y[0], True, -1.0),
                  _event(lambda t, y: s * y[0] - self.overturn_angle, True, 1.0),
                  _event(lambda t, y: y[1], False, 0.0)]
        if p.curved:
            events.append(_event(lambda t, y: s * y[0] - p.beta, True, 1.0 if self.phase == 1 else -1.0))
        sol = self.integrate(rocking_rhs(p, s, self.phase, accel), t_stop, events)
        self.track(sol.y, sol.y_events[2])
        self.record_steps(sol)
        if sol.status != 1:
            self.t, self.y = t_stop, sol.y[:, -1].copy()
            self.record(self.t, self.full_state())
            return
        t_e, y_e = float(sol.t[-1]), sol.y[:, -1].copy()
        if len(sol.t_events[0]):
            self.impact(t_e, y_e)
        elif len(sol.t_events[1]):
            y_e[0] = s * self.overturn_angle
            self.t, self.y, self.done, self.dynamic = t_e, y_e, True, True
            self.impacts_before_overturn = self.n_impacts
            self.theta_max = max(self.theta_max, self.overturn_angle)
            self.add_event("overturn", t_e, self.full_state(y_e), self.full_state(y_e))
        else:
            before = self.full_state(y_e)
            y_e[0] = s * p.beta
            self.phase = 2 if self.phase == 1 else 1
            self.t, self.y = t_e, y_e
            self.add_event("phase", t_e, before, self.full_state(y_e))

    def track(self, ys: np.ndarray, extrema: np.ndarray) -> None:
        """Update θ_max, u_B,max and max |u_T − u_B| from solver steps and θ̇ = 0 events."""
        s = self.side
        peak = float(np.max(s * ys[0]))
        self.theta_max = max(self.theta_max, float(np.max(np.abs(ys[0]))))
        if extrema.size:
            peak = max(peak, float(np.max(s * extrema[:, 0])))
            self.theta_max = max(self.theta_max, float(np.max(np.abs(extrema[:, 0]))))
        if peak > 0.0:
            theta = s * peak
            u_b = cap_beam_state(theta, 0.0, s, phase_of(theta, s, self.p), self.p)[0]
            self.u_B_max = max(self.u_B_max, abs(u_b))
        if self.p.elastic:
            for j in range(ys.shape[1]):
                theta = float(ys[0, j])
                u_b = cap_beam_state(theta, 0.0, s, phase_of(theta, s, self.p), self.p)[0]
                self.rel_max = max(self.rel_max, abs(float(ys[2, j]) - u_b))

    def impact(self, t_e: float, y_e: np.ndarray) -> None:
        """θ̇⁺ = √c_r θ̇⁻, side flips, u_T and u̇_T unchanged (Eqs 2.15, 4.21); rest if |θ̇⁺| is
        below ``rest_velocity`` and the uplift criterion is not met (SPEC §3.6)."""
        s = self.side
        before = self.full_state(y_e, phase=1)
        self.t = t_e
        if s * y_e[1] > 0.0:
            y_e[0] = 0.0
            self.y, self.first_step = y_e, 1e-9
            self.add_event("restart", t_e, before, before)
            return
        self.n_impacts += 1
        thd = self.sqrt_cr * float(y_e[1])
        u_T, u_T_dot = before[2], before[3]
        new_side, rest = -s, False
        if abs(thd) < self.rest_velocity:
            lower, upper = self.thresholds(u_T, u_T_dot)
            a = self.ground.accel(t_e)
            rest = lower < a < upper
            if not rest:
                # too slow to matter, but the ground pushes: rock to the side it pushes toward
                new_side = 1 if a <= lower else -1
                thd = thd if thd * new_side > 0.0 else 0.0
        self.side, self.phase = new_side, 1
        self.y = np.array([0.0, thd, u_T, u_T_dot]) if self.p.elastic else np.array([0.0, thd])
        after = self.full_state()
        self.add_event("impact", t_e, before, after)
        if rest:
            self.mode, self.fresh = REST, True
            self.y = np.array([u_T, u_T_dot]) if self.p.elastic else np.zeros(2)
            self.add_event("rest", t_e, after, self.full_state())

    # ---------------------------------------------------------------- output
    def result(self, wall: float, settings: dict) -> ReferenceResult:
        rows = np.array(self.rows, dtype=float).reshape(-1, 6)
        return ReferenceResult(
            t=rows[:, 0], theta=rows[:, 1], theta_dot=rows[:, 2], u_T=rows[:, 3], u_T_dot=rows[:, 4],
            u_B=rows[:, 5], theta_max=self.theta_max, alpha=self.p.alpha, theta_c=self.p.theta_c,
            u_B_max=self.u_B_max, relative_top_max=self.rel_max, n_impacts=self.n_impacts,
            uplift_time=self.uplift_time, events=self.events,
            exceeded=self.theta_max >= self.p.theta_c, dynamic=self.dynamic,
            impacts_before_overturn=self.impacts_before_overturn, c_r=self.p.c_r, t_end=self.t,
            nfev=self.nfev, n_solver_calls=self.n_calls, wall_time=wall, settings=settings)
