"""Overturning fragility (SPEC §11): lognormal fits against scipy.stats and known parameters, the
seeded bootstrap, and a deterministic regression on sine pulses whose overturning thresholds are the
Zhang–Makris bands of thesis Sec 2.2 (SPEC §7).

Sampling tolerances: for n lognormal capacities, SE(ln θ̂) = β/√n and SE(β̂) ≈ β/√(2n); the
tests allow 4 standard errors (a seeded sample, but a tolerance that means something).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from rockdesign.acceptance import fragility as F
from rockdesign.acceptance.scans import SCAN_RATIO
from rockdesign.planar.checks.margins import overturning_margins
from rockdesign.planar.dynamics.model import ModelChoice
from rockdesign.motions.motion import pulse_motion
from support import G, block_from_p

THETA, BETA = 2.0, 0.4


def _sample(n, seed):
    return np.exp(np.random.default_rng(seed).normal(math.log(THETA), BETA, n))


def test_moments_fit_against_scipy_and_known_parameters():
    x = _sample(400, 1)
    fit = F.fit_moments(x)
    shape, loc, scale = stats.lognorm.fit(x, floc=0)       # scipy's MLE: σ with n, not n−1
    assert fit.median == pytest.approx(scale, rel=1e-9)
    assert fit.beta == pytest.approx(shape * math.sqrt(400 / 399), rel=1e-9)
    assert abs(math.log(fit.median / THETA)) < 4 * BETA / math.sqrt(400)
    assert abs(fit.beta - BETA) < 4 * BETA / math.sqrt(2 * 400)


@pytest.mark.parametrize("quantile", [0.6, 0.85])
def test_censored_mle_against_scipy_and_known_parameters(quantile):
    n = 400
    x = _sample(n, 2)
    limit = THETA * math.exp(BETA * stats.norm.ppf(quantile))
    censored = x > limit
    x = np.where(censored, limit, x)
    assert 0.05 * n < censored.sum() < 0.5 * n
    fit = F.fit_censored_mle(x, censored)
    shape, _, scale = stats.lognorm.fit(stats.CensoredData.right_censored(x, censored), floc=0)
    assert fit.method == "censored-mle"
    assert fit.median == pytest.approx(scale, rel=2e-4) and fit.beta == pytest.approx(shape, rel=2e-4)
    # the censoring inflates the standard errors: 1.5 × the uncensored ones is generous for ≤ 40 %
    assert abs(math.log(fit.median / THETA)) < 4 * 1.5 * BETA / math.sqrt(n)
    assert abs(fit.beta - BETA) < 4 * 1.5 * BETA / math.sqrt(2 * n)
    # a moments fit treating censored values as capacities would be biased low
    assert F.fit_moments(x).median < fit.median


def test_em_fit_of_the_bootstrap_equals_scipy_censored_fit():
    x = _sample(60, 3)
    censored = x > 2.6
    x = np.where(censored, 2.6, x)
    mu, sigma = F.censored_normal_mle(np.log(x), censored)
    ref = stats.norm.fit(stats.CensoredData.right_censored(np.log(x), censored))
    fit = F.fit_censored_mle(x, censored)
    assert mu[0] == pytest.approx(ref[0], abs=2e-4) and sigma[0] == pytest.approx(ref[1], abs=2e-4)
    assert mu[0] == pytest.approx(math.log(fit.median), abs=1e-8) and sigma[0] == pytest.approx(fit.beta, abs=1e-8)


def test_stripe_binomial_fit_recovers_known_parameters():
    rng = np.random.default_rng(4)
    levels = THETA * np.exp(np.linspace(-2.0, 2.0, 15) * BETA)
    n = np.full(levels.size, 300)
    z = rng.binomial(n, stats.norm.cdf(np.log(levels / THETA) / BETA))
    fit = F.fit_stripes(levels, n, z)
    # 4500 Bernoulli outcomes spread over ±2β: standard errors ≈ 1 % in θ, 2.5 % in β
    assert fit.median == pytest.approx(THETA, rel=0.05) and fit.beta == pytest.approx(BETA, rel=0.12)
    # maximum: the log-likelihood is lower a little way off in either parameter
    def loglik(theta, beta):
        return stats.binom.logpmf(z, n, stats.norm.cdf(np.log(levels / theta) / beta)).sum()
    best = loglik(fit.median, fit.beta)
    for dt, db in ((1.01, 1.0), (0.99, 1.0), (1.0, 1.02), (1.0, 0.98)):
        assert loglik(fit.median * dt, fit.beta * db) < best


def test_stripe_outcomes_read_the_bands():
    # record overturns in [2, 3) and from 4 on, scanned to 6; IM at the design level 0.5
    n, z = F.stripe_outcomes([[(2.0, 3.0), (4.0, None)]], [6.0], [0.5], [0.5, 1.0, 1.25, 1.5, 2.0, 3.0, 3.5])
    assert list(n) == [1, 1, 1, 1, 1, 1, 0]
    assert list(z) == [0, 1, 1, 0, 1, 1, 0]


def test_bootstrap_is_reproducible_with_a_seed():
    x = _sample(44, 5)
    censored = x > 3.0
    x = np.where(censored, 3.0, x)
    a = F.bootstrap(x, censored, samples=400, seed=7)
    b = F.bootstrap(x, censored, samples=400, seed=7)
    c = F.bootstrap(x, censored, samples=400, seed=8)
    assert a["median_ci"] == b["median_ci"] and a["beta_ci"] == b["beta_ci"]
    assert np.array_equal(a["medians"], b["medians"])
    assert a["median_ci"] != c["median_ci"]
    fit = F.fit_censored_mle(x, censored)
    assert a["median_ci"][0] < fit.median < a["median_ci"][1]
    assert a["beta_ci"][0] < fit.beta < a["beta_ci"][1]
    # the 90 % interval of ln θ is about ±1.645 standard errors (β/√n), within sampling noise
    width = math.log(a["median_ci"][1] / a["median_ci"][0])
    assert width == pytest.approx(2 * 1.645 * fit.beta / math.sqrt(44), rel=0.35)


def test_fragility_analysis_without_censoring_uses_moments():
    x = _sample(30, 6)
    out = F.fragility_analysis([f"r{i}" for i in range(30)], list(x / 1.5), [[(s, None)] for s in x / 1.5],
                               [8.0] * 30, [1.5] * 30, im="pga", unit="m/s^2", design_intensity=1.5,
                               empirical=(0, 30), stripe_ratio=SCAN_RATIO, seed=1)
    ref = F.fit_moments(x)
    assert out["method"] == "moments" and out["n_censored"] == 0
    assert out["median"] == pytest.approx(ref.median) and out["beta"] == pytest.approx(ref.beta)
    assert out["p_overturn_design"] == pytest.approx(stats.norm.cdf(math.log(1.5 / ref.median) / ref.beta))
    assert out["p_overturn_design_ci90"][0] < out["p_overturn_design"] < out["p_overturn_design_ci90"][1]


# ---------------------------------------------------------------- Zhang–Makris regression
# Sec 2.2: linearized block α = 0.25, p = 2.14, c_r = 0.81, one-sine pulse ω_p/p = 5, dynamic
# criterion: overturning for a_p/(αg) in [3.0186, 6.3181) and from 7.1681 on.  A "suite" of such
# pulses at different design-level amplitudes k·αg: every record's capacity in PGA is 3.0186·αg, the
# pulse at 0.3·αg never overturns up to the scan limit 8 (8·0.3 < 3.0186: censored), and the raw
# stripe outcomes show the safe-again band.
ALPHA = 0.25
ZM_FIRST, ZM_SAFE_AGAIN, ZM_OVERTURN_AGAIN = 3.0186, 6.3181, 7.1681
AMPLITUDES = (0.3, 1.0, 1.5, 2.0, 2.5)


@pytest.fixture(scope="module")
def zhang_makris_suite():
    system = block_from_p(2.14, math.tan(ALPHA)).with_restitution(0.81)
    period = 2 * math.pi / (5 * 2.14)
    motions = [pulse_motion("sine", k * ALPHA * G, period) for k in AMPLITUDES]
    margins = overturning_margins(system, ModelChoice("block", "linear"), motions, uplift_factors=[0.5] * 5,
                                  max_scale=8.0, precision=0.002, rtol=1e-10, atol=1e-12, free_vibration=10.0,
                                  criterion="dynamic", rest_velocity=5e-4)
    pgas = [m.pga for m in motions]
    return margins, pgas


def test_zhang_makris_suite_gives_the_known_capacities(zhang_makris_suite):
    margins, pgas = zhang_makris_suite
    capacity = ZM_FIRST * ALPHA * G
    assert pgas[2] == pytest.approx(1.5 * ALPHA * G)
    out = F.fragility_analysis([f"k={k}" for k in AMPLITUDES], [m.overturn_scale for m in margins],
                               [m.intervals for m in margins], [m.scanned_up_to for m in margins], pgas,
                               im="pga", unit="m/s^2", design_intensity=1.5 * ALPHA * G, empirical=(0, 5),
                               stripe_ratio=SCAN_RATIO, samples=200, seed=1)
    assert out["n_censored"] == 1 and out["method"] == "censored-mle"
    caps = [c for c in out["capacities"] if not c["censored"]]
    for c in caps:      # bisected to 0.2 % from the overturning side
        assert capacity * (1 - 1e-4) <= c["capacity"] <= capacity * 1.003
    assert out["capacities"][0]["censored"] and out["capacities"][0]["capacity"] == pytest.approx(8 * 0.3 * ALPHA * G)
    assert out["median"] == pytest.approx(capacity, rel=0.003)
    assert out["beta"] < 0.003                       # one threshold: no record-to-record dispersion
    assert out["p_overturn_design"] < 1e-6           # design 1.5αg, half the capacity
    # raw stripe outcomes reproduce the bands: overturn in [3.0186, 6.3181)αg, safe in the gap, overturn from
    # 7.1681αg; stripes within the scan resolution (the outer band edges) of an edge are skipped
    st = out["stripes"]
    checked = 0
    for level, n, z in zip(st["levels"], st["n"], st["overturned"]):
        a = level / (ALPHA * G)
        if n == 0 or any(abs(math.log(a / e)) < math.log(SCAN_RATIO) for e in (ZM_SAFE_AGAIN, ZM_OVERTURN_AGAIN)) \
                or abs(math.log(a / ZM_FIRST)) < 0.003:
            continue
        expected = ZM_FIRST <= a < ZM_SAFE_AGAIN or a >= ZM_OVERTURN_AGAIN
        assert z == (n if expected else 0), (a, n, z)
        checked += 1
    assert checked >= 6
    # the stripe fit of these non-lognormal outcomes (zeros above a band of ones) is still the maximum of
    # the binomial likelihood: no grid point (θ over the stripes, β in 0.01–3) does better
    lv, n_j, z_j = (np.array(st[k], dtype=float) for k in ("levels", "n", "overturned"))
    lv, z_j, n_j = lv[n_j > 0], z_j[n_j > 0], n_j[n_j > 0]

    def loglik(theta, beta):
        p = stats.norm.cdf(np.log(lv / theta) / beta)
        return stats.binom.logpmf(z_j, n_j, p).sum()
    grid = max(loglik(t, b) for t in np.geomspace(lv.min(), lv.max(), 80) for b in np.geomspace(0.01, 3.0, 80))
    assert math.isfinite(st["median"]) and F.BETA_BOUNDS[0] <= st["beta"] <= F.BETA_BOUNDS[1]
    assert loglik(st["median"], st["beta"]) >= grid - 1e-6
    # the safe-again band (narrower than the scan ratio, so not every record's scan sees it) is found
    # by at least one record, with edges at the scan resolution
    seen = [(m, pga) for m, pga in zip(margins, pgas) if len(m.intervals) == 2]
    assert seen and out["n_nonmonotonic"] == len(seen)
    for m, pga in seen:
        (lo1, hi1), (lo2, hi2) = m.intervals
        assert hi2 is None
        assert abs(math.log(hi1 * pga / (ZM_SAFE_AGAIN * ALPHA * G))) <= math.log(SCAN_RATIO) + 1e-9
        assert abs(math.log(lo2 * pga / (ZM_OVERTURN_AGAIN * ALPHA * G))) <= math.log(SCAN_RATIO) + 1e-9


@pytest.mark.parametrize("im", ["pga", "sdmax", "sa"])
def test_check_fragility_in_each_intensity_measure(im):
    from types import SimpleNamespace

    from rockdesign.acceptance.scans import Margin
    from rockdesign.motions.spectra import motion_spectrum
    motions = [pulse_motion("sine", a, 0.6) for a in (1.0, 1.5, 2.0, 2.5)]
    scales = [2.0, 1.6, None, 1.1]
    outcomes = [SimpleNamespace(id=f"r{i}", pga=m.pga, sd_max=0.01 * (i + 1), motion=m,
                                margin=Margin(s, [] if s is None else [(s, None)], 8.0))
                for i, (m, s) in enumerate(zip(motions, scales))]
    analysis = SimpleNamespace(fragility_im=im, fragility_period=0.5 if im == "sa" else None, seed=1)
    out = F.check_fragility(outcomes, analysis, empirical=(0, 4), stripe_ratio=SCAN_RATIO)
    ims = {"pga": [m.pga for m in motions], "sdmax": [0.01, 0.02, 0.03, 0.04],
           "sa": [motion_spectrum(m, np.array([0.5]), 0.05)[2][0] for m in motions]}[im]
    assert out["unit"] == ("m" if im == "sdmax" else "m/s^2")
    assert out["design_intensity"] == pytest.approx(np.median(ims))
    for c, s, x in zip(out["capacities"], scales, ims):
        assert c["capacity"] == pytest.approx((8.0 if s is None else s) * x) and c["censored"] == (s is None)
    if im == "sa":       # a 0.6 s sine pulse amplifies a 0.5 s, 5 %-damped oscillator
        assert all(x > 1.5 * m.pga for x, m in zip(ims, motions))
