"""Typed rocking systems in SI units (the output of the project loader, the input of everything else).

One column description serves a solitary column (N = 1, no cap beam), a rocking frame (N columns
under a rigid cap beam of mass m_B) and a rocking podium (a frame carrying an elastic or rigid
superstructure of mass m_T) — SPEC §1.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace


@dataclass(frozen=True)
class Column:
    """Geometry and mass of one rigid rocking column (SPEC §1).

    Attributes:
        half_height: H [m] (total height 2H).
        half_width: B [m] (flat contact width 2B).
        mass: m_C [kg].
        mass_distribution: λ = I_C/(m_C R²) (Eq 3.6) [-].
        extension: ``"none"``, ``"flat"`` or ``"curved"``.
        half_width_ext: B' [m] (total base width 2B' with extensions; = B without).
        radius: r [m] of curved extensions (0 without, inf for flat extensions).
    """

    half_height: float
    half_width: float
    mass: float
    mass_distribution: float
    extension: str = "none"
    half_width_ext: float = 0.0
    radius: float = 0.0

    def __post_init__(self):
        if self.extension == "none" and self.half_width_ext == 0.0:
            object.__setattr__(self, "half_width_ext", self.half_width)
        if self.extension == "flat":
            object.__setattr__(self, "radius", math.inf)

    @property
    def tan_alpha(self) -> float:
        """Slenderness tan α = B/H (Eq 2.1)."""
        return self.half_width / self.half_height

    @property
    def tan_alpha_ext(self) -> float:
        """tan α' = B'/H (Sec 3.2.3)."""
        return self.half_width_ext / self.half_height

    @property
    def curvature(self) -> float:
        """ρ = r/(2H) (Eq 3.43); 0 without extensions, inf for flat extensions."""
        return self.radius / (2.0 * self.half_height)


@dataclass(frozen=True)
class Superstructure:
    """Elastic (or rigid) superstructure on a rocking podium, as an SDOF (Eq 4.1).

    Attributes:
        mass: m_T [kg].
        omega_s: fixed-base circular frequency ω_s [rad/s]; ``math.inf`` for a rigid superstructure.
        damping: fixed-base damping ratio ζ_s [-].
        damping_correction: use ζ_s/S_r as input damping so the uplifted damping equals ζ_s (Eq 4.27).
    """

    mass: float
    omega_s: float
    damping: float = 0.0
    damping_correction: bool = True

    @property
    def rigid(self) -> bool:
        return math.isinf(self.omega_s)


@dataclass(frozen=True)
class RockingSystem:
    """A planar rocking system: solitary column, frame or podium (SPEC §1).

    Attributes:
        name: project name.
        kind: ``"column"`` or ``"podium"``.
        column: the (identical) rocking columns.
        n_columns: N (1 for a solitary column).
        cap_beam_mass: m_B [kg] (0 for a solitary column).
        superstructure: the superstructure, or None.
        restitution: measured c_r to use instead of the CoAM value, or None.
        restitution_rule: ``"theory"`` (CoAM, SPEC §2), ``"measured"`` or ``"thesis-eq-3.39"``
            (the printed flat-extension formula, to reproduce thesis Table 3.4).
        g: gravitational acceleration [m/s²].
    """

    name: str
    kind: str
    column: Column
    n_columns: int = 1
    cap_beam_mass: float = 0.0
    superstructure: Superstructure | None = None
    restitution: float | None = None
    restitution_rule: str = "theory"
    g: float = 9.81

    @property
    def gamma(self) -> float:
        """γ = m_B/(N m_C) (Eq 3.77)."""
        return self.cap_beam_mass / (self.n_columns * self.column.mass)

    @property
    def eta(self) -> float:
        """η = m_T/m_B (Eq 4.2); 0 without a superstructure."""
        if self.superstructure is None or self.cap_beam_mass == 0.0:
            return 0.0
        return self.superstructure.mass / self.cap_beam_mass

    @property
    def has_elastic_superstructure(self) -> bool:
        return self.superstructure is not None and not self.superstructure.rigid

    def with_rigid_superstructure(self) -> "RockingSystem":
        """The frame whose cap beam carries m_B + m_T (γ̂ = γ(1+η), η = 0; SPEC §3.3, Polyakov rule 1)."""
        if self.superstructure is None:
            return self
        return replace(self, cap_beam_mass=self.cap_beam_mass + self.superstructure.mass, superstructure=None)

    def with_restitution(self, c_r: float) -> "RockingSystem":
        """The same system with an imposed coefficient of restitution."""
        return replace(self, restitution=float(c_r), restitution_rule="measured")


def block(half_height: float, half_width: float, mass: float = 1000.0, mass_distribution: float = 1.0 / 3.0,
          g: float = 9.81, name: str = "block") -> RockingSystem:
    """A solitary rectangular rocking block (Housner), convenient for scripts and tests."""
    return RockingSystem(name, "column", Column(half_height, half_width, mass, mass_distribution), g=g)
