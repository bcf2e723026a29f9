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


@dataclass
class ScanNeed:
    """What a verdict needs of an incremental scan, so that a design-grid cell scans no further (SPEC §15:
    "margin scans that stop once the margin is decided").

    A check's own scan goes up to ``margin_max_scale`` for every record and a few factors past its first
    overturning one (the fragility figure shows it all).  A cell needs three numbers, each an order statistic
    of the records' first overturning factors s_i, and each equal to the check's:

    - the incremental count up to the design level: whether s_i ≤ 1 (``incremental``);
    - the distance to the flip of the count (:mod:`rockdesign.acceptance.flip`): the (A+1)-th smallest s over
      ground motions (a ground motion's s is the least of its components'; A the allowance of the rule);
    - Ŝ_CT counted (FEMA P695 §6.4, :func:`~rockdesign.acceptance.collapse_margin.counted_median`): the
      ⌈n/2⌉-th smallest capacity s_i·IM_i (only when the collapse margin can still decide: ``intensities``).

    From the upper bounds known so far (a record's first overturning grid factor, or 1 when its design-level
    analysis overturned) each order statistic has an upper bound x; a record whose s_i is known to lie above
    every x it could matter to is irrelevant: it stops scanning once its scanned factor u_i ≥ L_i
    (:meth:`thresholds`), and its first overturning factor is bisected only while its bracket overlaps the
    interval an order statistic can still take (:meth:`to_refine`).  The bounds only fall as the scan goes on, so a record found irrelevant stays irrelevant, and every
    record that is relevant is scanned and bisected on the check's own grid: the three numbers are the
    check's.

    Attributes:
        ground_motions: the ground motion of each record (components of one station share one).
        design_overturned: per record, whether its design-level analysis overturned (its s is then ≤ 1).
        allowance: A, ground motions the rule allows (:func:`rockdesign.acceptance.flip.allowance`).
        intensities: IM_i of each design-level record when Ŝ_CT is needed, else None.
        incremental: the incremental count up to the design level is needed (not after a FAIL decided there).
    """

    ground_motions: list[str]
    design_overturned: list[bool]
    allowance: int
    intensities: list[float] | None = None
    incremental: bool = True

    def upper_bounds(self, first: list[float | None]) -> list[float]:
        """Per record, an upper bound of its first overturning factor (``first``: the first overturning grid
        factor found so far, or None), as :func:`~rockdesign.acceptance.rule.first_overturn_scale` counts it."""
        out = []
        for f, over in zip(first, self.design_overturned):
            v = math.inf if f is None else f
            out.append(min(v, 1.0) if over else v)
        return out

    def thresholds(self, first: list[float | None]) -> list[float]:
        """L_i: the factor up to which record i must be scanned (and below which its first overturning factor
        must be bisected) for the cell's three numbers to be exact (see the class docstring)."""
        upper = self.upper_bounds(first)
        by_gm: dict[str, float] = {}
        for g, v in zip(self.ground_motions, upper):
            by_gm[g] = min(by_gm.get(g, math.inf), v)
        ordered = sorted(by_gm.values())
        x_flip = ordered[self.allowance] if 0 <= self.allowance < len(ordered) else math.inf
        if self.allowance < 0:
            x_flip = 1.0
        x_med = math.inf
        if self.intensities is not None and upper:
            caps = sorted(v * im for v, im in zip(upper, self.intensities))
            x_med = caps[math.ceil(len(caps) / 2) - 1]
        out = []
        for i in range(len(upper)):
            med = x_med / self.intensities[i] if self.intensities is not None and self.intensities[i] > 0 else 0.0
            out.append(max(1.0 if self.incremental else 0.0, x_flip, med))
        return out

    def to_refine(self, lower: list[float], upper: list[float]) -> set[int]:
        """The records whose first overturning factor must be bisected further for the three numbers to be exact:
        those whose bracket [``lower``, ``upper``] (a record not found overturning: [its scanned factor, ∞)) overlaps
        the interval an order statistic can still take — [k-th smallest lower bound, k-th smallest upper bound] —
        or straddles the design level.  A record wholly below that interval is below the statistic whatever its
        exact value, one wholly above it above: neither changes it, so it is not bisected (the check bisects
        every first rise; the statistics are the same)."""
        up = self.upper_bounds([None if math.isinf(u) else u for u in upper])
        lo = [min(a, 1.0) if over else a for a, over in zip(lower, self.design_overturned)]
        out = {i for i, (a, b) in enumerate(zip(lo, up)) if self.incremental and a < 1.0 < b}

        def overlapping(lows, highs, k):
            if not 0 <= k - 1 < len(lows):
                return None
            return sorted(lows)[k - 1], sorted(highs)[k - 1]

        gms: dict[str, list[int]] = {}
        for i, g in enumerate(self.ground_motions):
            gms.setdefault(g, []).append(i)
        g_lo = {g: min(lo[i] for i in ix) for g, ix in gms.items()}
        g_up = {g: min(up[i] for i in ix) for g, ix in gms.items()}
        band = overlapping(list(g_lo.values()), list(g_up.values()), self.allowance + 1)
        if band is not None:
            for g, ix in gms.items():
                if g_lo[g] <= band[1] and g_up[g] >= band[0]:
                    out.update(i for i in ix if lo[i] <= band[1] and up[i] >= band[0])
        if self.intensities is not None:
            caps_lo = [a * im for a, im in zip(lo, self.intensities)]
            caps_up = [b * im for b, im in zip(up, self.intensities)]
            band = overlapping(caps_lo, caps_up, math.ceil(len(lo) / 2))
            if band is not None:
                out.update(i for i in range(len(lo)) if caps_lo[i] <= band[1] and caps_up[i] >= band[0])
        return out
