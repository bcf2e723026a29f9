"""Overturning margins of a cylinder's record pairs at and below the design level (thesis Sec 2.2:
responses are not monotonic in amplitude, so a pair safe at the design level may overturn below it).

Each pair, as scaled for the design (factor 1), is scanned on the geometric grid of
:mod:`rockdesign.planar.checks.margins` from half the factor at which its resultant PGA reaches the uplift
acceleration g·tan α up to 1; the lowest factor that overturns the 3D cylinder (θ reaching θ_ot) is then
bisected to ``[analysis] margin_precision``.  Nothing can overturn before uplift: a pair whose design
level does not reach uplift is not scanned.  The scan stops at the first overturning factor — the
criterion (:class:`~rockdesign.acceptance.criteria.IncrementalMargin`) needs the lowest one, not the bands
above it.
"""
from __future__ import annotations

from ..acceptance.scans import SCAN_RATIO, Margin, scan_grid


def pair_margins(cyl, scaled_pairs, nominal, a, run, progress=None) -> list[Margin]:
    """The overturning margin (factor ≤ 1 on the design-level pair) of every pair.

    Args:
        scaled_pairs: the design-level pairs (:class:`~rockdesign.motions.pairs.MotionPair`).
        nominal: their design-level 3D runs (``overturned``, ``status``): the factor 1 is not re-analysed.
        a: the project's ``[analysis]`` (``margin_precision``; the scan runs at rtol = max(rtol, scan_rtol)).
        run: ``run(pair, rtol) -> run summary`` (``overturned``, ``status``) of one 3D analysis.
    """
    uplift = cyl.g * cyl.tan_alpha
    rtol = max(a.rtol, a.scan_rtol)
    margins = []
    for i, (pair, base) in enumerate(zip(scaled_pairs, nominal)):
        margin = Margin(None, scanned_up_to=1.0)
        f_up = uplift / pair.resultant_pga if pair.resultant_pga > 0 else float("inf")
        if f_up < 1.0:
            grid = scan_grid(max(0.5 * f_up, 1e-3), 1.0, SCAN_RATIO)
            safe, hit = None, None
            for f in grid:
                r = base if f == grid[-1] else run(pair.scaled(f), rtol)
                margin.runs += f != grid[-1]
                if r.status != "completed":
                    margin.failed_scales.append(f)
                elif r.overturned:
                    hit = f
                    break
                else:
                    safe = f
            if hit is not None and safe is not None:
                lo, hi = safe, hit
                while hi / lo - 1.0 > a.margin_precision:
                    mid = (lo * hi) ** 0.5
                    r = run(pair.scaled(mid), rtol)
                    margin.runs += 1
                    if r.status != "completed":
                        margin.failed_scales.append(mid)
                        break
                    lo, hi = (lo, mid) if r.overturned else (mid, hi)
                hit = hi
            if hit is not None:
                margin.overturn_scale = hit
                margin.intervals = [(hit, None)]
        margins.append(margin)
        if progress is not None:
            progress("overturning margins (incremental 3D RHA)", i + 1, len(scaled_pairs))
    return margins
