"""A collapse margin after FEMA P695 (2009, Chs. 6–7), adapted to overturning of rocking structures
(SPEC §11).

FEMA P695 was written for conventional (yielding) seismic-force-resisting systems; this is an
adaptation: "collapse" is overturning by the check's criterion and the design intensity S_MT is the
design-level intensity of the suite in the fragility's intensity measure.  The median collapse
intensity Ŝ_CT is P695's own (Ch. 6, §6.4): the intensity at which one half of the records collapse,
counted on the records' first overturning intensities (:func:`counted_median`).  The median of the
fitted lognormal fragility is reported beside it as information (it smooths the count; the two differ
by the fit's error).

    CMR = Ŝ_CT / S_MT,  ACMR = SSF · CMR,
    β_TOT = √(β_RTR² + β_DR² + β_TD² + β_MDL²) rounded to 0.025 (P695 Eq 7-5, Table 7-2),
    ACMR_x = exp(−β_TOT Φ⁻¹(x)) (acceptable ACMR for a collapse probability x at S_MT),
    P(collapse at S_MT) = Φ(−ln(ACMR)/β_TOT).
"""
from __future__ import annotations

import math

from scipy.stats import norm

QUALITY_BETA = {"A": 0.10, "B": 0.20, "C": 0.35, "D": 0.50}
"""β of a quality rating: A superior, B good, C fair, D poor (P695 Tables 3-1, 3-2, 5-3)."""
QUALITY_KEYS = ("design_requirements", "test_data", "modeling")
BETA_RTR = 0.40
"""Record-to-record β of P695 Eq 7-2 for a period-based ductility μ_T ≥ 3 (its upper value)."""
BETA_STEP = 0.025
SSF = 1.0
SSF_REASON = ("SSF = 1: P695's spectral shape factor (Table 7-1) depends on the period-based ductility μ_T, which "
              "a rigid rocking body does not have (its lateral stiffness is negative after uplift); SSF ≥ 1 in "
              "P695, so SSF = 1 is the conservative choice")
ADAPTATION_NOTE = ("FEMA P695 was written for conventional seismic-force-resisting systems, not for rocking "
                   "structures; this is an adaptation: overturning stands for collapse, the overturning "
                   "fragility of the record suite for the incremental dynamic analysis, and SSF = 1")


def beta_total(quality: dict, beta_rtr: float = BETA_RTR) -> float:
    """β_TOT = √(β_RTR² + β_DR² + β_TD² + β_MDL²) rounded to the nearest 0.025 (P695 Eq 7-5).

    Args:
        quality: ratings "A"–"D" of design_requirements, test_data and modeling.
    """
    raw = math.sqrt(beta_rtr ** 2 + sum(QUALITY_BETA[quality[k]] ** 2 for k in QUALITY_KEYS))
    return round(math.floor(raw / BETA_STEP + 0.5) * BETA_STEP, 6)


def acceptable_acmr(beta_tot: float, probability: float) -> float:
    """ACMR_x = exp(−β_TOT Φ⁻¹(x)): the ACMR at which P(collapse at S_MT) = x (P695 Table 7-3)."""
    return math.exp(-beta_tot * norm.ppf(probability))


def collapse_probability(acmr: float, beta_tot: float) -> float:
    """P(collapse at the design intensity) = Φ(−ln(ACMR)/β_TOT) (lognormal with median ACMR·S_MT)."""
    return float(norm.cdf(-math.log(acmr) / beta_tot))


MEDIAN_DEFINITION = "counted"
"""Which median collapse intensity Ŝ_CT decides: P695's counted one (Ch. 6, §6.4), not the fitted lognormal's."""
MEDIAN_SOURCE = ("FEMA P695 (2009) Ch. 6, §6.4: Ŝ_CT is the intensity at which one half of the records "
                 "collapse, counted on each record's first overturning intensity")


def counted_median(capacities) -> dict | None:
    """Ŝ_CT counted (FEMA P695 2009, Ch. 6, §6.4): the lowest intensity at which at least half the
    records have collapsed, the k-th smallest capacity with k = ⌈n/2⌉ (for 44 records the 22nd).

    Args:
        capacities: the fragility's ``capacities`` rows ``{"capacity", "censored"}``; a censored row
            did not overturn up to its scan limit c_i, so its capacity is only known to exceed c_i.

    Returns ``{"value", "lower_bound", "upper_bound", "k", "n", "n_censored", "exact", "defined",
    "note"}`` [IM units], None without records.  Ŝ_CT is exact when the k smallest values are all
    uncensored; otherwise it is bounded below by the k-th smallest value (every true capacity is at
    least its value) and above by the k-th smallest uncensored capacity.  With more than half of the
    records censored (fewer than k uncensored) the count never reaches one half within the scan:
    Ŝ_CT is not defined there and only its lower bound is known.
    """
    rows = [(float(c["capacity"]), bool(c["censored"])) for c in capacities]
    n = len(rows)
    if n == 0:
        return None
    k = math.ceil(n / 2)
    ordered = sorted(rows, key=lambda r: (r[0], r[1]))   # at a tie the censored value sorts last (capacity > c)
    uncensored = sorted(v for v, c in rows if not c)
    n_cens = n - len(uncensored)
    exact = not any(c for _, c in ordered[:k])
    defined = len(uncensored) >= k
    lower = ordered[k - 1][0]
    upper = uncensored[k - 1] if defined else None
    if exact:
        note = f"the {_ordinal(k)} smallest of {n} first overturning intensities (half the records overturn there)"
    elif defined:
        note = (f"a censoring intensity lies below the {_ordinal(k)} smallest capacity: Ŝ_CT is only bounded, "
                f"between {lower:.4g} and {upper:.4g}")
    else:
        note = (f"{n_cens} of {n} records do not overturn within the scan (more than half): the counted Ŝ_CT is "
                f"not defined, only bounded below by {lower:.4g}")
    return {"value": lower if exact else None, "lower_bound": lower, "upper_bound": upper, "k": k, "n": n,
            "n_censored": n_cens, "exact": exact, "defined": defined, "note": note}


def _ordinal(k: int) -> str:
    return f"{k}{'th' if 10 <= k % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(k % 10, 'th')}"


def collapse_margin(fragility: dict | None, quality: dict, target: float = 0.10) -> dict | None:
    """The ``collapse_margin`` section of results.json from the ``fragility`` section.

    ``target`` [-]: the acceptable probability of collapse at the design intensity (ASCE 7-22 Table
    1.3-2 by risk category); ``passed`` says ACMR ≥ ACMR_target, None when only a lower bound of the
    ACMR is known and it is below ACMR_target.  Ŝ_CT (``median_capacity``) is the counted median of
    :func:`counted_median` (``median_definition`` = "counted"); where it is not exact (censoring below
    it, or more than half the records censored) its lower bound is used and the CMR is a lower bound.
    The fitted lognormal median (the fragility's ``median``) and its CMR, ACMR and P(collapse) are
    reported beside it (``median_fitted``, ``CMR_fitted``, ``ACMR_fitted``, ``p_collapse_design_fitted``).
    """
    if fragility is None:
        return None
    counted = counted_median(fragility["capacities"])
    if counted is None:
        return None
    b_tot = beta_total(quality)
    acmr10, acmr20 = acceptable_acmr(b_tot, 0.10), acceptable_acmr(b_tot, 0.20)
    design = fragility["design_intensity"]
    lower_bound = not counted["exact"]
    median = counted["lower_bound"]
    cmr = median / design
    acmr = SSF * cmr
    fitted = fragility["median"]
    acmr_fitted = None if fitted is None else SSF * fitted / design
    need = acceptable_acmr(b_tot, target)
    return {
        "CMR": cmr, "CMR_is_lower_bound": lower_bound, "SSF": SSF, "SSF_reason": SSF_REASON, "ACMR": acmr,
        "beta_tot": b_tot, "beta_rtr": BETA_RTR,
        "beta_components": {"record_to_record": BETA_RTR,
                            **{k: QUALITY_BETA[quality[k]] for k in QUALITY_KEYS}},
        "quality": {k: quality[k] for k in QUALITY_KEYS},
        "ACMR10": acmr10, "ACMR20": acmr20,
        "target_p_collapse": target, "ACMR_target": need,
        "p_collapse_design": collapse_probability(acmr, b_tot),
        "passed": True if acmr >= need else (None if lower_bound else False),
        "median_capacity": median, "median_definition": MEDIAN_DEFINITION, "median_source": MEDIAN_SOURCE,
        "median_counted": counted,
        "median_fitted": fitted, "median_fitted_method": fragility.get("method") if fitted is not None else None,
        "CMR_fitted": None if fitted is None else fitted / design, "ACMR_fitted": acmr_fitted,
        "p_collapse_design_fitted": None if acmr_fitted is None else collapse_probability(acmr_fitted, b_tot),
        "design_intensity": design, "im": fragility["im"], "im_label": fragility.get("im_label"),
        "unit": fragility["unit"], "fragility_beta": fragility["beta"],
        "note": ADAPTATION_NOTE,
    }
