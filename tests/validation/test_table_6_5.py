"""Thesis Table 6.5 and Sec 6.4.2: the shake-table columns F01–F08 (2H = 500 mm; tan α = 0.1 / 0.15,
tan α' = 0.3, ρ = 0.25 / 0.5 / 1): β (Eq 3.44), θc (corrected Eq 3.56), ρc (Eq 3.55), R.  Expected
values: tests/validation/data/cases.json (tab6.5_*, sec6.4.2_rho_c)."""
from __future__ import annotations

import math

from casedata import case_tests
from rockdesign.planar.design.geometry import critical_curvature, half_diagonal, rotation_capacity_curved, wedge_angle


def _beta_theta_c(tan_alpha, rho):
    return [wedge_angle(tan_alpha, 0.3, rho), rotation_capacity_curved(tan_alpha, 0.3, rho)]


COMPUTE = {
    "tab6.5_F01": lambda: math.atan(0.1),
    "tab6.5_F05": lambda: math.atan(0.15),
    "tab6.5_F02": lambda: _beta_theta_c(0.1, 0.25),
    "tab6.5_F03": lambda: _beta_theta_c(0.1, 0.5),
    "tab6.5_F04": lambda: _beta_theta_c(0.1, 1.0),
    "tab6.5_F06": lambda: _beta_theta_c(0.15, 0.25),
    "tab6.5_F07": lambda: _beta_theta_c(0.15, 0.5),
    "tab6.5_F08": lambda: _beta_theta_c(0.15, 1.0),
    "tab6.5_R": lambda: [1000 * half_diagonal(0.025, 0.25), 1000 * half_diagonal(0.0375, 0.25)],   # R [mm]
    "sec6.4.2_rho_c": lambda: [critical_curvature(0.1, 0.3), critical_curvature(0.15, 0.3)],
}

test_case = case_tests(COMPUTE)
