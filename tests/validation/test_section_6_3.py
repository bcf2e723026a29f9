"""Thesis Sec 6.3 (the shake-table rocking frame and podium model) and Eqs 6.14–6.26: γ, η (Eqs 6.16,
6.17), S_r (Eq 6.18 = Eq 4.25), k_s and T_s (Eqs 6.14, 6.15), prototype period (Sec 6.3.4), λ from
the measured p (Eqs 6.20, 6.24), c_r of frames and columns (Eqs 6.22/6.23, 6.26, Sec 6.3.5).
Expected values: tests/validation/data/cases.json (ids below)."""
from __future__ import annotations

import math

from casedata import case_tests
from rockdesign.planar.design.frequencies import uplifted_frequency_ratio
from rockdesign.planar.design.restitution import restitution_block, restitution_frame


def _lambda_from_p(p, R, g):
    """λ = g/(R p²) − 1 (Eq 3.13 solved for λ; Eqs 6.20, 6.24)."""
    return g / (R * p * p) - 1


def _stiffness_and_period():
    """k_s = 24 EI/h³ (two bars fixed at both ends, 12 EI/h³ each) [kN/m] and T_s = 2π√(m_T/k_s) [s]
    (Eqs 6.14, 6.15)."""
    E, h, I, m_T = 70e9, 0.401, 900e-12, 27.52
    k = 24 * E * I / h ** 3
    return [k / 1000, 2 * math.pi * math.sqrt(m_T / k)]


COMPUTE = {
    "sec6.3_gamma_eta": lambda: [17.05 / (2 * 3.94), 27.52 / 17.05],   # γ = m_B/(N m_C), η = m_T/m_B
    "sec6.3_Sr": lambda: uplifted_frequency_ratio(0.54, 2.1637, 1.6141, math.atan(0.1394)),
    "sec6.3_ks_Ts": _stiffness_and_period,
    "sec6.3.4_prototype_T": lambda: 0.222 * math.sqrt(6),                 # Froude similitude, length scale 6
    "eq6.20_lambda_g9.81": lambda: _lambda_from_p(5.018, 0.2524, 9.81),
    "eq6.20_lambda_g9.807": lambda: _lambda_from_p(5.018, 0.2524, 9.807),
    "eq6.24_lambda": lambda: _lambda_from_p(4.8883, 0.2528, 9.807),
    "eq6.22_crth_frame_gamma1.682": lambda: restitution_frame(math.atan(0.1394), 0.54, 1.682),
    "eq6.22_crth_frame_gamma3.692": lambda: restitution_frame(math.atan(0.1394), 0.54, 3.692),
    "eq6.26_crth": lambda: restitution_block(math.atan(0.15), 0.6235),
}

test_case = case_tests(COMPUTE)
