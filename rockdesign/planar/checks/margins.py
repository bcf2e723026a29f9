"""Overturning margins: the smallest amplitude factor that overturns the structure in RHA.

Responses are not monotonic in amplitude (thesis §2.2, Zhang & Makris: safe, overturn, safe again,
overturn), so each record is first scanned on a geometric grid of factors, every overturning band
found is then bracketed and its edges bisected to the requested precision.  Factors multiply the
record *as scaled for the design* (1 = design level), like Polyakov's predicted factor u_B(θc)/SD_max.
"""
from __future__ import annotations

import math

from types import SimpleNamespace

from ..dynamics.model import ModelChoice
from ...acceptance.flip import allowance
from ...acceptance.fragility import record_intensities
from ...acceptance.rule import acceptance_rule, count_rule
from ...motions.grouping import ground_motion_id
from .runner import analysis_failed
from ...acceptance.scans import SCAN_AFTER_FIRST, SCAN_BLOCK, SCAN_RATIO, Margin, ScanNeed, scan_grid
from .runner import run_jobs


NEED_BLOCK = 2
"""Factors analysed per record and round when a design-grid cell's scan stops once decided: a smaller block than
the check's scans past a record's threshold less often (the curved podium example's verdict: 676 analyses against
740 with blocks of 4); the grid's shared batches keep the cores busy across the extra rounds."""


def overturning_margins(system, choice: ModelChoice, motions, *, uplift_factors, max_scale: float, precision: float,
                        rtol: float, atol: float, free_vibration: float, criterion: str, rest_velocity: float,
                        progress=None, executor=None, need: ScanNeed | None = None) -> list[Margin]:
    """Scan, bracket and bisect the overturning factor of every motion (see module docstring).

    Args:
        uplift_factors: per motion, the factor at which its PGA reaches the uplift acceleration; the
            scan starts at half of it (nothing can overturn before uplift) but not above 1/4 of max.
        max_scale: largest factor analysed.
        precision: relative width to which band edges are bisected (e.g. 0.01).
        need: what a design-grid cell needs (:class:`~rockdesign.acceptance.scans.ScanNeed`): a record then
            stops at its first overturning factor or once it is scanned past its threshold L_i, and its first
            overturning factor is bisected only below L_i — the cell's order statistics are the full scan's.
            None (a check): every record is scanned to ``max_scale`` or a few factors past its first
            overturning one, and every first rise is bisected.
    """
    kw = dict(rtol=rtol, atol=atol, free_vibration=free_vibration, criterion=criterion, rest_velocity=rest_velocity,
              energy_stop=True, stop_at_capacity=(criterion == "static"), executor=executor)
    grids = [scan_grid(min(max(0.5 * f_up, 1e-3), max_scale / 4), max_scale, SCAN_RATIO) for f_up in uplift_factors]
    # scan in rounds of a few factors per record; a record stops scanning a few points after its first
    # overturning factor (enough to see a safe-again band right above it) or at the largest factor
    flags_of = [[] for _ in grids]
    failed_of = [[] for _ in grids]
    active = list(range(len(grids)))
    done = [0]
    # the time the record's last analysis ran: it predicts the next one's cost, to balance the cores
    ended = [m.duration + free_vibration for m in motions]
    while active:
        jobs = []
        block = SCAN_BLOCK if need is None else NEED_BLOCK
        for i in active:
            k0 = len(flags_of[i])
            jobs.extend((i, grids[i][k]) for k in range(k0, min(k0 + block, len(grids[i]))))
        base = done[0]

        def tick(n_done, base=base):
            done[0] = base + n_done
            if progress:
                progress(done[0])

        results = run_jobs(system, choice, [motions[i] for i, _ in jobs], [f for _, f in jobs], progress=tick,
                           costs=[ended[i] for i, _ in jobs], **kw)
        for (i, f), r in zip(jobs, results):
            flags_of[i].append(r.overturned)
            ended[i] = r.t_end
            if analysis_failed(r.status):
                failed_of[i].append(f)
        still = []
        found = [_first_found(grids[i], flags_of[i]) for i in range(len(grids))]
        limits = need.thresholds(found) if need is not None else None
        for i in active:
            flags = flags_of[i]
            first = next((k for k, f in enumerate(flags) if f), None)
            if need is not None and (first is not None or grids[i][len(flags) - 1] >= limits[i]):
                continue
            if len(flags) < len(grids[i]) and (first is None or len(flags) - 1 - first < SCAN_AFTER_FIRST):
                still.append(i)
        active = still
    margins = []
    edges = []   # (record, lower_safe, upper_ot, kind) to bisect; kind "rise" (safe→OT) or "fall" (OT→safe)
    for i, grid in enumerate(grids):
        flags = flags_of[i]
        grid = grid[:len(flags)]
        m = Margin(None, [], grid[-1], len(grid), failed_of[i])
        for k in range(len(grid)):
            if flags[k] and (k == 0 or not flags[k - 1]):
                edges.append([i, grid[k - 1] if k else 0.0, grid[k], "rise", len(m.intervals)])
                m.intervals.append([grid[k], None])
            if not flags[k] and k > 0 and flags[k - 1]:
                edges.append([i, grid[k - 1], grid[k], "fall", len(m.intervals) - 1])
        margins.append(m)
    # bisect the first rise of every record (its margin) to the precision, all records in one batch per
    # round; the other band edges are reported at the scan's resolution (SCAN_RATIO)
    first_rise = {}
    for e in edges:
        if e[3] == "rise" and e[0] not in first_rise:
            first_rise[e[0]] = e
    to_bisect = list(first_rise.values())
    while True:
        active = [e for e in to_bisect if e[1] > 0 and e[2] / e[1] - 1.0 > precision]
        if need is not None:        # only the first rises an order statistic of the cell can still fall on
            lower = [grids[i][len(flags_of[i]) - 1] for i in range(len(grids))]
            upper = [math.inf] * len(grids)
            for e in to_bisect:
                lower[e[0]], upper[e[0]] = e[1], e[2]
            refine = need.to_refine(lower, upper)
            active = [e for e in active if e[0] in refine]
        if not active:
            break
        mids = [math.sqrt(e[1] * e[2]) for e in active]
        res = run_jobs(system, choice, [motions[e[0]] for e in active], mids, costs=[ended[e[0]] for e in active],
                       **kw)
        for e, mid, r in zip(active, mids, res):
            ended[e[0]] = r.t_end
            margins[e[0]].runs += 1
            if analysis_failed(r.status):
                margins[e[0]].failed_scales.append(mid)
            ot_side = r.overturned
            # "rise": lower is safe, upper overturns; "fall": lower overturns, upper is safe
            if (e[3] == "rise") == ot_side:
                e[2] = mid
            else:
                e[1] = mid
    for e in edges:
        m = margins[e[0]]
        band = m.intervals[e[4]]
        if e[3] == "rise":
            band[0] = e[2]
        else:
            band[1] = e[2]
    for m in margins:
        m.intervals = [(a, b) for a, b in m.intervals]
        m.overturn_scale = m.intervals[0][0] if m.intervals else None
    return margins


def _first_found(grid: list[float], flags: list[bool]) -> float | None:
    """The first overturning factor of a record's scan so far (None: none yet)."""
    return next((grid[k] for k, f in enumerate(flags) if f), None)


def scan_need(a, records, runs, motions, sds, decided_fail: bool):
    """What a design-grid cell needs of its incremental scans (:class:`~rockdesign.acceptance.scans.ScanNeed`):
    the incremental count and the distance to the flip always, Ŝ_CT only while the collapse margin can decide
    (not after a FAIL decided at the design level); None when an analysis failed (no flip is computed)."""
    if any(analysis_failed(r.status) for r in runs):
        return None
    gms = [ground_motion_id(rec.id, rec.meta) for rec in records]
    ims = None
    if not decided_fail:
        rows = [SimpleNamespace(pga=m.pga, sd_max=sd, motion=m) for m, (sd, _) in zip(motions, sds)]
        ims = record_intensities(rows, a.fragility_im, a.fragility_period if a.fragility_im == "sa" else None)
    return ScanNeed(gms, [bool(r.overturned) for r in runs], allowance(acceptance_rule(a), len(set(gms))), ims,
                    incremental=not decided_fail)


def decided_at_design_level(rule, records, runs) -> bool:
    """True when the design-level suite alone already makes the verdict FAIL, whatever the incremental
    analyses would add (SPEC §15): an analysis failed (never counted as safe), or the count rule of
    the acceptance method fails (ASCE 7-22 §16.4.1.1 count, or the binomial bound at the design level).
    The margins can only add failing criteria, never remove one, so the word cannot change."""
    if any(analysis_failed(r.status) for r in runs):
        return True
    rows = [SimpleNamespace(id=rec.id, ground_motion=ground_motion_id(rec.id, rec.meta)) for rec in records]
    holds = count_rule(rule, rows, {rec.id for rec, r in zip(records, runs) if r.overturned})[0]
    return not holds
