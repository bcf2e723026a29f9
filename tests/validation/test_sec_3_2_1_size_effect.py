"""Thesis Sec 3.2.1 (size effect, Eq 3.13, Fig 3.7), Example 3.1 and Eqs 3.16/3.17: two blocks with
tan α = 0.2, R = 2 m and 3 m, λ = 1/3, released from 0.75 α (linearized Eq 3.15).  Expected values:
tests/validation/data/cases.json (sec3.2.1_*, ex3.1_tau, eq3.16, eq3.17)."""
from __future__ import annotations

import math

from casedata import case_tests
from rockdesign.planar.design.frequencies import frequency_parameter
from rockdesign.planar.dynamics.simulate import simulate
from support import G, block_from_p

ALPHA = math.atan(0.2)


def _first_impact(R):
    p = frequency_parameter(R, 1 / 3, G)
    return simulate(block_from_p(p, 0.2), None, theta0=0.75 * ALPHA, t_end=2, model="linear").impact_times[0]


def _initial_acceleration(R):
    """θ̈(t0) of the linearized Eq 3.15 for θ0 = 0.75 α: p²(θ0 − α) [1/s²]."""
    return frequency_parameter(R, 1 / 3, G) ** 2 * (0.75 * ALPHA - ALPHA)


COMPUTE = {
    "sec3.2.1_p1": lambda: frequency_parameter(2.0, 1 / 3, G),
    "sec3.2.1_p2": lambda: frequency_parameter(3.0, 1 / 3, G),
    "sec3.2.1_t1": lambda: _first_impact(2.0),
    "sec3.2.1_t2": lambda: _first_impact(3.0),
    "ex3.1_tau": lambda: frequency_parameter(2.0, 1 / 3, G) * _first_impact(2.0),   # τ = p t1 = acosh 4
    "eq3.16": lambda: _initial_acceleration(2.0),
    "eq3.17": lambda: _initial_acceleration(3.0),
}

test_case = case_tests(COMPUTE)
