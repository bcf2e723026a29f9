"""A collapse margin after FEMA P695 (2009, Ch. 7), adapted to overturning of rocking structures
(SPEC §11).

FEMA P695 was written for conventional (yielding) seismic-force-resisting systems; this is an
adaptation: "collapse" is overturning by the check's criterion, the median collapse intensity Ŝ_CT is
the median of the fitted overturning fragility and the design intensity S_MT is the design-level
intensity of the suite in the same intensity measure.

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


def collapse_margin(fragility: dict | None, quality: dict, target: float = 0.10) -> dict | None:
    """The ``collapse_margin`` section of results.json from the ``fragility`` section.

    ``target`` [-]: the acceptable probability of collapse at the design intensity (ASCE 7-22 Table
    1.3-2 by risk category); ``passed`` says ACMR ≥ ACMR_target, None when only a lower bound of the
    ACMR is known and it is below ACMR_target.  Without a fitted median (fewer than two records
    overturn within the scan) the CMR is a lower bound: the smallest censoring intensity over the
    design intensity (the median of the capacities is at least that).
    """
    if fragility is None:
        return None
    b_tot = beta_total(quality)
    acmr10, acmr20 = acceptable_acmr(b_tot, 0.10), acceptable_acmr(b_tot, 0.20)
    design = fragility["design_intensity"]
    median = fragility["median"]
    lower_bound = median is None
    if lower_bound:
        cens = [c["capacity"] for c in fragility["capacities"] if c["censored"]]
        if not cens:
            return None
        median = min(cens)
    cmr = median / design
    acmr = SSF * cmr
    return {
        "CMR": cmr, "CMR_is_lower_bound": lower_bound, "SSF": SSF, "SSF_reason": SSF_REASON, "ACMR": acmr,
        "beta_tot": b_tot, "beta_rtr": BETA_RTR,
        "beta_components": {"record_to_record": BETA_RTR,
                            **{k: QUALITY_BETA[quality[k]] for k in QUALITY_KEYS}},
        "quality": {k: quality[k] for k in QUALITY_KEYS},
        "ACMR10": acmr10, "ACMR20": acmr20,
        "target_p_collapse": target, "ACMR_target": acceptable_acmr(b_tot, target),
        "p_collapse_design": collapse_probability(acmr, b_tot),
        "passed": True if acmr >= acceptable_acmr(b_tot, target) else (None if lower_bound else False),
        "median_capacity": median, "design_intensity": design, "im": fragility["im"], "unit": fragility["unit"],
        "fragility_beta": fragility["beta"],
        "note": ADAPTATION_NOTE,
    }
