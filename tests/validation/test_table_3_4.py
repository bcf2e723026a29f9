"""Thesis Table 3.4: five oscillators (2H = 3 m, tan α = 0.1, tan α' = 0.2, λ = 1/3) — a block B1, curved
extensions B2ec–B4ec (ρ = 0.25, 0.5, 1), flat extensions B5ef — under the antisymmetric Ricker pulse
a_p = 0.38 g, T_p = 0.95 s (Eq A.2).  Expected values: tests/validation/data/cases.json (tab3.4_*)."""
from __future__ import annotations

import math
from functools import lru_cache

from casedata import case_tests
from rockdesign.planar.design.quantities import design_quantities
from rockdesign.planar.design.restitution import restitution_flat_extensions
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import pulse_motion
from support import G, table34_column

RICKER = pulse_motion("ricker-anti", 0.38 * G, 0.95)


@lru_cache(maxsize=None)
def _response(name):
    return simulate(table34_column(name), RICKER, t_end=None if name == "B5ef" else 10.0)


def _c_r(name):
    return design_quantities(table34_column(name))["c_r"].value


COMPUTE = {f"tab3.4_{n}_cr": (lambda n=n: _c_r(n)) for n in ("B1", "B2ec", "B3ec", "B4ec")}
COMPUTE.update({f"tab3.4_{n}_tup": (lambda n=n: _response(n).uplift_time) for n in ("B1", "B2ec", "B3ec", "B4ec", "B5ef")})
COMPUTE.update({f"tab3.4_{n}_thmax": (lambda n=n: _response(n).theta_max_over_alpha)
                for n in ("B1", "B2ec", "B3ec", "B4ec")})
COMPUTE["tab3.4_B5ef_cr"] = lambda: restitution_flat_extensions(math.atan(0.1), math.atan(0.2), 1 / 3, printed=True)
COMPUTE["tab3.4_B5ef_overturn"] = lambda: _response("B5ef").overturn_mode == "dynamic"

test_case = case_tests(COMPUTE)
