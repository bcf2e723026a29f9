"""Thesis Example 2.1 (Eqs 2.8, 2.10, 2.15): free rocking of a block, p = 2.2 1/s, tan α = 0.1, λ = 1/3,
released from θ0 = 0.08 rad.  Expected values: tests/validation/data/cases.json (ex2.1_*); the thesis
prints t1 = 1.044 s, |θ̇1| = 0.2156 rad/s, |θ̇2| = 0.2124 rad/s, which do not reproduce (see the cases'
notes) — the engine is compared with the reference solution."""
from __future__ import annotations

import math
from functools import lru_cache

from casedata import case_tests
from rockdesign.planar.design.frequencies import rocking_period
from rockdesign.planar.design.restitution import restitution_block
from rockdesign.planar.dynamics.simulate import simulate
from support import block_from_p


@lru_cache(maxsize=None)   # one analysis per model for all cases of the module
def _free(model="exact", t_end=4.0):
    return simulate(block_from_p(2.2, 0.1), None, theta0=0.08, t_end=t_end, model=model)


COMPUTE = {
    "ex2.1_V_over_mR2": lambda: 2.2 ** 2 * (1 + 1 / 3) * (math.cos(math.atan(0.1) - 0.08) - math.cos(math.atan(0.1))),
    "ex2.1_TR_quarter": lambda: rocking_period(2.2, math.atan(0.1), 0.08) / 4,
    "ex2.1_cr": lambda: restitution_block(math.atan(0.1), 1 / 3),
    "ex2.1_t1_exact": lambda: _free().impact_times[0],
    "ex2.1_thd1_exact": lambda: abs(_free().events_of("impact")[0].state[1]),
    "ex2.1_thd2_exact": lambda: abs(_free().events_of("impact")[1].state[1]),
    "ex2.1_t1_linear": lambda: _free("linear", 2.0).impact_times[0],
}

test_case = case_tests(COMPUTE)
