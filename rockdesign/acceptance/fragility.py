"""Overturning fragility: lognormal fits of the suite's overturning capacities (SPEC §11).

Per record i the incremental analysis gives the first overturning factor s_i on the design-level
record; with IM_i the record's intensity measure at that level (PGA, Sa(T) at 5 % damping, or
Polyakov's SD_max) the capacity is x_i = s_i·IM_i.  Records that do not overturn up to the scan
limit are right-censored at (scan limit)·IM_i.  The fragility P(overturn | IM = x) = Φ(ln(x/θ)/β)
is fitted three ways:

- method of moments on the capacities (IDA fit): ln θ = mean ln x_i, β = std ln x_i (n−1);
- censored maximum likelihood (``scipy.stats.norm.fit`` of ln x on ``scipy.stats.CensoredData``)
  when some records are censored — this is then the reported fit;
- binomial maximum likelihood on the raw outcomes at common IM stripes (Baker 2015, Earthquake
  Spectra 31(1)): responses are not monotonic in amplitude, so a record that overturns at x can be
  safe again at a larger x ("resurrection" bands); the stripe fit counts those as safe, the capacity
  fits use the first crossing.

Confidence intervals of θ and β are percentiles of a bootstrap over records (seeded).  The resampling
loop is written here rather than with ``scipy.stats.bootstrap`` because a resample may hold fewer
than two overturning records, where no fit exists: such resamples are counted and left out.  The
censored resamples are fitted all at once by the EM algorithm of the same likelihood (a thousand
``norm.fit`` calls would take ~10 s; the tests check both give the same fit).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, stats
from scipy.special import log_ndtr

from .rule import first_overturn_scale
from .statistics import overturning_probability

IMS = ("pga", "sa", "sdmax")
IM_UNITS = {"pga": "m/s^2", "sa": "m/s^2", "sdmax": "m", "resultant_pga": "m/s^2"}
IM_LABELS = {"pga": "PGA", "sa": "Sa(T)", "sdmax": "SD_max", "resultant_pga": "resultant PGA"}
"""Units and labels of the intensity measures: the three of ``[analysis] fragility_im`` for records of
one component, and the resultant PGA max √(ü_gx² + ü_gy²) of a record pair (the measure a pair is
scaled by, thesis Table 5.4)."""
SA_DAMPING = 0.05
"""Damping ratio of the Sa(T) intensity measure (the usual 5 %)."""
BOOTSTRAP_SAMPLES = 1000
CONFIDENCE = 0.90
BETA_BOUNDS = (0.01, 3.0)
"""Range of β searched by the stripe fit (dispersions outside it are not a lognormal fragility)."""


@dataclass(frozen=True)
class LognormalFit:
    """P(overturn | IM = x) = Φ(ln(x/median)/beta); median in IM units, beta dimensionless."""

    median: float
    beta: float
    method: str

    def probability(self, x: float) -> float:
        """P(overturn) at intensity x (same unit as the median)."""
        return float(stats.norm.cdf(math.log(x / self.median) / self.beta))


def capacities(overturn_scales, scanned_up_to, intensities) -> tuple[np.ndarray, np.ndarray]:
    """(x, censored): overturning capacities x_i = s_i·IM_i in IM units (SPEC §11); a record with no
    overturning factor (None) is censored at its scan limit times IM_i."""
    x = np.array([(s if s is not None else top) * im
                  for s, top, im in zip(overturn_scales, scanned_up_to, intensities)], dtype=float)
    censored = np.array([s is None for s in overturn_scales], dtype=bool)
    return x, censored


def fit_moments(x) -> LognormalFit | None:
    """Method of moments (IDA): ln θ = mean ln x, β = std ln x with n−1 (SPEC §11); None below 2 values."""
    y = np.log(np.asarray(x, dtype=float))
    if y.size < 2 or np.ptp(y) == 0.0:
        return None
    return LognormalFit(float(math.exp(y.mean())), float(y.std(ddof=1)), "moments")


def fit_censored_mle(x, censored) -> LognormalFit | None:
    """Maximum likelihood with right-censored capacities, by ``scipy.stats.norm.fit`` of ln x on
    ``CensoredData`` (SPEC §11); None when fewer than two distinct uncensored capacities exist."""
    y = np.log(np.asarray(x, dtype=float))
    c = np.asarray(censored, dtype=bool)
    if np.unique(y[~c]).size < 2:
        return None
    mu0, sigma0 = censored_normal_mle(y, c)     # a good start makes scipy's simplex converge tightly
    start = (float(mu0[0]), float(sigma0[0]))
    data = stats.CensoredData.right_censored(y, c)

    def simplex(func, x0, args=(), disp=0):
        return optimize.fmin(func, start, args=args, disp=disp, xtol=1e-10, ftol=1e-12, maxiter=2000)

    mu, sigma = stats.norm.fit(data, optimizer=simplex)
    return LognormalFit(float(math.exp(mu)), float(sigma), "censored-mle")


def censored_normal_mle(y, censored, *, tol: float = 1e-11, max_iter: int = 5000) -> tuple[np.ndarray, np.ndarray]:
    """(μ, σ) of the right-censored normal likelihood for each row of ``y`` (rows = samples, shape
    m × n or n), by the EM algorithm vectorised over the rows (the bootstrap fits a thousand at once).

    E-step for a value censored at c with a = (c − μ)/σ and h = φ(a)/Φ(−a) (inverse Mills ratio):
    E[Y | Y > c] = μ + σh, E[Y² | Y > c] = μ² + σ² + σh(μ + c); M-step: the moments of the completed
    sample.  Converges to the same maximum as ``scipy.stats.norm.fit`` on ``CensoredData``.
    """
    y = np.atleast_2d(np.asarray(y, dtype=float))
    c = np.atleast_2d(np.asarray(censored, dtype=bool))
    n = y.shape[1]
    yu = np.where(c, 0.0, y)
    n_u = (~c).sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        mu = yu.sum(axis=1) / n_u
        sigma = np.sqrt(np.maximum((yu ** 2).sum(axis=1) / n_u - mu ** 2, 1e-6))
    sum_u, sq_u = yu.sum(axis=1), (yu ** 2).sum(axis=1)
    active = c.any(axis=1) & (n_u >= 1)
    for _ in range(max_iter):
        if not active.any():
            break
        m, s = mu[active, None], sigma[active, None]
        with np.errstate(divide="ignore", invalid="ignore"):    # σ = 0: a degenerate resample (dropped)
            a = (y[active] - m) / s
            h = np.exp(-0.5 * a * a - 0.5 * math.log(2 * math.pi) - log_ndtr(-a))
        ca = c[active]
        e1 = np.where(ca, m + s * h, 0.0).sum(axis=1)
        e2 = np.where(ca, m * m + s * s + s * h * (m + y[active]), 0.0).sum(axis=1)
        mu_new = (sum_u[active] + e1) / n
        sigma_new = np.sqrt(np.maximum((sq_u[active] + e2) / n - mu_new ** 2, 0.0))
        change = np.abs(mu_new - mu[active]) + np.abs(sigma_new - sigma[active])
        mu[active], sigma[active] = mu_new, sigma_new
        idx = np.flatnonzero(active)
        active[idx[~(change >= tol * np.maximum(1.0, sigma_new))]] = False     # converged or NaN (σ = 0)
    return mu, sigma


def stripe_outcomes(intervals, scanned_up_to, intensities, levels) -> tuple[np.ndarray, np.ndarray]:
    """(n_j, z_j): at each IM level x_j [IM units], the records whose outcome is known (x_j/IM_i within
    the scan) and how many of them overturn there (x_j/IM_i inside one of the record's overturning
    bands [lower, upper); an open band reaches the scan limit).  Band edges are those of the
    incremental analysis (the first lower edge bisected, the others at the scan resolution)."""
    levels = np.asarray(levels, dtype=float)
    n = np.zeros(levels.size, dtype=int)
    z = np.zeros(levels.size, dtype=int)
    for bands, top, im in zip(intervals, scanned_up_to, intensities):
        s = levels / im
        known = s <= top * (1.0 + 1e-12)
        ot = np.zeros(levels.size, dtype=bool)
        for lower, upper in bands:
            ot |= (s >= lower) & ((s < upper) if upper is not None else True)
        n += known
        z += known & ot
    return n, z


def fit_stripes(levels, n, z, start: LognormalFit | None = None) -> LognormalFit | None:
    """Binomial maximum likelihood on stripe outcomes (Baker 2015): maximise
    Σ ln C(n_j, z_j) + z_j ln Φ(u_j) + (n_j − z_j) ln Φ(−u_j), u_j = ln(x_j/θ)/β.  None without both
    outcomes in the data."""
    levels, n, z = (np.asarray(v, dtype=float) for v in (levels, n, z))
    keep = n > 0
    levels, n, z = levels[keep], n[keep], z[keep]
    if z.sum() == 0 or z.sum() == n.sum():
        return None
    lx = np.log(levels)

    def nll(p):
        u = (lx - p[0]) / math.exp(p[1])
        return -np.sum(z * log_ndtr(u) + (n - z) * log_ndtr(-u))

    # non-monotonic stripe data (safe-again bands) make the likelihood multimodal with a ridge towards
    # θ, β → ∞: bounded quasi-Newton from several starts, the best maximum kept
    frac = z / n
    theta_half = float(np.exp(lx[np.argmin(np.abs(frac - 0.5))]))
    starts = [(theta_half, 0.3), (theta_half, 0.8)] + ([(start.median, max(start.beta, 0.05))] if start else [])
    bounds = [(lx.min() - 3.0, lx.max() + 3.0), (math.log(BETA_BOUNDS[0]), math.log(BETA_BOUNDS[1]))]
    res = min((optimize.minimize(nll, [math.log(t), math.log(b)], method="L-BFGS-B", bounds=bounds,
                                 options={"ftol": 1e-14, "gtol": 1e-10}) for t, b in starts), key=lambda r: r.fun)
    return LognormalFit(float(math.exp(res.x[0])), float(math.exp(res.x[1])), "stripes-binomial-mle")


def bootstrap(x, censored, *, samples: int = BOOTSTRAP_SAMPLES, seed: int = 0,
              confidence: float = CONFIDENCE) -> dict:
    """Percentile bootstrap over records of (θ, β) of the fit :func:`fragility_fit` would choose.

    Returns ``{"median_ci", "beta_ci", "medians", "betas", "degenerate"}`` (arrays of the valid
    resamples).  Reproducible for a given seed (numpy ``default_rng``).
    """
    x = np.asarray(x, dtype=float)
    c = np.asarray(censored, dtype=bool)
    y = np.log(x)
    rng = np.random.default_rng(seed)
    idx = rng.integers(0, x.size, size=(samples, x.size))
    if not c.any():
        ys = y[idx]
        mu, sd = ys.mean(axis=1), ys.std(axis=1, ddof=1)
        ok = sd > 0
    else:
        ys, cs = y[idx], c[idx]
        distinct = np.array([np.unique(ys[k][~cs[k]]).size for k in range(samples)])
        mu, sd = censored_normal_mle(ys, cs)
        ok = (distinct >= 2) & np.isfinite(mu) & (sd > 0)
    a = 100 * (1 - confidence) / 2
    med, beta = np.exp(mu[ok]), sd[ok]
    ci = (lambda v: [float(np.percentile(v, a)), float(np.percentile(v, 100 - a))] if v.size else [None, None])
    return {"median_ci": ci(med), "beta_ci": ci(beta), "medians": med, "betas": beta,
            "degenerate": int(samples - ok.sum())}


def stripe_levels(design_intensity: float, lowest: float, highest: float, ratio: float) -> np.ndarray:
    """IM stripes design·ratio^k (k integer) covering [lowest/ratio, highest] [IM units]."""
    k_lo = math.floor(math.log(lowest / design_intensity) / math.log(ratio)) - 1
    k_hi = math.floor(math.log(highest / design_intensity) / math.log(ratio) + 1e-9)
    return design_intensity * ratio ** np.arange(k_lo, k_hi + 1, dtype=float)


def fragility_analysis(ids, overturn_scales, intervals, scanned_up_to, intensities, *, im: str, unit: str,
                       design_intensity: float, empirical: tuple[int, int], stripe_ratio: float,
                       samples: int = BOOTSTRAP_SAMPLES, seed: int = 0, period: float | None = None) -> dict:
    """The ``fragility`` section of results.json (SPEC §11): capacities, the three fits, bootstrap
    90 % intervals, the stripe data and P(overturn) at the design intensity (fit vs empirical).

    Args:
        overturn_scales, intervals, scanned_up_to: per record, from the incremental analysis
            (factors on the design-level record; None = no overturning up to the scan).
        intensities: IM_i of the design-level records [IM units].
        design_intensity: the design IM [IM units] (the median IM_i of the design-level suite).
        empirical: (overturned, n) of the nominal analysis at the design level.
    """
    x, censored = capacities(overturn_scales, scanned_up_to, intensities)
    n_cens = int(censored.sum())
    moments = fit_moments(x) if n_cens == 0 else None
    mle = fit_censored_mle(x, censored) if n_cens else None
    chosen = moments if n_cens == 0 else mle
    k, n = empirical
    p_emp, lo, hi = overturning_probability(k, n, CONFIDENCE)
    levels = stripe_levels(design_intensity, float(x.min()), float(max(t * i for t, i in zip(scanned_up_to,
                                                                                             intensities))),
                           stripe_ratio)
    n_j, z_j = stripe_outcomes(intervals, scanned_up_to, intensities, levels)
    stripe = fit_stripes(levels, n_j, z_j, start=chosen)
    out = {
        "im": im, "im_label": IM_LABELS[im], "unit": unit, "period": period,
        "sa_damping": SA_DAMPING if im == "sa" else None,
        "design_intensity": design_intensity,
        "method": "moments" if n_cens == 0 else "censored-mle",
        "median": None, "beta": None, "n_records": int(x.size), "n_censored": n_cens,
        "median_ci90": [None, None], "beta_ci90": [None, None],
        "moments": None if moments is None else {"median": moments.median, "beta": moments.beta},
        "censored_mle": None if mle is None else {"median": mle.median, "beta": mle.beta},
        "stripes": {"median": None if stripe is None else stripe.median,
                    "beta": None if stripe is None else stripe.beta,
                    "p_overturn_design": None if stripe is None else stripe.probability(design_intensity),
                    "levels": [float(v) for v in levels], "n": [int(v) for v in n_j],
                    "overturned": [int(v) for v in z_j]},
        "p_overturn_design": None, "p_overturn_design_ci90": [None, None],
        "p_overturn_empirical": p_emp, "p_overturn_empirical_ci90": [lo, hi],
        "n_capacity_below_design": int(np.sum(~censored & (x <= design_intensity))),
        "n_nonmonotonic": sum(1 for b in intervals if len(b) > 1 or (b and b[0][1] is not None)),
        "bootstrap": {"samples": samples, "seed": seed, "degenerate": None, "confidence": CONFIDENCE},
        "capacities": [{"id": i, "capacity": float(v), "censored": bool(c)} for i, v, c in zip(ids, x, censored)],
    }
    if chosen is None:
        out["note"] = ("fewer than two records overturn within the scan: no lognormal fit; every capacity "
                       f"exceeds the censoring values (smallest {float(x[censored].min()):.4g} {unit})"
                       if n_cens else "the capacities do not vary: no lognormal fit")
        return out
    boot = bootstrap(x, censored, samples=samples, seed=seed)
    p_boot = stats.norm.cdf(np.log(design_intensity / boot["medians"]) / boot["betas"])
    a = 100 * (1 - CONFIDENCE) / 2
    out.update({"median": chosen.median, "beta": chosen.beta, "median_ci90": boot["median_ci"],
                "beta_ci90": boot["beta_ci"], "p_overturn_design": chosen.probability(design_intensity),
                "p_overturn_design_ci90": [float(np.percentile(p_boot, a)), float(np.percentile(p_boot, 100 - a))]
                if p_boot.size else [None, None]})
    out["bootstrap"]["degenerate"] = boot["degenerate"]
    return out


def record_intensities(outcomes, im: str, period: float | None) -> list[float]:
    """IM_i of each design-level record: PGA [m/s²], Sa(T) = PSA at 5 % damping [m/s²] or SD_max [m]."""
    if im == "pga":
        return [o.pga for o in outcomes]
    if im == "sdmax":
        return [o.sd_max for o in outcomes]
    from ..motions.spectra import motion_spectrum
    return [float(motion_spectrum(o.motion, np.array([period]), SA_DAMPING)[2][0]) for o in outcomes]


def check_fragility(outcomes, analysis, *, empirical: tuple[int, int], stripe_ratio: float,
                    measure: tuple[str, list[float]] | None = None) -> dict | None:
    """:func:`fragility_analysis` of a check's records (None without incremental analysis); the design
    intensity is the median IM of the design-level records (= the design PGA for PGA scaling).  Each
    record's capacity is its *first* overturning intensity: the incremental analysis's lowest
    overturning factor, or the design level when the design-level analysis overturned below it.

    ``measure``: (IM key of :data:`IM_UNITS`, IM_i of each design-level record) for a kind whose records
    carry their own measure (a record pair's resultant PGA); default ``[analysis] fragility_im``."""
    if not outcomes or any(o.margin is None for o in outcomes):
        return None     # no incremental analysis, or no completed analysis to fit
    if measure is None:
        im = analysis.fragility_im
        period = analysis.fragility_period if im == "sa" else None
        ims = record_intensities(outcomes, im, period)
    else:
        (im, ims), period = measure, None
    return fragility_analysis([o.id for o in outcomes], [first_overturn_scale(o) for o in outcomes],
                              [o.margin.intervals for o in outcomes], [o.margin.scanned_up_to for o in outcomes],
                              ims, im=im, unit=IM_UNITS[im], design_intensity=float(np.median(ims)),
                              empirical=empirical, stripe_ratio=stripe_ratio, seed=analysis.seed, period=period)
