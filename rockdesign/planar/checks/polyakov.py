"""Polyakov's rules of thumb for rocking ("kinematic") storeys and the Fig 4.9 classification.

Rule 1 (thesis Sec 1.2.4, 4.2.1): treat the superstructure as rigid.
Rule 2 (Sec 4.2.5, SPEC §5): a rocking storey is stable while SD_max < 2B, SD_max being the maximum
of the relative-displacement elastic spectrum of the ground motion (2 % damping by default).
Generalisation (ours, SPEC §5): for columns with extensions, 2B becomes the column-top displacement
at the rotation capacity θc.
"""
from __future__ import annotations

from dataclasses import dataclass

CLASSES = ("a1", "a2", "b", "c", "d")
CLASS_MEANING = {
    "a1": "both safe, Polyakov conservative",
    "a2": "both safe, Polyakov unconservative",
    "b": "RHA overturns, Polyakov says safe (false negative)",
    "c": "Polyakov predicts overturning, RHA survives",
    "d": "both overturn",
}


@dataclass(frozen=True)
class PolyakovRule:
    """Rule 2 with its capacity and the damping and period band of SD_max."""

    capacity: float            # u_B(θc) [m] (2B for a flat block)
    damping: float = 0.02
    band: tuple[float, float] = (0.05, 10.0)

    def utilisation(self, sd_max: float) -> float:
        """SD_max / capacity [-] (Polyakov predicts overturning at ≥ 1)."""
        return sd_max / self.capacity

    def predicted_scale(self, sd_max: float) -> float:
        """Amplitude factor at which Polyakov's rule predicts overturning: capacity / SD_max."""
        return self.capacity / sd_max if sd_max > 0 else float("inf")

    def describe(self) -> str:
        return (f"SD_max < u_B(θc) = {self.capacity:.4g} m, SD_max at ζ = {100 * self.damping:g} % over "
                f"T = {self.band[0]:g}–{self.band[1]:g} s")


def classify(polyakov_ratio: float, response_ratio: float, overturned: bool) -> str:
    """Class of thesis Fig 4.9 from x = SD_max/2B and y = u_B,max/2B (y ≥ 1 when the RHA overturns).

    a1: x < 1, y < 1, y ≤ x; a2: x < 1, y < 1, y > x; b: x < 1, y ≥ 1; c: x ≥ 1, y < 1; d: x ≥ 1, y ≥ 1.
    """
    y = max(response_ratio, 1.0) if overturned else response_ratio
    x = polyakov_ratio
    if x < 1.0:
        if y >= 1.0:
            return "b"
        return "a1" if y <= x else "a2"
    return "d" if y >= 1.0 else "c"
