"""The free-standing solid cylinder that rocks and wobbles in 3D (thesis Ch. 5), in SI units.

A solid rigid cylinder of radius B and total height 2H tilts by θ ≥ 0 toward the azimuth φ about a
point T of its base rim; it does not slide and stays above its original footprint (an inverted
pendulum, ψ = −φ).  Its contact is either rigid (the undamped model, Sec 5.2) or a vertical
spring–dashpot of circular frequency ω_n and damping ratio ζ (the damped model, Sec 5.3).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

CONTACTS = ("rigid", "spring-dashpot")
DEFAULT_CONTACT_FREQUENCY = 200.0
"""ω_n [rad/s] of the spring–dashpot contact (thesis Eq 5.32 default)."""
DEFAULT_CONTACT_DAMPING = 0.5
"""ζ [-] of the spring–dashpot contact (thesis Eq 5.32 default)."""
DEFAULT_OVERTURN_TILT = 1.5
"""θ_ot/α: the tilt at which a cylinder counts as overturned (thesis Sec 5.5.1)."""


@dataclass(frozen=True)
class Cylinder:
    """A rocking and wobbling solid cylinder (thesis Ch. 5), SI units.

    Attributes:
        name: project name.
        half_height: H [m] (total height 2H).
        base_radius: B [m] (diameter 2B).
        mass: m [kg] (the motion does not depend on it; the contact force does).
        contact: ``"rigid"`` (undamped model, Eqs 5.22/5.23) or ``"spring-dashpot"`` (damped model,
            Eqs 5.36/5.37).
        contact_frequency: ω_n [rad/s] of the spring–dashpot (unused for a rigid contact).
        contact_damping: ζ [-] of the spring–dashpot (unused for a rigid contact).
        g: gravitational acceleration [m/s²].
        overturn_tilt: θ_ot/α, the overturning limit as a multiple of α (Sec 5.5.1).
    """

    name: str
    half_height: float
    base_radius: float
    mass: float
    contact: str = "rigid"
    contact_frequency: float = DEFAULT_CONTACT_FREQUENCY
    contact_damping: float = DEFAULT_CONTACT_DAMPING
    g: float = 9.81
    overturn_tilt: float = DEFAULT_OVERTURN_TILT

    kind = "cylinder"

    def __post_init__(self):
        if self.contact not in CONTACTS:
            raise ValueError(f"contact must be one of {CONTACTS}, got {self.contact!r}")
        if not (self.half_height > 0 and self.base_radius > 0 and self.mass > 0):
            raise ValueError("half_height, base_radius and mass must be positive")

    @property
    def damped(self) -> bool:
        """True for the spring–dashpot contact (damped model, Sec 5.3)."""
        return self.contact == "spring-dashpot"

    @property
    def tan_alpha(self) -> float:
        """Slenderness tan α = B/H [-]."""
        return self.base_radius / self.half_height

    @property
    def alpha(self) -> float:
        """Slenderness angle α = atan(B/H) [rad]."""
        return math.atan2(self.base_radius, self.half_height)

    @property
    def R(self) -> float:
        """Distance from the base rim to the centre of mass R = √(B² + H²) [m]."""
        return math.hypot(self.base_radius, self.half_height)

    @property
    def theta_overturn(self) -> float:
        """θ_ot = overturn_tilt · α [rad] (Sec 5.5.1)."""
        return self.overturn_tilt * self.alpha

    @property
    def height(self) -> float:
        """Total height 2H [m]."""
        return 2.0 * self.half_height

    @property
    def diameter(self) -> float:
        """Diameter 2B [m]."""
        return 2.0 * self.base_radius


def cylinder(height: float, diameter: float, mass: float = 1000.0, *, contact: str = "rigid",
             contact_frequency: float = DEFAULT_CONTACT_FREQUENCY, contact_damping: float = DEFAULT_CONTACT_DAMPING,
             g: float = 9.81, overturn_tilt: float = DEFAULT_OVERTURN_TILT, name: str = "cylinder") -> Cylinder:
    """A cylinder from its total height 2H [m] and diameter 2B [m], convenient for scripts and tests."""
    return Cylinder(name, height / 2.0, diameter / 2.0, mass, contact, contact_frequency, contact_damping, g,
                    overturn_tilt)
