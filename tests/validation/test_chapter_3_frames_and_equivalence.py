"""Thesis Ch. 3 curved extensions, frames and equivalent blocks: Examples 3.4, 3.5, 3.7, Example 3.8 and Sec 3.4.1 (Eq 3.81, Fig 3.28), Eq 2.24,
Eq 3.65, Sec 3.3.3 (Eq 3.71), Examples 3.9 and 3.10 (c_r of Eq 3.80, p̂ of Eqs 3.76/3.94, a_p/g = 2α,
T_p = 2π/(2.4 p̂)).  Expected values: tests/validation/data/cases.json (ids below)."""
from __future__ import annotations

import math

from casedata import case_tests
from rockdesign.planar.design.equivalence import equivalent_size, equivalent_size_from_spectra, frame_size_factor
from rockdesign.planar.design.frequencies import (critical_rolling_frequency_parameter, frame_frequency_parameter,
                                           frequency_parameter)
from rockdesign.planar.design.geometry import rotation_capacity_curved, wedge_angle
from rockdesign.planar.design.restitution import restitution_block, restitution_frame
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import pulse_motion
from rockdesign.planar.system import Column, RockingSystem
from support import G


def _example(c_r, p_hat, tan_alpha=0.1):
    """[c_r, p̂ [1/s], a_p/g = 2α (â_p = 2 at linearized uplift), T_p = 2π/(2.4 p̂) [s]] of Examples 3.7–3.10."""
    return [c_r, p_hat, 2 * math.atan(tan_alpha), 2 * math.pi / (2.4 * p_hat)]


def _block_example(R, tan_alpha, lam):
    return _example(restitution_block(math.atan(tan_alpha), lam), frequency_parameter(R, lam, G), tan_alpha)


def _frame_example(R, lam, gamma):
    return _example(restitution_frame(math.atan(0.1), lam, gamma), frame_frequency_parameter(R, lam, gamma, G))


def _example_3_5():
    """[p (Eq 3.13), ω_p/p, a_p/(g tan α)] of a block 2H = 3 m, tan α = 0.1 under a_p = 0.38 g, T_p = 0.95 s."""
    p = frequency_parameter(math.hypot(1.5, 0.15), 1 / 3, G)
    return [p, 2 * math.pi / 0.95 / p, 0.38 / 0.1]


def _example_3_4(R, tan_alpha, tan_alpha_ext, lam):
    """[β (Eq 3.44), p, a_p/g = 2α (â_p = 2), ω_p = 5p, T_p, β/α] of Example 3.4 (ρ = 0.25)."""
    beta, p, alpha = wedge_angle(tan_alpha, tan_alpha_ext, 0.25), frequency_parameter(R, lam, G), math.atan(tan_alpha)
    return [beta, p, 2 * alpha, 5 * p, 2 * math.pi / (5 * p), beta / alpha]


def _example_3_4_stays_rolling():
    """Example 3.4 case a: under the sine pulse â_p = 2, ω_p/p = 5 (linearized) both columns stay in phase I."""
    rolling = []
    for R, tan_a, tan_ae, lam in ((2.0, 0.11, 0.16, 0.33), (3.0, 0.12, 0.15, 0.4)):
        a = math.atan(tan_a)
        H, B = R * math.cos(a), R * math.sin(a)
        system = RockingSystem("ex3.4", "column", Column(H, B, 1000.0, lam, "curved", tan_ae * H, 0.25 * 2 * H), g=G)
        p = frequency_parameter(R, lam, G)
        r = simulate(system.with_restitution(0.9), pulse_motion("sine", 2 * G * a, 2 * math.pi / (5 * p)),
                     model="linear", t_end=10.0)
        rolling.append(r.uplift_time is not None and not r.events_of("phase-rocking"))
    return all(rolling)


def _example_3_7_b1ec():
    """[β, c_r, θc, p̂ (Eq 3.94 at ρc), a_p/g = 2α, T_p = 2π/(2.4 p̂)] of Example 3.7 B1ec."""
    a, ae = math.atan(0.1), math.atan(0.15)
    p_hat = critical_rolling_frequency_parameter(2.0, 0.33, 0, a, ae, G)
    return [wedge_angle(0.1, 0.15, 0.165), restitution_block(a, 0.33), rotation_capacity_curved(0.1, 0.15, 0.165),
            p_hat, 2 * a, 2 * math.pi / (2.4 * p_hat)]


COMPUTE = {
    "ex3.4_B1ec": lambda: _example_3_4(2.0, 0.11, 0.16, 0.33),
    "ex3.4_B2ec": lambda: _example_3_4(3.0, 0.12, 0.15, 0.4),
    "ex3.4_case_a_pure_rolling": _example_3_4_stays_rolling,
    "ex3.7_B1ec": _example_3_7_b1ec,
    "ex3.8_Rhat": lambda: frame_size_factor(0.422, 10),
    "ex3.8_reduction": lambda: 100 * (1 - frame_size_factor(0.422, 10) / frame_size_factor(1 / 3, 10)),
    "sec3.4.1_Rhat_lam0.333_gam5": lambda: frame_size_factor(1 / 3, 5),
    "sec3.4.1_Rhat_lam0.333_gaminf": lambda: frame_size_factor(1 / 3, math.inf),
    "sec3.4.1_Rhat_lam0.490_gaminf": lambda: frame_size_factor(0.49, math.inf),
    "eq2.24_vs_3.81": lambda: frame_size_factor(1 / 3, 5),
    "eq3.65": lambda: equivalent_size_from_spectra(4.53, 3.21),
    "eq3.71_B2a": lambda: equivalent_size(1.0, 1 / 3, 0.0, math.atan(0.2) / math.atan(0.1)),
    "ex3.5": _example_3_5,
    "ex3.7_B2": lambda: _block_example(1.5, 0.1, 0.36),
    "ex3.9_B2": lambda: _block_example(3.0, 0.15, 0.35),
    "ex3.10_F2": lambda: _frame_example(2.5, 0.34, 15),
    "ex3.10_B4": lambda: _frame_example(4.0, 0.37, 0),
    "ex3.9_F1": lambda: _example(restitution_frame(math.atan(0.1), 0.42, 15), frame_frequency_parameter(2.0, 0.42, 15, G)),
    "ex3.10_F1ec": lambda: _example(restitution_frame(math.atan(0.1), 0.38, 10), critical_rolling_frequency_parameter(
        2.0, 0.38, 10, math.atan(0.1), math.atan(0.15), G)),
}

test_case = case_tests(COMPUTE)
