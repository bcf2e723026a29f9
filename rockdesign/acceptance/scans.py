"""Incremental analysis, shared by every kind: the geometric scan of amplitude factors and the overturning
margin of one ground motion it finds (thesis §2.2: responses are not monotonic in amplitude, so every
overturning band found is kept, not only the first).  Factors multiply the ground motion *as scaled for the
design* (1 = design level)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

SCAN_RATIO = 1.2
"""Ratio between consecutive factors of the scan; bands narrower than this can be missed."""
SCAN_BLOCK = 4
"""Factors analysed per record and round of the scan."""
SCAN_AFTER_FIRST = 5
"""Factors scanned above the first overturning one: 1.2⁵ ≈ 2.5, enough to find a safe-again band like
Zhang & Makris' (an overturning band spanning a factor ≈ 2, SPEC §7)."""


@dataclass
class Margin:
    """Overturning factors of one record (multipliers of the design-level record)."""

    overturn_scale: float | None            # smallest overturning factor found (None: none up to max)
    intervals: list[tuple[float, float | None]] = field(default_factory=list)  # [lower, upper) bands
    # the first lower edge is bisected to the precision; the other edges are known to the scan ratio
    scanned_up_to: float = 0.0
    runs: int = 0
    failed_scales: list[float] = field(default_factory=list)  # factors whose analysis failed (not counted safe)


def scan_grid(start: float, stop: float, ratio: float) -> list[float]:
    """Geometric grid of amplitude factors from ``start`` to ``stop`` (both included), consecutive factors at
    most ``ratio`` apart."""
    n = max(1, int(math.ceil(math.log(stop / start) / math.log(ratio))))
    return [start * (stop / start) ** (k / n) for k in range(n + 1)]
