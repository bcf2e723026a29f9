"""Record scaling per ASCE 7-22 §16.2: period range, ground-motion pairs, amplitude scaling (SPEC §16).

* **Period range** (§16.2.1, SPEC §16): an upper bound of at least twice the largest first-mode period
  and a lower bound of at most 20 % of the smallest.  A rocking structure has no single period; the
  caller passes its characteristic periods (:func:`rocking_structure_periods`: the superstructure's
  fixed-base T_s, its uplifted T_s/S_r, Eq 4.25, and the rocking period at the design rotation, Eq 2.8)
  and :func:`scaling_period_range` takes 0.2 × the smallest and 2 × the largest; a project may give the
  range instead (``periods = ["0.08 s", "3.0 s"]``).  docs/records.md justifies the default.
* **Ground motions** (§16.2.2): a ground motion is the pair of horizontal components of one station's
  recording (:func:`rockdesign.motions.grouping.ground_motion_id`); :func:`pair_components` groups a
  suite's records into pairs and says why a group is not a pair (one component only, three, different
  time steps, non-orthogonal azimuths).  A suite of single components cannot be scaled per §16.2.3.
* **Amplitude scaling** (§16.2.3.2): one factor per ground motion, applied to both its components; the
  average of the pairs' maximum-direction (RotD100, :mod:`rockdesign.motions.max_direction`) 5 % spectra
  must not fall below 90 % of the target over the period range.  :func:`asce7_22_scaling` first scales
  each pair to the target on its own (geometric least squares over the range: the mean of
  ln(target/RotD100) over a log-spaced grid is zero), then multiplies every factor by one common number
  so that the smallest ratio of the suite average to the target over the range is exactly 0.90 — the
  floor of §16.2.3.2.  Reasons (docs/records.md): each ground motion enters the average on an equal
  footing and keeps its own spectral shape; the common multiplier meets the standard's requirement
  with no intensity beyond it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy as np

from ..errors import MotionError
from .grouping import ground_motion_id

LOWER_BOUND_FRACTION = 0.2
"""§16.2.1: the lower bound of the period range is at most 20 % of the smallest first-mode period."""
UPPER_BOUND_MULTIPLE = 2.0
"""§16.2.1: the upper bound of the period range is at least twice the largest first-mode period."""
MINIMUM_RATIO = 0.9
"""§16.2.3.2: the suite average of the maximum-direction spectra is not below 90 % of the target."""
RATIO_ROUND_OFF = 1e-9
"""Relative round-off allowed when comparing the constructed minimum ratio with 0.90."""
N_PERIODS = 400
"""Points of the logarithmic period grid over the range (step ≈ 1.2 % over a 1:100 range), before the
corner periods of the target are added and the minimum ratio is refined.  On the FEMA P695 far-field
pairs over four ranges (0.028–2.7, 0.05–4, 0.08–3, 0.2–2 s) no point of a 6,000-point grid fell below the
refined minimum (they stayed 0 to 5e-5 above it); with 200 points one range missed a dip by 1.5e-5."""
ORTHOGONALITY_TOLERANCE_DEG = 1.0
"""Two components whose azimuths are known must be 90° ± this apart to form a pair."""


@dataclass(frozen=True)
class PeriodRange:
    """The period range [s] over which a suite is scaled (ASCE 7-22 §16.2.1) and why.

    Attributes:
        lo: lower bound [s].
        hi: upper bound [s].
        basis: one or two sentences: where the bounds come from.
        given: the project gave the range (``periods``) rather than the structure.
    """

    lo: float
    hi: float
    basis: str
    given: bool = False

    def as_list(self) -> list[float]:
        """[lo, hi] [s] (results.json ``period_range``)."""
        return [float(self.lo), float(self.hi)]


def rocking_structure_periods(*, fixed_base: float | None = None, uplifted: float | None = None,
                              rocking: float | None = None) -> dict[str, float]:
    """The characteristic periods [s] of a rocking structure, labelled for :func:`scaling_period_range`.

    Args:
        fixed_base: the superstructure's fixed-base period T_s [s] (None: rigid or no superstructure).
        uplifted: its period while the podium rocks, T_s/S_r [s] (Eq 4.25).
        rocking: the rocking period T_R [s] near the design rotation, (4/p) acosh(1/(1 − θ/α)) (Eq 2.8).
    """
    out = {}
    if fixed_base is not None:
        out["superstructure fixed-base period T_s"] = float(fixed_base)
    if uplifted is not None:
        out["uplifted superstructure period T_s/S_r (Eq 4.25)"] = float(uplifted)
    if rocking is not None:
        out["rocking period at the design rotation (Eq 2.8)"] = float(rocking)
    return out


def scaling_period_range(characteristic: Mapping[str, float] | None = None, *,
                         override: tuple[float, float] | None = None) -> PeriodRange:
    """The period range [lo, hi] [s] of ASCE 7-22 §16.2.1, with its basis in words.

    Default: lo = 0.2 × the smallest and hi = 2 × the largest of the ``characteristic`` periods (SPEC §16;
    docs/records.md).  ``override`` (the project's ``periods``) replaces it; the basis then also states the
    default where the periods are known, and says when the given range is narrower than the default.

    Args:
        characteristic: label → period [s] (e.g. :func:`rocking_structure_periods`).
        override: (lo, hi) [s] given by the project.

    Raises:
        MotionError: neither periods nor an override, a non-positive period, or lo ≥ hi.
    """
    periods = {str(k): float(v) for k, v in (characteristic or {}).items()}
    for label, value in periods.items():
        if not (math.isfinite(value) and value > 0.0):
            raise MotionError("a characteristic period must be positive", key="excitation.scale.periods",
                              expected="periods > 0 s", found=f"{label} = {value!r}")
    default = None
    if periods:
        small = min(periods, key=periods.get)
        large = max(periods, key=periods.get)
        lo = LOWER_BOUND_FRACTION * periods[small]
        hi = UPPER_BOUND_MULTIPLE * periods[large]
        basis = (f"ASCE 7-22 §16.2.1: upper bound 2 × the largest characteristic period ({large} "
                 f"{periods[large]:.3g} s) = {hi:.3g} s; lower bound 0.2 × the smallest ({small} "
                 f"{periods[small]:.3g} s) = {lo:.3g} s")
        default = PeriodRange(lo, hi, basis)
    if override is not None:
        lo, hi = (float(v) for v in override)
        if not 0.0 < lo < hi:
            raise MotionError("invalid period range", key="excitation.scale.periods", expected="0 < lo < hi",
                              found=f"[{lo:g} s, {hi:g} s]")
        basis = f"given in the project (excitation.scale.periods = [{lo:g} s, {hi:g} s])"
        if default is not None:
            basis += f"; the structure's §16.2.1 range would be {default.lo:.3g}–{default.hi:.3g} s"
            narrower = [w for w, bad in (("upper bound below", hi < default.hi * (1 - 1e-9)),
                                         ("lower bound above", lo > default.lo * (1 + 1e-9))) if bad]
            if narrower:
                basis += (" (the given range is narrower: " + " and ".join(narrower) +
                          " it; §16.2.1 allows a lower upper bound only where justified)")
        return PeriodRange(lo, hi, basis, given=True)
    if default is None:
        raise MotionError("ASCE 7-22 scaling needs a period range", key="excitation.scale.periods",
                          expected='periods = ["0.08 s", "3.0 s"], or the structure\'s characteristic periods',
                          found="neither")
    return default


@dataclass(frozen=True, eq=False)
class GroundMotionPair:
    """The two horizontal components of one ground motion (SI), as scaled so far.

    Attributes:
        ground_motion: the ground motion (:func:`~rockdesign.motions.grouping.ground_motion_id`).
        record_ids: the two records (components), in suite order.
        x, y: their accelerations [m/s²] on a common length (the shorter padded with zeros).
        dt: the common sample spacing [s].
    """

    ground_motion: str
    record_ids: tuple[str, str]
    x: np.ndarray
    y: np.ndarray
    dt: float


def _azimuth(record_id: str, motion, meta: dict) -> float | None:
    """The azimuth [deg] of a component when its name tells it (``YER270``, ``ERZ_032``, ``p695-nfp/6@90``)."""
    from .library import component_azimuth
    for text in (meta.get("builtin"), motion.meta.get("id"), record_id):
        if text and "@" in str(text):
            try:
                return float(str(text).rsplit("@", 1)[1]) % 360.0
            except ValueError:
                pass
    for key in ("component_name", "component"):
        for source in (motion.meta, meta):
            name = source.get(key)
            if isinstance(name, str) and name.strip():
                az = component_azimuth(name)
                if az is not None:
                    return az
    return None


def pair_components(records: Sequence[tuple[str, object, dict]]) -> tuple[list[GroundMotionPair],
                                                                           list[tuple[str, list[str], str]]]:
    """Group records (id, GroundMotion [m/s²], meta) into ground-motion pairs (ASCE 7-22 §16.2.2).

    Returns:
        (pairs in order of first appearance, problems): each problem is (ground motion, its record ids,
        why it is not a pair: one component only, more than two, not sampled records, different time
        steps, azimuths not 90° apart).
    """
    groups: dict[str, list[tuple[str, object, dict]]] = {}
    for rid, motion, meta in records:
        groups.setdefault(ground_motion_id(rid, meta), []).append((rid, motion, meta))
    pairs, problems = [], []
    for gm, items in groups.items():
        ids = [rid for rid, _, _ in items]
        if len(items) == 1:
            problems.append((gm, ids, "one component only (§16.2.3.2 needs both horizontal components)"))
            continue
        if len(items) > 2:
            problems.append((gm, ids, f"{len(items)} components of one station (a pair has two)"))
            continue
        (ia, ma, ta), (ib, mb, tb) = items
        if not (ma.is_record and mb.is_record):
            problems.append((gm, ids, "not sampled records"))
            continue
        if abs(ma.dt - mb.dt) > 1e-9 * ma.dt:
            problems.append((gm, ids, f"different time steps ({ma.dt:g} s and {mb.dt:g} s)"))
            continue
        az_a, az_b = _azimuth(ia, ma, ta), _azimuth(ib, mb, tb)
        if az_a is not None and az_b is not None:
            gap = (az_b - az_a) % 180.0
            if abs(gap - 90.0) > ORTHOGONALITY_TOLERANCE_DEG:
                problems.append((gm, ids, f"components not orthogonal (azimuths {az_a:g}° and {az_b:g}°)"))
                continue
        x = ma.scale * ma.samples
        y = mb.scale * mb.samples
        n = max(x.size, y.size)
        x = np.concatenate([x, np.zeros(n - x.size)])
        y = np.concatenate([y, np.zeros(n - y.size)])
        pairs.append(GroundMotionPair(gm, (ia, ib), np.ascontiguousarray(x), np.ascontiguousarray(y), ma.dt))
    return pairs, problems


def pair_spectra(pairs: Sequence[GroundMotionPair], periods, damping: float = 0.05) -> np.ndarray:
    """RotD100 PSA [m/s²] of each pair at the periods [s]: an array (pairs × periods)."""
    from .max_direction import max_direction_spectrum
    return np.array([max_direction_spectrum(p.x, p.y, p.dt, periods, damping)[2] for p in pairs])


def scaling_grid(period_range: PeriodRange, corner_periods=(), n_periods: int = N_PERIODS) -> np.ndarray:
    """The periods [s] where a suite is compared with its target: a log grid of ``n_periods`` over the
    range plus the target's corner periods inside it (where the target's slope changes), sorted."""
    grid = np.geomspace(period_range.lo, period_range.hi, int(n_periods))
    inside = [t for t in corner_periods if period_range.lo < t < period_range.hi]
    return np.unique(np.concatenate([grid, np.asarray(inside, dtype=float)]))


def minimum_ratio(pairs: Sequence[GroundMotionPair], factors: Sequence[float], target, periods: np.ndarray,
                  average: np.ndarray, damping: float = 0.05, *, refine: bool = True) -> tuple[float, float, dict]:
    """min over the range of (suite-average RotD100 / target) and its period [s], refined between grid points.

    ``average`` is the scaled suite average [m/s²] on ``periods``.  Every local minimum within 3 % of the
    smallest (at most 4) is refined by three rounds of 21-point log grids shrinking the bracket tenfold
    (as :func:`rockdesign.motions.spectra.sd_max_of_samples` refines SD_max), so a dip of the jagged average
    between grid points is not missed.  Returns (ratio, period, {period: average} of the refined points).
    """
    ratio = average / target.psa(periods)
    best = int(np.argmin(ratio))
    best_ratio, best_T = float(ratio[best]), float(periods[best])
    extra: dict[float, float] = {}
    if not refine or len(pairs) == 0:
        return best_ratio, best_T, extra
    n = ratio.size
    is_min = np.array([ratio[i] <= (ratio[i - 1] if i > 0 else np.inf) and
                       ratio[i] <= (ratio[i + 1] if i < n - 1 else np.inf) for i in range(n)])
    candidates = [i for i in np.argsort(ratio) if is_min[i] and ratio[i] <= 1.03 * best_ratio][:4]
    f = np.asarray(factors, dtype=float)
    lo_range, hi_range = float(periods[0]), float(periods[-1])
    for i in candidates:
        lo, hi = periods[max(i - 1, 0)], periods[min(i + 1, n - 1)]
        for _ in range(3):
            grid = np.geomspace(lo, hi, 21)
            avg = f @ pair_spectra(pairs, grid, damping) / len(pairs)
            r = avg / target.psa(grid)
            extra.update(zip(grid.tolist(), avg.tolist()))
            j = int(np.argmin(r))
            if r[j] < best_ratio:
                best_ratio, best_T = float(r[j]), float(grid[j])
            lo = max(grid[max(j - 1, 0)], lo_range)
            hi = min(grid[min(j + 1, 20)], hi_range)
            if hi <= lo:
                break
    return best_ratio, best_T, extra


def refuse_unresolved_periods(period_range: PeriodRange, pairs: Sequence[GroundMotionPair]) -> None:
    """Refuse a period range that starts below the largest time step Δt of the suite's records.

    The spectrum at a period T is read at the samples, sub-stepped to Δt/m ≤ T/10 below T = 10 Δt (PEER's
    convention, docs/records.md): a period of 0.001 ms with records at Δt = 0.01 s asks 100,000 sub-steps per
    sample, and the check ran for minutes without a word; yet the samples carry nothing at periods shorter than
    the time between two of them (their shortest resolved period is 2 Δt).  Δt, not 2 Δt, is the floor, so that
    the default range of a stiff structure (0.2 × its uplifted period) stays usable with records at Δt = 0.02 s.

    Raises:
        MotionError: keyed ``excitation.scale.periods`` (the range given) or ``excitation.scale`` (the range
            derived from the structure), saying the limit and the record that sets it.
    """
    if not pairs:
        return
    coarsest = max(pairs, key=lambda p: p.dt)
    if period_range.lo >= coarsest.dt * (1.0 - 1e-9):
        return
    key = "excitation.scale.periods" if period_range.given else "excitation.scale"
    raise MotionError("the period range starts below what the records' samples resolve", key=key,
                      expected=f"a lower bound ≥ {coarsest.dt:g} s, the largest time step of the suite's records "
                               f"({coarsest.ground_motion}: Δt = {coarsest.dt:g} s)",
                      found=f"{period_range.lo:.3g} s ({period_range.basis})")


@dataclass
class Asce722Scaling:
    """The outcome of ASCE 7-22 §16.2.3.2 amplitude scaling of a suite (SI).

    Attributes:
        period_range: the range and its basis (§16.2.1).
        target: the MCE_R target (:mod:`rockdesign.motions.targets`).
        factors: ground motion → its factor (applied to both components).
        fit_factors: ground motion → the factor matching the pair alone to the target (geometric least
            squares over the range), before the common multiplier.
        multiplier: the common multiplier making the minimum ratio 0.90.
        components: ground motion → its two record ids.
        periods: the comparison periods [s] (grid, target corners and refined points).
        target_psa: the target at ``periods`` [m/s²].
        average_psa: the scaled suite's average RotD100 5 % PSA at ``periods`` [m/s²].
        min_ratio: min over the range of average/target; min_ratio_period: where [s].
        mean_ratio: geometric mean of average/target over the log grid (how far above the floor the suite
            sits on the whole).
        conformant: min_ratio ≥ 0.90 (to round-off).
    """

    period_range: PeriodRange
    target: object
    factors: dict[str, float]
    fit_factors: dict[str, float]
    multiplier: float
    components: dict[str, tuple[str, str]]
    periods: np.ndarray
    target_psa: np.ndarray
    average_psa: np.ndarray
    min_ratio: float
    min_ratio_period: float
    mean_ratio: float
    conformant: bool
    damping: float = 0.05
    notes: list[str] = field(default_factory=list)


def asce7_22_scaling(pairs: Sequence[GroundMotionPair], target, period_range: PeriodRange, *,
                     n_periods: int = N_PERIODS, damping: float = 0.05) -> Asce722Scaling:
    """Per-ground-motion factors per ASCE 7-22 §16.2.3.2 (module docstring): fit each pair, then one
    common multiplier so that min over the range of (suite-average RotD100 5 % PSA / target) = 0.90.

    Args:
        pairs: the suite's ground motions (:func:`pair_components`), unscaled.
        target: :class:`~rockdesign.motions.targets.MCERSpectrum` or
            :class:`~rockdesign.motions.targets.TabulatedSpectrum` (psa [m/s²] of periods [s]).
        period_range: §16.2.1 range (:func:`scaling_period_range`).
        n_periods: points of the log grid over the range.
        damping: 0.05 (the target's damping).

    Raises:
        MotionError: no pairs, a target that does not cover the range, or a pair with no response.
    """
    if not pairs:
        raise MotionError("ASCE 7-22 scaling needs ground-motion pairs", key="excitation.scale",
                          expected="both horizontal components of each ground motion", found="no pairs")
    refuse_unresolved_periods(period_range, pairs)
    if not target.covers(period_range.lo, period_range.hi):
        T = np.asarray(target.corner_periods)
        raise MotionError("the target spectrum does not cover the period range", key="excitation.scale.target",
                          expected=f"a table spanning {period_range.lo:.3g}–{period_range.hi:.3g} s "
                                   f"({period_range.basis})",
                          found=f"periods {T.min():g}–{T.max():g} s")
    base = np.geomspace(period_range.lo, period_range.hi, int(n_periods))
    periods = scaling_grid(period_range, target.corner_periods, n_periods)
    spectra = pair_spectra(pairs, periods, damping)
    in_base = np.isin(periods, base)
    target_psa = target.psa(periods)
    if np.any(spectra <= 0.0):
        bad = [p.ground_motion for p, s in zip(pairs, spectra) if np.any(s <= 0.0)]
        raise MotionError("cannot scale a ground motion with no response", key="excitation.scale",
                          expected="records with motion in the period range", found=", ".join(bad))
    fit = np.exp(np.mean(np.log(target_psa[in_base] / spectra[:, in_base]), axis=1))
    average = fit @ spectra / len(pairs)
    low, low_T, extra = minimum_ratio(pairs, fit, target, periods, average, damping)
    multiplier = MINIMUM_RATIO / low
    factors = multiplier * fit
    if extra:
        more = np.array(sorted(set(extra) - set(periods.tolist())))
        if more.size:
            periods = np.concatenate([periods, more])
            average = np.concatenate([average, [extra[t] for t in more]])
            order = np.argsort(periods)
            periods, average = periods[order], average[order]
            target_psa = target.psa(periods)
    average = multiplier * average
    ratio = average / target_psa
    min_ratio = multiplier * low
    return Asce722Scaling(
        period_range=period_range, target=target,
        factors={p.ground_motion: float(f) for p, f in zip(pairs, factors)},
        fit_factors={p.ground_motion: float(f) for p, f in zip(pairs, fit)},
        multiplier=float(multiplier),
        components={p.ground_motion: p.record_ids for p in pairs},
        periods=periods, target_psa=target_psa, average_psa=average,
        min_ratio=float(min_ratio), min_ratio_period=float(low_T),
        mean_ratio=float(np.exp(np.mean(np.log(ratio[np.isin(periods, base)])))),
        conformant=bool(min_ratio >= MINIMUM_RATIO * (1.0 - RATIO_ROUND_OFF)), damping=damping)
