"""First overturning intensities of a cylinder's record pairs (thesis Sec 2.2: responses are not
monotonic in amplitude, so a pair safe at the design level may overturn below it).

Each pair, as scaled for the design (factor 1), is scanned on the geometric grid of
:mod:`rockdesign.acceptance.scans`: from half the factor at which its resultant PGA reaches the uplift
acceleration g·tan α up to 1, then on from 1 to ``[analysis] margin_max_scale``, until the first factor
that overturns the 3D cylinder (θ reaching θ_ot); that factor is then bisected to ``[analysis]
margin_precision``.  Nothing can overturn before uplift: factors below it are safe without an
analysis.  The incremental count needs the lowest overturning factor at or below the design level, the
fragility and the collapse margin (FEMA P695, counted Ŝ_CT) the lowest one at any intensity; a pair
that does not overturn up to ``margin_max_scale`` is censored there.  As in the planar scan the grid
goes on a few factors past the first overturning one, so that a safe-again band above it is seen by
the fragility's stripe fit.
"""
from __future__ import annotations

from ..acceptance.fragility import check_fragility
from ..acceptance.scans import SCAN_AFTER_FIRST, SCAN_RATIO, Margin, scan_grid


def pair_grid(f_up: float, max_scale: float) -> list[float]:
    """The factors scanned for a pair whose resultant PGA reaches uplift at the factor ``f_up``: from
    0.5·f_up to 1 (when f_up < 1), then from 1 to ``max_scale``, consecutive factors at most
    :data:`~rockdesign.acceptance.scans.SCAN_RATIO` apart; 1 (the design-level run) is always on it."""
    below = scan_grid(max(0.5 * f_up, 1e-3), 1.0, SCAN_RATIO)[:-1] + [1.0] if f_up < 1.0 else [1.0]
    return below + (scan_grid(1.0, max_scale, SCAN_RATIO)[1:] if max_scale > 1.0 else [])


def pair_margins(cyl, scaled_pairs, nominal, a, run, progress=None) -> list[Margin]:
    """The first overturning factor (on the design-level pair) of every pair, up to ``a.margin_max_scale``,
    and the overturning bands the scan sees.

    Args:
        scaled_pairs: the design-level pairs (:class:`~rockdesign.motions.pairs.MotionPair`).
        nominal: their design-level 3D runs (``overturned``, ``status``): the factor 1 is not re-analysed.
        a: the project's ``[analysis]`` (``margin_max_scale``, ``margin_precision``; the scan runs at
            rtol = max(rtol, scan_rtol)).
        run: ``run(pair, rtol) -> run summary`` (``overturned``, ``status``) of one 3D analysis.

    Returns one :class:`~rockdesign.acceptance.scans.Margin` per pair: ``overturn_scale`` the bisected
    first overturning factor (None: none up to ``margin_max_scale``); ``intervals`` the overturning bands
    [lower, upper) of the grid factors analysed (the scan goes on :data:`SCAN_AFTER_FIRST` factors past
    the first overturning one, to see a safe-again band as the planar scan does; the first lower edge is
    bisected, the other edges are known to the scan ratio); ``scanned_up_to`` the last factor analysed.
    """
    uplift = cyl.g * cyl.tan_alpha
    rtol = max(a.rtol, a.scan_rtol)
    margins = []
    for i, (pair, base) in enumerate(zip(scaled_pairs, nominal)):
        f_up = uplift / pair.resultant_pga if pair.resultant_pga > 0 else float("inf")
        grid = pair_grid(f_up, a.margin_max_scale)
        margin = Margin(None, scanned_up_to=grid[-1])
        flags, safe, first = [], [], None     # safe: analysed (or below uplift) and not overturned
        for k, f in enumerate(grid):
            if first is not None and k - first > SCAN_AFTER_FIRST:
                break
            if f < f_up:                 # below uplift the cylinder does not move
                flags.append(False)
                safe.append(True)
                continue
            r = base if f == 1.0 else run(pair.scaled(f), rtol)
            margin.runs += f != 1.0
            if r.status != "completed":
                margin.failed_scales.append(f)
            flags.append(r.status == "completed" and bool(r.overturned))
            safe.append(r.status == "completed" and not r.overturned)
            if flags[-1] and first is None:
                first = k
        grid = grid[:len(flags)]
        margin.scanned_up_to = grid[-1]
        bands = []
        for k, hit in enumerate(flags):
            if hit and (k == 0 or not flags[k - 1]):
                bands.append([grid[k], None])
            elif not hit and k > 0 and flags[k - 1]:
                bands[-1][1] = grid[k]
        below = [k for k in range(first or 0) if safe[k]]
        if first is not None and below:     # bisect the first rise between the last safe factor and it
            lo, hi = grid[below[-1]], grid[first]
            while hi / lo - 1.0 > a.margin_precision:
                mid = (lo * hi) ** 0.5
                r = run(pair.scaled(mid), rtol)
                margin.runs += 1
                if r.status != "completed":
                    margin.failed_scales.append(mid)
                    break
                lo, hi = (lo, mid) if r.overturned else (mid, hi)
            bands[0][0] = hi
        margin.intervals = [(lower, upper) for lower, upper in bands]
        margin.overturn_scale = bands[0][0] if bands else None
        margins.append(margin)
        if progress is not None:
            progress("overturning margins (incremental 3D RHA)", i + 1, len(scaled_pairs))
    return margins


def pair_fragility(valid, a, n_overturned: int) -> dict | None:
    """The overturning fragility of the completed pairs (SPEC §11, :mod:`rockdesign.acceptance.fragility`;
    ``valid``: outcomes with their ``margin``) in the resultant PGA [m/s²]: each pair's capacity is its
    first overturning factor times its design-level resultant PGA, censored at ``margin_max_scale`` where
    the scan found none; the design intensity is the median design-level resultant PGA (the target for
    ``resultant_pga`` scaling)."""
    return check_fragility(valid, a, empirical=(n_overturned, len(valid)), stripe_ratio=SCAN_RATIO,
                           measure=("resultant_pga", [o.resultant_pga for o in valid]))
