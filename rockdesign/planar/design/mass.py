"""Column mass and mass distribution λ = I_C/(m_C R²) from the section (Eq 3.6, Table 3.1, Fig 3.6).

λ of a column with steel end plates is computed by integrating the composite section: a concrete
core of height 2H − 2d_s between two steel plates of thickness d_s over the full section.  The
thesis assumes ρ_steel = 3.25 ρ_concrete (Table 3.1), which is the default ratio here.
"""
from __future__ import annotations

import math

STEEL_TO_CONCRETE_DENSITY = 3.25
"""ρ_steel/ρ_concrete assumed by thesis Table 3.1 and Fig 3.6."""

SECTIONS = ("rectangular", "circular")


def _slab_inertia(section: str, half_width: float, thickness: float, mass: float, z: float) -> float:
    """Inertia [kg m²] about the out-of-plane axis through C of a slab of the section at height z."""
    if section == "rectangular":
        # rectangle 2B × t rotating in its plane: m((2B)² + t²)/12
        own = mass * ((2.0 * half_width) ** 2 + thickness ** 2) / 12.0
    else:
        # disc of radius B and thickness t about a diameter: m(B²/4 + t²/12)
        own = mass * (half_width ** 2 / 4.0 + thickness ** 2 / 12.0)
    return own + mass * z * z


def section_area(section: str, half_width: float, depth: float | None) -> float:
    """Plan area [m²] of the column section: 2B × depth (rectangular) or πB² (circular, diameter 2B)."""
    if section == "rectangular":
        if depth is None:
            raise ValueError("a rectangular section needs its depth")
        return 2.0 * half_width * depth
    return math.pi * half_width ** 2


def composite_column(section: str, half_width: float, half_height: float, plate_thickness: float,
                     density_ratio: float = STEEL_TO_CONCRETE_DENSITY) -> tuple[float, float]:
    """(λ, mass per unit core density and area [m]) of a column with end plates (Table 3.1, Fig 3.6).

    Args:
        section: ``"rectangular"`` (width 2B) or ``"circular"`` (diameter 2B).
        half_width: B [m]; half_height: H [m]; plate_thickness: d_s [m] of each end plate.
        density_ratio: ρ_plate/ρ_core.

    Returns:
        λ = I_C/(m R²) and the mass divided by (ρ_core × section area), i.e. the equivalent core
        height [m], so that m_C = ρ_core × area × that height.
    """
    if not 0.0 <= plate_thickness < half_height:
        raise ValueError("end plates must be thinner than half the column height")
    core = 2.0 * half_height - 2.0 * plate_thickness
    m_core = core
    m_plate = density_ratio * plate_thickness
    z_plate = half_height - plate_thickness / 2.0
    inertia = _slab_inertia(section, half_width, core, m_core, 0.0)
    inertia += 2.0 * _slab_inertia(section, half_width, plate_thickness, m_plate, z_plate)
    mass = m_core + 2.0 * m_plate
    R2 = half_width ** 2 + half_height ** 2
    return inertia / (mass * R2), mass


