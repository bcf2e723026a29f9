"""Thesis Ch. 4, the rocking podium: S_r (Eqs 4.25/4.26, Fig 4.5), c_r (Eq 4.20), the uplift thresholds of
the 2DOF model (Eq 4.7), the reference podium's periods (Secs 4.2.3, 4.2.4).  Expected values:
tests/validation/data/cases.json (ids below)."""
from __future__ import annotations

import math

from casedata import case_tests
from rockdesign.planar.design.frequencies import frequency_parameter, uplifted_frequency_ratio
from rockdesign.planar.design.restitution import restitution_podium
from rockdesign.planar.design.uplift import podium_uplift_thresholds
from support import G

ALPHA = math.atan(0.15)


def _pulse_period_6m():
    """T_p [s] at ω_p/p = 8 for 2H = 6 m, tan α = 0.15, λ = 1/3 (Eq 3.13)."""
    p = frequency_parameter(math.hypot(3.0, 0.45), 1 / 3, G)
    return 2 * math.pi / (8 * p)


COMPUTE = {
    "eq4.25_Sr_eta1": lambda: uplifted_frequency_ratio(1 / 3, 10, 1, ALPHA),
    "eq4.25_Sr_eta5": lambda: uplifted_frequency_ratio(1 / 3, 10, 5, ALPHA),
    "eq4.25_Sr_eta10": lambda: uplifted_frequency_ratio(1 / 3, 10, 10, ALPHA),
    "eq4.25_Sr_eta1e+09": lambda: uplifted_frequency_ratio(1 / 3, 10, 1e9, ALPHA),
    "eq4.20_podium_cr": lambda: restitution_podium(ALPHA, 1 / 3, 10, 5),
    "eq4.7_thresholds": lambda: list(podium_uplift_thresholds(0.15, G, 10, 5, 13.2, 0.01, 0.002, -0.01)),
    "sec4.2.4_Ts_for_ws_over_p_6": lambda: 2 * math.pi / (6 * 2.2),
    "sec4.2.4_Ts_for_ws_over_p_3": lambda: 2 * math.pi / (3 * 2.2),
    "sec4.2.3_Tp_6m": _pulse_period_6m,
}

test_case = case_tests(COMPUTE)
