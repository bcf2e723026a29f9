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

from ..acceptance.flip import allowance
from ..acceptance.fragility import check_fragility
from ..acceptance.scans import SCAN_AFTER_FIRST, SCAN_RATIO, Margin, ScanNeed, scan_grid


def pair_grid(f_up: float, max_scale: float) -> list[float]:
    """The factors scanned for a pair whose resultant PGA reaches uplift at the factor ``f_up``: from
    0.5·f_up to 1 (when f_up < 1), then from 1 to ``max_scale``, consecutive factors at most
    :data:`~rockdesign.acceptance.scans.SCAN_RATIO` apart; 1 (the design-level run) is always on it."""
    below = scan_grid(max(0.5 * f_up, 1e-3), 1.0, SCAN_RATIO)[:-1] + [1.0] if f_up < 1.0 else [1.0]
    return below + (scan_grid(1.0, max_scale, SCAN_RATIO)[1:] if max_scale > 1.0 else [])


def pair_margins(cyl, scaled_pairs, nominal, a, run, progress=None, need: ScanNeed | None = None) -> list[Margin]:
    """The first overturning factor (on the design-level pair) of every pair, up to ``a.margin_max_scale``,
    and the overturning bands the scan sees.

    Args:
        scaled_pairs: the design-level pairs (:class:`~rockdesign.cylinder.pairs.MotionPair`).
        nominal: their design-level 3D runs (``overturned``, ``status``): the factor 1 is not re-analysed.
        a: the project's ``[analysis]`` (``margin_max_scale``, ``margin_precision``; the scan runs at
            rtol = max(rtol, scan_rtol)).
        run: ``run(jobs) -> run summaries`` (``overturned``, ``status``) of a batch of 3D analyses, each job
            ``(pair, rtol)`` (a :class:`~rockdesign.cylinder.batch.PairRunner`: each round's analyses run as one
            batch, in this process or on an executor).
        need: what a design-grid cell needs (:class:`~rockdesign.acceptance.scans.ScanNeed`): a pair then stops
            at its first overturning factor or once scanned past its threshold, and is bisected only below it
            (the cell's order statistics are the full scan's); None: the check's full scan.

    The pairs advance together, one analysis each per round, so that a cell knows after every round which
    pairs still matter; each pair's own sequence of factors is the check's.

    Returns one :class:`~rockdesign.acceptance.scans.Margin` per pair: ``overturn_scale`` the bisected
    first overturning factor (None: none up to ``margin_max_scale``); ``intervals`` the overturning bands
    [lower, upper) of the grid factors analysed (the scan goes on :data:`SCAN_AFTER_FIRST` factors past
    the first overturning one, to see a safe-again band as the planar scan does; the first lower edge is
    bisected, the other edges are known to the scan ratio); ``scanned_up_to`` the last factor analysed.
    """
    uplift = cyl.g * cyl.tan_alpha
    rtol = max(a.rtol, a.scan_rtol)
    scans = [_PairScan(pair_grid(uplift / p.resultant_pga if p.resultant_pga > 0 else float("inf"),
                                 a.margin_max_scale), uplift / p.resultant_pga if p.resultant_pga > 0 else float("inf"))
             for p in scaled_pairs]
    done = 0
    active = list(range(len(scans)))
    while active:
        step = {}                              # pair → the factor of its one analysis this round
        for i in active:
            s = scans[i]
            while s.more():
                f = s.grid[s.k]
                s.k += 1
                if f < s.f_up:                 # below uplift the cylinder does not move
                    s.record(False, True)
                    continue
                step[i] = f
                break
        jobs = [i for i in step if step[i] != 1.0]
        ran = dict(zip(jobs, run([(scaled_pairs[i].scaled(step[i]), rtol) for i in jobs]))) if jobs else {}
        for i, f in step.items():
            s = scans[i]
            r = nominal[i] if f == 1.0 else ran[i]
            s.margin.runs += f != 1.0
            if r.status != "completed":
                s.margin.failed_scales.append(f)
            s.record(r.status == "completed" and bool(r.overturned), r.status == "completed" and not r.overturned)
        limits = need.thresholds([s.first_factor() for s in scans]) if need is not None else None
        still = []
        for i in active:
            s = scans[i]
            if not s.more() or (need is not None and (s.first is not None or s.grid[s.k - 1] >= limits[i])):
                done += 1
                if progress is not None:
                    progress("overturning margins (incremental 3D RHA)", done, len(scans))
                continue
            still.append(i)
        active = still
    brackets = {i: s.bracket() for i, s in enumerate(scans) if s.bracket() is not None}
    bisecting = set(brackets)
    while bisecting:                       # bisect the first rise between the last safe factor and it
        refine = None
        if need is not None:        # only the first rises an order statistic of the cell can still fall on
            lower = [brackets[i][0] if i in brackets else (0.0 if s.first is not None else s.grid[s.k - 1])
                     for i, s in enumerate(scans)]
            upper = [brackets[i][1] if i in brackets else (s.first_factor() if s.first is not None else float("inf"))
                     for i, s in enumerate(scans)]
            refine = need.to_refine(lower, upper)
        mids = {}
        for i in sorted(bisecting):
            lo, hi = brackets[i]
            if hi / lo - 1.0 <= a.margin_precision or (refine is not None and i not in refine):
                bisecting.discard(i)
                continue
            mids[i] = (lo * hi) ** 0.5
        runs = run([(scaled_pairs[i].scaled(mid), rtol) for i, mid in mids.items()]) if mids else []
        for (i, mid), r in zip(mids.items(), runs):     # one batch per round of bisection
            lo, hi = brackets[i]
            scans[i].margin.runs += 1
            if r.status != "completed":
                scans[i].margin.failed_scales.append(mid)
                bisecting.discard(i)
                continue
            brackets[i] = (lo, mid) if r.overturned else (mid, hi)
    for i, (_, hi) in brackets.items():
        scans[i].settle(hi)
    return [s.finish() for s in scans]


class _PairScan:
    """One pair's scan: its grid, the factors analysed so far and its margin."""

    def __init__(self, grid: list[float], f_up: float):
        self.grid, self.f_up, self.k = grid, f_up, 0
        self.flags: list[bool] = []
        self.safe: list[bool] = []
        self.first: int | None = None
        self.margin = Margin(None, scanned_up_to=grid[-1])
        self.lower_edge: float | None = None

    def more(self) -> bool:
        """Another grid factor to analyse (up to :data:`SCAN_AFTER_FIRST` past the first overturning one)."""
        return self.k < len(self.grid) and not (self.first is not None and self.k - self.first > SCAN_AFTER_FIRST)

    def record(self, hit: bool, safe: bool) -> None:
        self.flags.append(hit)
        self.safe.append(safe)
        if hit and self.first is None:
            self.first = len(self.flags) - 1

    def first_factor(self) -> float | None:
        return None if self.first is None else self.grid[self.first]

    def bracket(self) -> tuple[float, float] | None:
        """(last safe factor below the first overturning one, that one), or None (nothing to bisect)."""
        below = [k for k in range(self.first or 0) if self.safe[k]]
        return (self.grid[below[-1]], self.grid[self.first]) if self.first is not None and below else None

    def settle(self, hi: float) -> None:
        self.lower_edge = hi

    def finish(self) -> Margin:
        grid = self.grid[:len(self.flags)]
        self.margin.scanned_up_to = grid[-1]
        bands = []
        for k, hit in enumerate(self.flags):
            if hit and (k == 0 or not self.flags[k - 1]):
                bands.append([grid[k], None])
            elif not hit and k > 0 and self.flags[k - 1]:
                bands[-1][1] = grid[k]
        if bands and self.lower_edge is not None:
            bands[0][0] = self.lower_edge
        self.margin.intervals = [(lower, upper) for lower, upper in bands]
        self.margin.overturn_scale = bands[0][0] if bands else None
        return self.margin


def pair_fragility(valid, a, n_overturned: int) -> dict | None:
    """The overturning fragility of the completed pairs (SPEC §11, :mod:`rockdesign.acceptance.fragility`;
    ``valid``: outcomes with their ``margin``) in the resultant PGA [m/s²]: each pair's capacity is its
    first overturning factor times its design-level resultant PGA, censored at ``margin_max_scale`` where
    the scan found none; the design intensity is the median design-level resultant PGA (the target for
    ``resultant_pga`` scaling)."""
    return check_fragility(valid, a, empirical=(n_overturned, len(valid)), stripe_ratio=SCAN_RATIO,
                           measure=("resultant_pga", [o.resultant_pga for o in valid]))


def pair_need(rule, outcomes, decided: bool):
    """What a design-grid cell needs of its pairs' scans (:class:`~rockdesign.acceptance.scans.ScanNeed`): the
    incremental count and the distance to the flip always, Ŝ_CT (on the resultant PGA) only while the collapse
    margin can decide; None when an analysis failed (no flip)."""
    if any(o.run.status != "completed" for o in outcomes):
        return None
    return ScanNeed([o.ground_motion for o in outcomes], [bool(o.run.overturned) for o in outcomes],
                    allowance(rule, len({o.ground_motion for o in outcomes})),
                    None if decided else [o.resultant_pga for o in outcomes], incremental=not decided)
