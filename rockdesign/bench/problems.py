"""The reference problems of the work-precision study: three excitations × three systems.

Systems (SI):

* ``housner-block`` — the rigid oscillator of thesis Appendix B (Figs B.1–B.3): R = 1.50 m,
  tan α = 0.15, λ = 0.33, c_r = 0.90 imposed.
* ``curved-block`` — thesis Table 3.4 B2ec: 2H = 3 m, tan α = 0.1, tan α' = 0.2, ρ = 0.25 (= ρc),
  λ = 1/3, CoAM restitution (SPEC §2).
* ``podium-2dof`` — the reference podium of thesis Sec 4.2: 2H = 3 m, tan α = 0.15, λ = 1/3,
  γ = 10, η = 5, ω_s/p = 6, ζ_s = 1 % (damping correction on), analysed as a 2DOF podium.
* ``frame`` (speed benchmark only) — the same columns and cap beam without a superstructure.

Excitations:

* ``free-vibration`` — released from rest at θ0 = 0.4α (0.8α for the curved block), 10 s.
* ``ricker-anti`` — antisymmetric Ricker pulse (SPEC §4, t_m = 1.5 T_p), 10 s: a_p = 0.25 g,
  T_p = 0.9 s for the block (thesis Fig B.1b); Table 3.4's 0.38 g, 0.95 s for the curved block;
  0.5 g, 0.9 s for the podium.
* ``record-30s`` — FEMA P695 far-field record 1a (Northridge 1994, Beverly Hills – Mulholland,
  29.99 s at 0.01 s, built in) scaled by 0.6, analysed until 35 s.  Quick runs stop at 12 s.

Each problem exists with the exact equations (SPEC §3.1; reference: a converged high-precision
solution) and, for the SDOF systems, with the linearized equations (SPEC §3.2; reference: the
closed form of SPEC §3.8).  The linearized Ricker problem feeds the pulse sampled at T_p/200 as a
record, so that every method and the closed form solve the same piecewise-linear input.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..planar.dynamics.linear_exact import sampled_pulse
from ..motions.library import load_record
from ..motions.motion import GroundMotion, no_motion, pulse_motion
from ..planar.system import Column, RockingSystem, Superstructure

G = 9.81
RECORD_ID = "p695-ff/1a"
"""Built-in 30-s record of the ``record-30s`` problem (Northridge 1994, Beverly Hills – Mulholland)."""
RECORD_SCALE = 0.6
RECORD_T_END = 35.0
QUICK_RECORD_T_END = 12.0
PULSE_T_END = 10.0
FREE_T_END = 10.0
LINEAR_PULSE_SAMPLES_PER_PERIOD = 200

SYSTEM_NAMES = ("housner-block", "curved-block", "podium-2dof")
EXCITATIONS = ("free-vibration", "ricker-anti", "record-30s")


def housner_block() -> RockingSystem:
    """Thesis Appendix B rigid oscillator: R = 1.5 m, tan α = 0.15, λ = 0.33, c_r = 0.90."""
    R, tan_alpha = 1.5, 0.15
    a = math.atan(tan_alpha)
    column = Column(R * math.cos(a), R * math.sin(a), 1000.0, 0.33)
    return RockingSystem("housner-block", "column", column, g=G).with_restitution(0.90)


def curved_block() -> RockingSystem:
    """Thesis Table 3.4 B2ec: 2H = 3 m, tan α = 0.1, tan α' = 0.2, ρ = 0.25, λ = 1/3."""
    column = Column(1.5, 0.15, 1000.0, 1 / 3, "curved", 0.3, 0.25 * 3.0)
    return RockingSystem("curved-block", "column", column, g=G)


def _reference_columns() -> tuple[Column, float]:
    H, B, lam = 1.5, 0.225, 1 / 3
    p = math.sqrt(G / (math.hypot(H, B) * (1 + lam)))
    return Column(H, B, 1000.0, lam), p


def podium_2dof(omega_s_over_p: float = 6.0, damping: float = 0.01) -> RockingSystem:
    """Thesis Sec 4.2 reference podium: 2H = 3 m, tan α = 0.15, λ = 1/3, γ = 10, η = 5, ω_s/p given."""
    column, p = _reference_columns()
    gamma, eta = 10.0, 5.0
    sup = Superstructure(eta * gamma * column.mass, omega_s_over_p * p, damping, True)
    return RockingSystem("podium-2dof", "podium", column, 1, gamma * column.mass, sup, g=G)


def frame() -> RockingSystem:
    """The reference podium's columns and cap beam (γ = 10) without a superstructure (Eq 3.75)."""
    column, _ = _reference_columns()
    return RockingSystem("frame", "podium", column, 1, 10.0 * column.mass, None, g=G)


SYSTEMS = {"housner-block": (housner_block, "block"), "curved-block": (curved_block, "block"),
           "podium-2dof": (podium_2dof, "podium-2dof"), "frame": (frame, "frame")}
"""name → (factory, structural model passed to ``simulate``)."""


@dataclass(frozen=True)
class Problem:
    """One work-precision problem: a system, an excitation, the equations and the comparison window.

    Attributes:
        name: excitation name, with ``-linearized`` appended for the linearized equations.
        system_name: key of :data:`SYSTEMS`.
        system: the rocking system.
        structure: structural model for :func:`~rockdesign.planar.dynamics.simulate.simulate`.
        motion: ground motion (``no_motion()`` for free vibration).
        equations: ``"exact"`` (SPEC §3.1) or ``"linear"`` (SPEC §3.2).
        t_end: end of the analysis [s].
        theta0: initial tilt [rad] (free vibration).
        description: one line for tables and figure titles.
    """

    name: str
    system_name: str
    system: RockingSystem
    structure: str
    motion: GroundMotion
    equations: str
    t_end: float
    theta0: float = 0.0
    description: str = ""
    meta: dict = field(default_factory=dict)

    @property
    def key(self) -> str:
        """``name/system`` — unique within a study."""
        return f"{self.name}/{self.system_name}"

    @property
    def closed_form(self) -> bool:
        """True when the closed form of SPEC §3.8 solves this problem exactly (linearized SDOF)."""
        return self.equations == "linear" and self.structure != "podium-2dof"

    @property
    def alpha(self) -> float:
        """Slenderness angle α [rad] of the columns."""
        c = self.system.column
        return math.atan2(c.half_width, c.half_height)


def _ricker(system_name: str) -> GroundMotion:
    a_p, T_p = {"housner-block": (0.25, 0.9), "curved-block": (0.38, 0.95), "podium-2dof": (0.5, 0.9)}[system_name]
    return pulse_motion("ricker-anti", a_p * G, T_p)


def bench_record() -> GroundMotion:
    """The ``record-30s`` input: built-in record :data:`RECORD_ID` × :data:`RECORD_SCALE` (m/s², 0.01 s)."""
    return load_record(RECORD_ID, gravity=G).scaled(RECORD_SCALE)


def make_problem(excitation: str, system_name: str, equations: str = "exact", quick: bool = False) -> Problem:
    """Build one problem (see the module docstring for the definitions).

    Args:
        excitation: ``free-vibration`` | ``ricker-anti`` | ``record-30s``.
        system_name: ``housner-block`` | ``curved-block`` | ``podium-2dof`` | ``frame``.
        equations: ``exact`` or ``linear`` (linearized equations; SDOF systems only).
        quick: stop the record problem at 12 s instead of 35 s.
    """
    if excitation not in EXCITATIONS:
        raise ValueError(f"unknown excitation {excitation!r}; expected one of {EXCITATIONS}")
    if system_name not in SYSTEMS:
        raise ValueError(f"unknown system {system_name!r}; expected one of {tuple(SYSTEMS)}")
    if equations not in ("exact", "linear"):
        raise ValueError(f"equations must be 'exact' or 'linear', not {equations!r}")
    factory, structure = SYSTEMS[system_name]
    system = factory()
    alpha = math.atan2(system.column.half_width, system.column.half_height)
    theta0 = 0.0
    meta: dict = {}
    if excitation == "free-vibration":
        motion = no_motion()
        factor = 0.8 if system_name == "curved-block" else 0.4
        theta0 = factor * alpha
        t_end = FREE_T_END
        text = f"free rocking from θ0 = {factor:g}α"
        meta = {"theta0_over_alpha": factor}
    elif excitation == "ricker-anti":
        motion = _ricker(system_name)
        t_end = PULSE_T_END
        a_p, T_p = motion.params[0], motion.params[1]
        text = f"antisymmetric Ricker a_p = {a_p / G:.3g} g, T_p = {T_p:g} s"
        meta = {"a_p": float(a_p), "T_p": float(T_p), "t_m": float(motion.params[2])}
        if equations == "linear":
            motion = sampled_pulse(motion, LINEAR_PULSE_SAMPLES_PER_PERIOD)
            text += f" sampled at T_p/{LINEAR_PULSE_SAMPLES_PER_PERIOD}"
            meta["sampled_dt"] = float(motion.dt)
    else:
        motion = bench_record()
        t_end = QUICK_RECORD_T_END if quick else RECORD_T_END
        text = f"record {RECORD_ID} × {RECORD_SCALE:g} (Northridge 1994, Mulholland), until {t_end:g} s"
        meta = {"record": RECORD_ID, "scale": RECORD_SCALE, "dt": motion.dt}
    name = excitation + ("-linearized" if equations == "linear" else "")
    text = ("linearized, " if equations == "linear" else "") + text
    return Problem(name, system_name, system, structure, motion, equations, float(t_end), float(theta0),
                   text, meta)


def problem_set(quick: bool = False, systems=None, excitations=None, linearized: bool = True) -> list[Problem]:
    """All problems of the study: exact equations for every system, linearized for the SDOF systems.

    Args:
        quick: shorter record problem (12 s).
        systems, excitations: optional subsets (names).
        linearized: include the closed-form-referenced linearized problems.
    """
    systems = tuple(systems) if systems else SYSTEM_NAMES
    excitations = tuple(excitations) if excitations else EXCITATIONS
    out = [make_problem(e, s, "exact", quick) for s in systems for e in excitations]
    if linearized:
        out += [make_problem(e, s, "linear", quick) for s in systems if SYSTEMS[s][1] != "podium-2dof"
                for e in excitations]
    return out
