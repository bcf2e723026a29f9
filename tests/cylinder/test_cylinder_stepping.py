"""The cylinder integrator's step mechanics behind its speed: within a step a record's ü_g is linear.

The kernel evaluates the record at the two ends of a step and interpolates it at the DOP853 stages;
that is exact only because no step crosses a record sample.  Checked here on a record pair run (every
accepted step lies inside one sample interval) and, for the right-hand side, against the per-stage
table look-up it replaced.
"""
from __future__ import annotations

import numpy as np

from rockdesign.cylinder.engine import simulate_cylinder
from rockdesign.cylinder.eom import ground_xy, parameters, rhs, rhs_ground
from rockdesign.cylinder.system import cylinder
from rockdesign.cylinder.pairs import parse_pair


def _pair():
    return parse_pair("record:p695-ff/1,resultant_pga=0.3g", gravity=9.81).pair


def test_rhs_is_rhs_ground_at_the_interpolated_record():
    pair = _pair()
    cyl = cylinder(3.0, 0.6, contact="spring-dashpot")
    par = parameters(cyl.R, cyl.alpha, cyl.g, cyl.contact_frequency, cyl.contact_damping, True, False)
    sx = np.ascontiguousarray(pair.x, dtype=np.float64)
    sy = np.ascontiguousarray(pair.y, dtype=np.float64)
    params = np.ascontiguousarray(pair.params, dtype=np.float64)
    rng = np.random.default_rng(12)
    dt = pair.dt
    for _ in range(50):
        i = int(rng.integers(100, sx.size - 2))
        c = float(rng.random())
        y = np.array([rng.uniform(1e-6, 0.2), rng.normal(), rng.uniform(-3, 3), rng.normal(), 1e-5, 1e-4])
        a0 = ground_xy(i * dt, True, int(pair.kind), params, sx, sy, 1.0, 1.0)
        a1 = ground_xy((i + 1) * dt, True, int(pair.kind), params, sx, sy, 1.0, 1.0)
        direct, interp = np.zeros(6), np.zeros(6)
        rhs((i + c) * dt, y, direct, par, True, int(pair.kind), params, sx, sy, 1.0, 1.0)
        rhs_ground(y, interp, par, a0[0] + c * (a1[0] - a0[0]), a0[1] + c * (a1[1] - a0[1]))
        np.testing.assert_allclose(interp, direct, rtol=1e-12, atol=1e-12 * np.max(np.abs(direct)))


def test_no_step_crosses_a_record_sample():
    pair = _pair()
    for contact in ("rigid", "spring-dashpot"):
        r = simulate_cylinder(cylinder(3.0, 0.6, contact=contact), pair, t_end=12.0)
        x = r.t / pair.dt
        moving = r.t[1:] > r.uplift_time
        eps = 1e-9
        lo = np.floor(x[:-1] + eps)[moving]             # sample interval where each step starts
        hi = np.ceil(x[1:] - eps)[moving]               # … and where it ends
        assert np.all(hi - lo <= 1.0 + 1e-12), contact
        # and the stretched steps do land on samples: every sample after uplift is a step point
        samples = np.arange(np.ceil(r.uplift_time / pair.dt), np.floor(min(r.t[-1], pair.duration) / pair.dt))
        on = np.isclose(x[:, None], samples[None, :], atol=1e-9).any(axis=0)
        assert on.all(), contact
