"""The FEMA P695-style collapse margin (SPEC §11, FEMA P695 2009 Chs. 6–7): β_TOT from the quality
ratings, acceptable ACMRs against the check values of SPEC §11 (β_TOT 0.525 → ACMR10% 1.96,
ACMR20% 1.56; 0.600 → 2.16, 1.66), the counted median collapse intensity Ŝ_CT (P695 §6.4: the
intensity at which half the records collapse) against numpy's inverted-CDF quantile and hand-built
order statistics, and the [analysis] quality keys."""
from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.stats import norm

from rockdesign.acceptance.collapse_margin import (acceptable_acmr, beta_total, collapse_margin, collapse_probability,
                                                  counted_median)
from rockdesign.errors import ProjectError
from rockdesign.kinds import parse_document as parse_project

B = {"design_requirements": "B", "test_data": "B", "modeling": "B"}


@pytest.mark.parametrize("quality,expected", [
    (("B", "B", "B"), 0.525),          # √(0.4² + 3·0.2²) = 0.529 → 0.525
    (("B", "C", "B"), 0.600),          # √(0.4² + 0.2² + 0.35² + 0.2²) = 0.602 → 0.600
    (("A", "A", "A"), 0.425),          # P695 Table 7-2a, superior/superior/superior
    (("D", "D", "D"), 0.950),          # P695 Table 7-2, poor/poor/poor
])
def test_beta_total_rounded_to_0_025(quality, expected):
    q = dict(zip(("design_requirements", "test_data", "modeling"), quality))
    assert beta_total(q) == pytest.approx(expected, abs=1e-12)


KEYS = ("design_requirements", "test_data", "modeling")
QUALITY_COMBINATIONS = list(itertools.product("ABCD", repeat=3))


def _nearest_multiple_of_0_025(quality):
    """Independent rounding: β_TOT by numpy, then the closest point of an explicit grid of 0.025 multiples."""
    raw = np.sqrt(0.40 ** 2 + sum({"A": 0.10, "B": 0.20, "C": 0.35, "D": 0.50}[r] ** 2 for r in quality))
    grid = 0.025 * np.arange(0, 81)
    return grid[np.argmin(np.abs(grid - raw))], raw


@pytest.mark.parametrize("quality", QUALITY_COMBINATIONS, ids="".join)
def test_beta_total_rounds_to_nearest_0_025_for_every_rating(quality):
    """All 64 ratings (P695 Eq 7-5, Table 7-2): rounding to the nearest 0.025, not truncating."""
    expected, raw = _nearest_multiple_of_0_025(quality)
    q = dict(zip(("design_requirements", "test_data", "modeling"), quality))
    assert beta_total(q) == pytest.approx(expected, abs=1e-12)
    assert abs(beta_total(q) - raw) <= 0.0125 + 1e-12


def test_ratings_that_round_up_are_among_the_64():
    """The 64 cases tell rounding from truncation: 12 of them round up (A/A/B → 0.475, B/C/C → 0.675);
    B/B/D is exactly 0.700 (√0.49), which a floating-point truncation may also turn into 0.675."""
    up = [q for q in QUALITY_COMBINATIONS if _nearest_multiple_of_0_025(q)[0] > _nearest_multiple_of_0_025(q)[1]]
    assert len(up) == 12 and ("A", "A", "B") in up and ("B", "C", "C") in up
    assert beta_total(dict(zip(KEYS, "AAB"))) == pytest.approx(0.475, abs=1e-12)
    assert beta_total(dict(zip(KEYS, "BCC"))) == pytest.approx(0.675, abs=1e-12)
    assert beta_total(dict(zip(KEYS, "BBD"))) == pytest.approx(0.700, abs=1e-12)


@pytest.mark.parametrize("beta_tot,acmr10,acmr20", [(0.525, 1.96, 1.56), (0.600, 2.16, 1.66)])
def test_acceptable_acmr_matches_spec(beta_tot, acmr10, acmr20):
    assert acceptable_acmr(beta_tot, 0.10) == pytest.approx(acmr10, abs=0.005)
    assert acceptable_acmr(beta_tot, 0.20) == pytest.approx(acmr20, abs=0.005)
    # at exactly the acceptable ACMR the collapse probability is the target
    assert collapse_probability(acceptable_acmr(beta_tot, 0.10), beta_tot) == pytest.approx(0.10, abs=1e-12)


def _fragility(median, design, censored=(), capacities=None):
    """A fragility section with uncensored ``capacities`` (default: three whose counted median is
    ``median``) and ``censored`` censoring values; the fitted median is ``median``."""
    if capacities is None:
        capacities = () if median is None else (0.6 * median, median, 1.7 * median)
    rows = [{"id": f"u{i}", "capacity": c, "censored": False} for i, c in enumerate(capacities)]
    rows += [{"id": f"c{i}", "capacity": c, "censored": True} for i, c in enumerate(censored)]
    return {"median": median, "beta": 0.5, "design_intensity": design, "im": "pga", "unit": "m/s^2",
            "capacities": rows, "method": "moments"}


def test_collapse_margin_values_at_each_target():
    """The counted Ŝ_CT (here equal to the fitted median) over the design intensity, at each category's target."""
    m = collapse_margin(_fragility(4.8, 2.0), B)
    assert m["median_definition"] == "counted" and m["median_capacity"] == pytest.approx(4.8)
    assert m["CMR"] == pytest.approx(2.4) and m["SSF"] == 1.0 and m["ACMR"] == pytest.approx(2.4)
    assert m["beta_tot"] == 0.525 and m["passed"] and m["target_p_collapse"] == 0.10
    assert m["p_collapse_design"] == pytest.approx(norm.cdf(-math.log(2.4) / 0.525))
    assert "conventional" in m["note"] and "adaptation" in m["note"]
    low = collapse_margin(_fragility(3.6, 2.0), B)          # ACMR 1.8 < 1.96
    assert low["passed"] is False
    # risk categories III (5 %) and IV (2.5 %): ACMR_x = exp(−β Φ⁻¹(x)) = 2.37 and 2.80 with β_TOT 0.525
    for x, need in ((0.05, 2.37), (0.025, 2.80)):
        mx = collapse_margin(_fragility(4.8, 2.0), B, x)
        assert mx["ACMR_target"] == pytest.approx(math.exp(-0.525 * norm.ppf(x))) == pytest.approx(need, abs=0.005)
        assert mx["passed"] is (2.4 >= need)


def test_without_a_fit_the_cmr_is_a_lower_bound():
    """Every record censored: the counted Ŝ_CT is not defined, only bounded below by the smaller censoring
    value (k = 1 of n = 2)."""
    m = collapse_margin(_fragility(None, 2.0, censored=(16.0, 18.0)), B)
    assert m["CMR_is_lower_bound"] and m["CMR"] == pytest.approx(8.0) and m["passed"]
    assert m["median_counted"]["defined"] is False and m["ACMR_fitted"] is None


# --------------------------------------------------------------- Ŝ_CT counted (FEMA P695 Ch. 6, §6.4)

def _p695_count(values) -> float:
    """Independent: the lowest intensity at which at least half of the records have collapsed, i.e. the
    smallest x with empirical CDF F(x) ≥ 1/2 — numpy's "inverted_cdf" quantile at 0.5."""
    return float(np.quantile(np.asarray(values, dtype=float), 0.5, method="inverted_cdf"))


@pytest.mark.parametrize("n", [5, 11, 22, 44])
def test_counted_median_is_the_intensity_at_which_half_the_records_collapse(n):
    rng = np.random.default_rng(n)
    x = np.exp(rng.normal(math.log(4.0), 0.5, size=n))
    c = counted_median([{"capacity": v, "censored": False} for v in x])
    assert c["exact"] and c["defined"] and c["k"] == math.ceil(n / 2) and c["n_censored"] == 0
    assert c["value"] == _p695_count(x)
    # closed form: the ⌈n/2⌉-th order statistic; for odd n numpy's median, for even n the lower middle value
    xs = np.sort(x)
    assert c["value"] == xs[math.ceil(n / 2) - 1]
    if n % 2:
        assert c["value"] == float(np.median(x))
    else:
        assert xs[n // 2 - 1] == c["value"] < float(np.median(x)) < xs[n // 2]
    # exactly k of n records have a capacity ≤ Ŝ_CT: the fraction collapsed reaches one half there
    assert int(np.sum(x <= c["value"])) == math.ceil(n / 2)


def test_counted_median_with_censoring():
    """Censored above the count: exact, the numpy median of the uncensored capacities when they are the odd
    lower part (hand-built); more than half censored: not defined, bounded below; censoring below the k-th
    capacity: only bounded."""
    unc = [1.0, 2.0, 3.0, 4.0, 5.0]
    rows = [{"capacity": v, "censored": False} for v in unc] + [{"capacity": 40.0, "censored": True}] * 4
    c = counted_median(rows)                                  # n = 9, k = 5: the 5th smallest = 5.0
    assert c["exact"] and c["value"] == 5.0 == _p695_count(unc + [np.inf] * 4)
    rows = [{"capacity": v, "censored": False} for v in unc[:3]] + [{"capacity": 8.0, "censored": True}] * 4
    c = counted_median(rows)                                  # n = 7, k = 4, 3 uncensored: undefined
    assert not c["defined"] and c["value"] is None and c["lower_bound"] == 8.0 and c["upper_bound"] is None
    assert "not defined" in c["note"] and "4 of 7" in c["note"]
    rows = [{"capacity": v, "censored": False} for v in (1.0, 2.0, 6.0, 7.0)] + [{"capacity": 1.5, "censored": True}]
    c = counted_median(rows)                                  # n = 5, k = 3: between 2.0 and 6.0
    assert c["defined"] and not c["exact"] and c["lower_bound"] == 2.0 and c["upper_bound"] == 6.0
    m = collapse_margin(_fragility(None, 1.0, capacities=()) | {"capacities": [dict(r, id="r") for r in rows]}, B)
    assert m["CMR_is_lower_bound"] and m["CMR"] == pytest.approx(2.0) and m["passed"] is True


def test_counted_median_governs_and_the_fitted_one_is_reported():
    """A fragility whose fitted median (5.0) differs from the count (4.0): the counted Ŝ_CT decides, the
    fitted median's CMR, ACMR and P(collapse) are reported beside it."""
    frag = _fragility(5.0, 2.0, capacities=(3.0, 3.5, 4.0, 6.0, 9.0))
    m = collapse_margin(frag, B)
    assert m["median_capacity"] == 4.0 and m["ACMR"] == pytest.approx(2.0) and not m["CMR_is_lower_bound"]
    assert m["median_fitted"] == 5.0 and m["ACMR_fitted"] == pytest.approx(2.5)
    assert m["p_collapse_design"] == pytest.approx(norm.cdf(-math.log(2.0) / 0.525), rel=1e-12)
    assert m["p_collapse_design_fitted"] == pytest.approx(norm.cdf(-math.log(2.5) / 0.525), rel=1e-12)
    assert m["passed"] is True and "§6.4" in m["median_source"]
    assert collapse_margin(frag | {"median": None}, B)["ACMR_fitted"] is None


PROJECT = """
[project]
name = "q"
[column]
height = "3 m"
width = "0.6 m"
mass = "2 t"
mass_distribution = 0.3333
[analysis]
"""


@pytest.mark.parametrize("line,key", [
    ('quality = { design_requirements = "E" }', "analysis.quality.design_requirements"),
    ('quality = { modelling = "B" }', "analysis.quality.modelling"),
    ('quality = "B"', "analysis.quality"),
    ('fragility_im = "pgv"', "analysis.fragility_im"),
    ('fragility_im = "sa"', "analysis.fragility_period"),
    ('fragility_period = "1 s"', "analysis.fragility_period"),
    ('ensemble_size = -1', "analysis.ensemble_size"),
    ('ensemble_size = 2.5', "analysis.ensemble_size"),
    ('seed = "x"', "analysis.seed"),
])
def test_bad_analysis_keys_raise_project_errors(line, key):
    import tomllib
    with pytest.raises(ProjectError) as exc:
        parse_project(tomllib.loads(PROJECT + line + "\n"), file="p.toml")
    assert exc.value.key == key


def test_analysis_keys_parse():
    import tomllib
    text = PROJECT + ('quality = { test_data = "C" }\nfragility_im = "sa"\nfragility_period = "0.8 s"\n'
                      'ensemble_size = 0\nseed = 3\n')
    a = parse_project(tomllib.loads(text), file="p.toml").analysis
    assert dict(a.quality) == {"design_requirements": "B", "test_data": "C", "modeling": "B"}
    assert a.fragility_im == "sa" and a.fragility_period == pytest.approx(0.8)
    assert a.ensemble_size == 0 and a.seed == 3
    default = parse_project(tomllib.loads(PROJECT), file="p.toml").analysis
    assert default.fragility_im == "pga" and default.ensemble_size == 8 and dict(default.quality) == B
