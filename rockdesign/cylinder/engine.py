"""Time-history analysis of the rocking and wobbling cylinder: the Python face of :mod:`.kernel`.

    >>> from rockdesign.cylinder.system import cylinder
    >>> from rockdesign.cylinder.engine import simulate_cylinder
    >>> from rockdesign.cylinder.pairs import parse_pair
    >>> spec = parse_pair("record:p695-ff/11,resultant_pga=0.3g")
    >>> r = simulate_cylinder(cylinder(3.0, 0.6), spec.pair)
    >>> r.theta_max, r.quasi_impacts, r.status
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .pairs import MotionPair, no_pair
from .eom import parameters
from .motion_line import one_directional
from .kernel import (EV_CROSSING, EV_OVERTURN, EV_QUASI_IMPACT, EV_REST, EV_THETA_MAX, EV_UPLIFT, ST_COMPLETED,
                     ST_OVERTURNED, ST_STEP_COLLAPSED, ST_STEP_LIMIT, integrate)
from .quantities import restitution_root
from .system import Cylinder

DEFAULT_RTOL = 1e-10
DEFAULT_ATOL = 1e-12
QUASI_IMPACT_TILT = 0.01
"""A minimum of θ below this fraction of α is counted as a quasi-impact (Sec 5.4.1)."""
DEFAULT_REST_VELOCITY = 5e-4
"""v_rest [rad/s] of the rest rule (energy ½ M R² v_rest², the planar engine's |θ̇⁺| < v_rest, SPEC §3.6)."""
UPLIFT_HYSTERESIS = 1e-9
"""Uplift needs θ̈ at θ = θ̇ = φ̇ = 0 (Eq 5.22) above this fraction of g/R: the planar engine's chatter guard
(``rockdesign.dynamics.model.UPLIFT_HYSTERESIS``, SPEC §3.6), |ü_g| ≥ g tan α + 1e-9 g M/cos α."""
SEED_FRACTION = 1e-2
"""θ_seed/θ_rest: an uplift starts at the tilt whose potential energy is this fraction of the rest energy
(:func:`seed_tilt`), so that the seed cannot decide a rest."""
THETA_SEED = 1e-9
"""θ_seed [rad] without a rest rule (rest_velocity = 0), where :func:`seed_tilt` has no rest energy to scale."""
MAX_STEPS = 20_000_000
STATUS = {ST_COMPLETED: "completed", ST_OVERTURNED: "overturned (θ reached θ_ot)",
          ST_STEP_COLLAPSED: "step size collapsed", ST_STEP_LIMIT: "step limit reached"}
EVENT_NAMES = {EV_UPLIFT: "uplift", EV_QUASI_IMPACT: "quasi-impact", EV_THETA_MAX: "theta-max",
               EV_CROSSING: "planar-crossing", EV_REST: "rest", EV_OVERTURN: "overturn"}


SPIN_TILT_MIN = 0.2
"""θ/α above which the spin φ̇ is reported.  Near θ = 0 the contact point whirls round the rim: φ̇ grows like
the vertical angular momentum over sin²θ, without bound at a quasi-impact (Sec 5.4.1), while the cylinder
barely moves; a spin read there is the speed of the contact point, not a rotation of the body."""


def rest_energy(R: float, alpha: float, rest_velocity: float) -> float:
    """E_rest = ½ M R² v_rest² [J/kg], M = (15 + cos²α)/12 (Eq 5.22): the rocking energy below which a
    quasi-impact ends in rest — at a planar crossing (θ = 0, φ̇ = 0) exactly the planar engine's |θ̇⁺| < v_rest
    for the block of equal inertia (I_O/m = M R², λ = (3 + cos²α)/12, Eq 5.20)."""
    return 0.5 * (15.0 + math.cos(alpha) ** 2) / 12.0 * R * R * rest_velocity ** 2


def uplift_level(alpha: float, g: float) -> float:
    """|ü_g| [m/s²] at which a resting cylinder uplifts: Eq 5.24's g tan α plus the hysteresis.

    Eq 5.22 at θ = θ̇ = φ̇ = 0, tilting toward the inertia force: M R θ̈ = |ü_g| cos α − g sin α; uplift when
    θ̈ > :data:`UPLIFT_HYSTERESIS`·g/R, i.e. |ü_g| > g tan α + 1e-9 g M/cos α — the planar engine's criterion
    for the block of equal inertia (M = 1 + λ), so both engines uplift at the same instant."""
    M = (15.0 + math.cos(alpha) ** 2) / 12.0
    return g * math.tan(alpha) + UPLIFT_HYSTERESIS * g * M / math.cos(alpha)


def seed_tilt(R: float, alpha: float, g: float, rest_velocity: float) -> float:
    """θ_seed [rad]: :data:`SEED_FRACTION` of θ_rest, the tilt whose potential gR(cos(α−θ) − cos α) is the
    rest energy (θ_rest ≈ M R v_rest²/(2 g sin α), 7.7e-8 rad for 2H = 2.5 m, tan α = 0.3).

    The seed is a numerical device (Eq 5.23 is singular at θ = 0; the planar engine uplifts at θ = 0 with no
    energy): its potential energy, V(θ_seed) ≈ SEED_FRACTION · E_rest, stays far below the rest energy, so a
    cylinder that barely uplifts rests at its first quasi-impact whatever the seed (docs/cylinder.md)."""
    if rest_velocity <= 0.0:
        return THETA_SEED
    e = rest_energy(R, alpha, rest_velocity)
    return SEED_FRACTION * e / (g * R * math.sin(alpha))


@dataclass(frozen=True)
class CylinderResponse:
    """Response of a cylinder to a pair of ground motions (SI units).

    History (every accepted step and event): ``t`` [s], ``theta``, ``phi`` [rad], ``thetadot``,
    ``phidot`` [rad/s], ``w_T`` [m], ``wdot_T`` [m/s] (zero for a rigid contact), ``contact_force``
    N/(m g) [-], ``ground_x``/``ground_y`` [m/s²].  ``events``: (kind, time [s], θ [rad], value).
    """

    t: np.ndarray
    theta: np.ndarray
    thetadot: np.ndarray
    phi: np.ndarray
    phidot: np.ndarray
    w_T: np.ndarray
    wdot_T: np.ndarray
    contact_force: np.ndarray
    ground_x: np.ndarray
    ground_y: np.ndarray
    events: list
    alpha: float
    theta_overturn: float
    R: float
    half_height: float
    base_radius: float
    damped: bool
    planar: bool
    status: str
    message: str
    solver: dict = field(default_factory=dict)

    def times_of(self, kind: str) -> np.ndarray:
        return np.array([e[1] for e in self.events if e[0] == kind])

    @property
    def quasi_impact_times(self) -> np.ndarray:
        """Times [s] of the quasi-impacts (minima of θ below 1 % of α) and planar crossings."""
        return np.array([e[1] for e in self.events if e[0] in ("quasi-impact", "planar-crossing")])

    @property
    def quasi_impacts(self) -> int:
        return int(self.quasi_impact_times.size)

    @property
    def theta_min_at_quasi_impacts(self) -> np.ndarray:
        return np.array([e[2] for e in self.events if e[0] == "quasi-impact"])

    @property
    def theta_max(self) -> float:
        """Peak tilt [rad] (dense-output maxima and step points)."""
        peaks = [e[2] for e in self.events if e[0] in ("theta-max", "overturn")]
        return float(max([float(np.max(self.theta))] + peaks))

    @property
    def t_theta_max(self) -> float:
        best_t, best = float(self.t[int(np.argmax(self.theta))]), float(np.max(self.theta))
        for e in self.events:
            if e[0] in ("theta-max", "overturn") and e[2] > best:
                best_t, best = e[1], e[2]
        return best_t

    @property
    def overturned(self) -> bool:
        return self.status.startswith("overturned")

    @property
    def uplift_time(self) -> float | None:
        up = self.times_of("uplift")
        return float(up[0]) if up.size else (0.0 if self.theta[0] > 0 else None)

    @property
    def top_displacement(self) -> np.ndarray:
        """Horizontal displacement [m] of the centre of the top face: B(1 − cosθ) + 2H sinθ."""
        return self.base_radius * (1.0 - np.cos(self.theta)) + 2.0 * self.half_height * np.sin(self.theta)

    @property
    def orbit(self) -> tuple[np.ndarray, np.ndarray]:
        """Plan-view position (x, y) [m] of the centre of mass: R(sinα − sin(α−θ))(cosφ, sinφ)."""
        rho = self.R * (math.sin(self.alpha) - np.sin(self.alpha - self.theta))
        return rho * np.cos(self.phi), rho * np.sin(self.phi)

    def spin(self, tilt_min: float = SPIN_TILT_MIN) -> np.ndarray:
        """φ̇ [rad/s] where θ ≥ ``tilt_min``·α, NaN elsewhere (see :data:`SPIN_TILT_MIN`)."""
        return np.where(self.theta >= tilt_min * self.alpha, self.phidot, np.nan)

    def spin_max(self, tilt_min: float = SPIN_TILT_MIN) -> float | None:
        """max |φ̇| [rad/s] over θ ≥ ``tilt_min``·α; None if the tilt never gets there."""
        spin = self.spin(tilt_min)
        return float(np.nanmax(np.abs(spin))) if np.any(np.isfinite(spin)) else None

    @property
    def min_contact_force_over_weight(self) -> float:
        return float(np.min(self.contact_force))

    @property
    def overturn_mode(self) -> str:
        if self.overturned:
            return "dynamic"
        return "exceeded" if self.theta_max >= self.alpha else "none"

    def cost_reason(self) -> str:
        """Why this run took the steps it took, in one sentence (for a console note on a slow analysis).

        Micro-rocking is the known expensive case: a cylinder that barely uplifts (θ_max ≪ α) but keeps more
        than the rest energy makes quasi-impacts at a period ∝ √θ (the contact point whirls round the rim),
        each resolved by the step control with tens of steps (docs/cylinder.md, "Rest, uplift and the seed")."""
        steps, qi = self.solver.get("steps", 0), self.quasi_impacts
        ratio = self.theta_max / self.alpha
        per = f"; ≈ {steps / qi:.0f} steps each" if qi else ""
        head = f"{steps:,} steps, {qi:,} quasi-impacts, θ_max/α = {ratio:.2g}"
        if qi >= 1000 and ratio < 0.01:
            why = ("a spin about the vertical that the contact's dashpot does not remove" if self.damped
                   else "the rigid contact dissipates nothing")
            return (f"{head}: micro-rocking just above the uplift acceleration, its energy above the rest energy "
                    f"½ M R² v_rest² ({why}){per}")
        if qi >= 1000:
            return f"{head}: long rocking with many quasi-impacts{per}"
        return f"{head} over {self.t[-1]:.4g} s"

    def as_json(self) -> dict:
        """``simulate --json`` for a cylinder: the planar keys plus quasi-impacts, φ_end, N_min/(mg)."""
        out = {
            "theta_max": self.theta_max,
            "theta_max_over_alpha": self.theta_max / self.alpha,
            "theta_max_over_theta_c": self.theta_max / self.alpha,
            "u_B_max": float(np.max(self.top_displacement)),
            "uplift_time": self.uplift_time,
            "impacts": self.quasi_impacts,
            "overturned": self.overturned,
            "overturn_mode": self.overturn_mode,
            "t_end": float(self.t[-1]),
            "model": "cylinder-" + ("damped" if self.damped else "undamped") + ("-planar" if self.planar else ""),
            "solver": dict(self.solver, status=self.status, message=self.message),
            "quasi_impacts": self.quasi_impacts,
            "quasi_impact_times": [float(x) for x in self.quasi_impact_times],
            "phi_end": float(self.phi[-1]),
            "theta_overturn": self.theta_overturn,
            "t_theta_max": self.t_theta_max,
            "phidot_max": float(np.max(np.abs(self.phidot))),
        }
        if self.damped:
            out["min_contact_force_over_weight"] = self.min_contact_force_over_weight
        return out


def simulate_cylinder(cyl: Cylinder, pair: MotionPair | None = None, *, t_end: float | None = None,
                      free_vibration: float = 10.0, theta0: float = 0.0, thetadot0: float = 0.0, phi0: float = 0.0,
                      phidot0: float = 0.0, rtol: float = DEFAULT_RTOL, atol: float = DEFAULT_ATOL,
                      rest_velocity: float = DEFAULT_REST_VELOCITY, theta_seed: float | None = None,
                      quasi_impact_tilt: float = QUASI_IMPACT_TILT, max_steps: int = MAX_STEPS,
                      output_dt: float = 0.0, planar_reduction: bool = True) -> CylinderResponse:
    """Integrate the cylinder's Eqs 5.22–5.23 (rigid contact) or 5.23, 5.36–5.37 (spring–dashpot).

    Args:
        cyl: the cylinder.
        pair: the bidirectional ground motion (None: free vibration).
        t_end: end time [s]; default: end of the excitation + ``free_vibration``.
        theta0, thetadot0, phi0, phidot0: initial state [rad, rad/s] (free vibration).
        rtol, atol: tolerances of the DOP853 step control (rad, rad/s, m, m/s).
        rest_velocity: v_rest [rad/s] of the rest rule, both contacts (docs/cylinder.md); 0: never rest.
        theta_seed: tilt [rad] at which the seed phase of a 3D uplift hands over to Eq 5.23; default
            :func:`seed_tilt` (an uplift on a planar motion, whose equation is regular at θ = 0, needs none).
        quasi_impact_tilt: minima of θ below this fraction of α count as quasi-impacts.
        max_steps: bound on the number of steps (status "step limit reached").
        output_dt: > 0 adds the 7th-order dense output on the grid k·output_dt [s] to the history
            (besides every step and event).
        planar_reduction: integrate a motion along one line, from an uplift, as the planar cylinder (φ̇ ≡ 0,
            Eq 5.26; :mod:`.motion_line`), whatever its azimuth; False: the 3D equations throughout (what
            the stability study shows they do on a planar motion: a step-size collapse at θ → 0).

    The response is ``planar`` (model ``cylinder-…-planar``) when the whole excitation acts along one line
    (one component, a pulse, or two proportional components) and there is no initial spin.
    """
    pair = pair if pair is not None else no_pair()
    if theta0 < 0.0:
        raise ValueError("the tilt θ0 must be ≥ 0 (tilt toward φ0)")
    end = t_end if t_end is not None else pair.duration + free_vibration
    sx = np.ascontiguousarray(pair.x if pair.is_record else np.zeros(0), dtype=np.float64)
    sy = np.ascontiguousarray(pair.y if pair.is_record else np.zeros(0), dtype=np.float64)
    dirx, diry = pair.direction
    planar = (planar_reduction and phidot0 == 0.0
              and (pair.planar or one_directional(int(pair.kind), pair.params, sx, sy, dirx, diry)))
    par = parameters(cyl.R, cyl.alpha, cyl.g, cyl.contact_frequency, cyl.contact_damping, cyl.damped, planar)
    y0 = np.array([theta0, thetadot0, phi0, phidot0, 0.0, 0.0])
    up = uplift_level(cyl.alpha, cyl.g)
    e_rest = rest_energy(cyl.R, cyl.alpha, rest_velocity)
    if theta_seed is None:
        theta_seed = seed_tilt(cyl.R, cyl.alpha, cyl.g, rest_velocity)
    restitution = restitution_root(cyl.alpha) if cyl.damped else 1.0
    hist, events, stats = integrate(y0, 0.0, float(end), float(pair.duration), par, int(pair.kind),
                                    np.ascontiguousarray(pair.params, dtype=np.float64), sx, sy, float(dirx), float(diry),
                                    float(rtol), float(atol), float(theta_seed), float(cyl.theta_overturn),
                                    float(quasi_impact_tilt * cyl.alpha), float(e_rest), float(restitution),
                                    float(up), int(max_steps), float(output_dt), bool(planar_reduction))
    t = hist[:, 0]
    ax, ay = pair.acceleration(t)
    ax = np.where(t > pair.duration, 0.0, ax)
    ay = np.where(t > pair.duration, 0.0, ay)
    status_code = int(stats[4])
    ev = [(EVENT_NAMES[int(e[0])], float(e[1]), float(e[2]), float(e[3])) for e in events]
    status = STATUS[status_code]
    message = {ST_COMPLETED: f"integrated to t = {stats[5]:.6g} s",
               ST_OVERTURNED: f"θ reached θ_ot = {cyl.theta_overturn:.6g} rad at t = {stats[5]:.6g} s",
               ST_STEP_COLLAPSED: f"the step size fell below round-off at t = {stats[5]:.6g} s",
               ST_STEP_LIMIT: f"{max_steps} steps reached at t = {stats[5]:.6g} s"}[status_code]
    solver = {"method": "DOP853 (numba)", "rtol": rtol, "atol": atol, "steps": int(stats[0]),
              "rejected_steps": int(stats[1]), "rhs_evaluations": int(stats[2]), "dense_outputs": int(stats[3]),
              "rest_entries": sum(1 for e in ev if e[0] == "rest"), "theta_seed": 0.0 if planar else theta_seed}
    return CylinderResponse(t, hist[:, 1], hist[:, 2], hist[:, 3], hist[:, 4], hist[:, 5], hist[:, 6], hist[:, 7],
                            ax, ay, ev, cyl.alpha, cyl.theta_overturn, cyl.R, cyl.half_height, cyl.base_radius,
                            cyl.damped, planar, status, message, solver)
