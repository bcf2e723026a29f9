"""Output of the scipy reference integrator: the events of a run and the result record."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Event:
    """One discrete event of a run.

    Attributes:
        kind: ``"uplift"``, ``"impact"``, ``"rest"``, ``"phase"``, ``"overturn"``, or
            ``"restart"`` (a θ = 0 crossing located at the very start of a call while moving away
            from zero — not an impact; the call is repeated with a tiny first step).
        t: time [s].
        before, after: state (θ [rad], θ̇ [rad/s], u_T [m], u̇_T [m/s]) just before / after.
        side, phase: rocking side s and phase (1 rolling/flat, 2 rocking on a curved base) after.
    """

    kind: str
    t: float
    before: tuple
    after: tuple
    side: int
    phase: int


@dataclass
class ReferenceResult:
    """Outcome of :func:`simulate_scipy` (SI units, radians).

    Arrays ``t, theta, theta_dot, u_T, u_T_dot, u_B`` hold the states where the event loop stopped
    (stretch ends, events; every solver step with ``record_every_step``).  u_T is measured from the
    ground; without an elastic superstructure u_T = u_B (the column top).  In linearized runs u_B
    is the first-order 2Rθ.

    Attributes (besides the arrays):
        theta_max: max |θ| [rad] over solver steps, events and every extremum (θ̇ = 0 events).
        alpha, theta_c: α [rad] of the column and its capacity θc (SPEC §2).
        u_B_max: max |u_B| [m], column-top displacement 2u_C at the extrema.
        relative_top_max: max |u_T − u_B| [m] over solver steps (podium; 0 otherwise).
        n_impacts, uplift_time: impacts; time [s] of the first uplift (None if none or free vibration).
        events: list of :class:`Event`.
        exceeded: θ_max ≥ θc; dynamic: |θ| reached the overturn angle (SPEC §3.7).
        impacts_before_overturn: impacts before dynamic overturning (−1 if none).
        c_r: restitution used; t_end: time [s] where the run stopped.
        nfev, n_solver_calls, wall_time: right-hand-side evaluations, ``solve_ivp`` calls, seconds.
        settings: the solver options of the run.
    """

    t: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    u_T: np.ndarray
    u_T_dot: np.ndarray
    u_B: np.ndarray
    theta_max: float
    alpha: float
    theta_c: float
    u_B_max: float
    relative_top_max: float
    n_impacts: int
    uplift_time: float | None
    events: list = field(default_factory=list)
    exceeded: bool = False
    dynamic: bool = False
    impacts_before_overturn: int = -1
    c_r: float = math.nan
    t_end: float = math.nan
    nfev: int = 0
    n_solver_calls: int = 0
    wall_time: float = 0.0
    settings: dict = field(default_factory=dict)

    @property
    def theta_max_over_alpha(self) -> float:
        return self.theta_max / self.alpha

    @property
    def overturn_mode(self) -> str:
        """``"none"``, ``"exceeded"`` (θ_max ≥ θc, came back) or ``"dynamic"`` (|θ| reached the
        overturn angle) — the CONTRACT's ``overturn_mode`` (SPEC §3.7)."""
        return "dynamic" if self.dynamic else ("exceeded" if self.exceeded else "none")

    def events_of(self, kind: str) -> list:
        """The events of one kind, in time order."""
        return [e for e in self.events if e.kind == kind]
