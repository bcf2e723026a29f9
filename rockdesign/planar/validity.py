"""Warnings (not errors) when a system leaves the range the models were validated for (SPEC §6)."""
from __future__ import annotations

import math

from .design.frequencies import frequency_parameter
from .system import RockingSystem


def validity_warnings(system: RockingSystem, analysis=None) -> list[str]:
    """Human-readable warnings for parameters outside the validated ranges of SPEC §6 / Sec 4.2.3."""
    c = system.column
    out = []
    tan_a = c.tan_alpha
    if system.kind == "podium" and tan_a > 0.2:
        out.append(f"tan α = {tan_a:.3g} > 0.2: outside the slenderness range validated for rocking podia "
                   "(thesis Sec 4.2.3)")
    elif tan_a > 0.5:
        out.append(f"tan α = {tan_a:.3g} > 0.5: very squat column; sliding and bouncing (not modelled) become "
                   "likely")
    if 2 * c.half_height > 6.0:
        out.append(f"column height 2H = {2 * c.half_height:.3g} m > 6 m: the rigid-column assumption was "
                   "validated up to 6 m (docs/model.md §7); tall columns deform (thesis Ch. 7, 20 m specimen)")
    if not 0.3 <= c.mass_distribution <= 0.55:
        out.append(f"λ = {c.mass_distribution:.3g} outside 0.30–0.55, the realistic range of thesis Table 3.1 "
                   "and Fig 3.6")
    if system.kind == "podium" and system.superstructure is not None:
        if system.eta > 10:
            out.append(f"η = {system.eta:.3g} > 10: outside the validated range η ≤ 10 (thesis Sec 4.2.3)")
        s = system.superstructure
        if not s.rigid:
            R = math.hypot(c.half_width, c.half_height)
            p = frequency_parameter(R, c.mass_distribution, system.g)
            ratio = s.omega_s / p
            if ratio < 3:
                out.append(f"ω_s/p = {ratio:.3g} < 3: superstructure more flexible than the validated range "
                           "ω_s/p ≥ 3 (thesis Sec 4.2.3)")
    if system.kind == "podium" and system.gamma < 1.0:
        out.append(f"γ = {system.gamma:.3g} < 1: light cap beam; the columns' own inertia dominates")
    return out
