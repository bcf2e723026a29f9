"""Every grid point of a spectrum equals a direct ``simulate()`` call (bit for bit).

The spectrum kernel builds the pulse of each grid point inside numba; ``simulate`` takes the
``GroundMotion`` of ``pulse_motion``. Both must run the very same analysis: same pulse parameters,
same end time (excitation end + 10 s), same tolerances. Compared: θ_max (exact float equality),
overturning by both criteria and the impacts before overturning — with the energy stop (as the
spectrum runs) and against the full-length run (the stop does not change the result).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from casedata import expected

from support import block_from_p, reference_podium, table34_column
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import pulse_motion
from rockdesign.planar.spectra import SpectrumRequest, compute_spectrum, parse_axis
from rockdesign.planar.system import Column, RockingSystem

CASES = [
    # (id, system factory, structure, equations, pulse, x axis, y axis, overturn)
    ("B1-ricker-anti", lambda: table34_column("B1"), "auto", "exact", "ricker-anti", "omega_p/p:0.5:12:9",
     "ap/up:0:8:7", "static"),
    ("B1-linear-sine", lambda: table34_column("B1"), "auto", "linear", "sine", "omega_p/p:1:10:7", "ap/up:0.5:9:6",
     "dynamic"),
    ("B2ec-ricker-sym", lambda: table34_column("B2ec"), "auto", "exact", "ricker-sym", "Tp:0.3:3:7", "ap/g:0.05:0.8:6",
     "static"),
    ("B4ec-cycloidal-c", lambda: table34_column("B4ec"), "auto", "exact", "cycloidal-c", "omega_p/p:1:8:6",
     "ap/up:1:8:6", "dynamic"),
    ("B5ef-cycloidal-b", lambda: table34_column("B5ef"), "auto", "exact", "cycloidal-b", "omega_p/p:1:8:6",
     "ap/up:1:8:6", "static"),
    ("frame-cycloidal-a", lambda: RockingSystem("frame", "podium", Column(1.5, 0.2, 800.0, 0.4), 4, 16000.0),
     "auto", "exact", "cycloidal-a", "omega_p/p_hat:1:9:6", "ap/up:1:8:6", "static"),
    ("podium-2dof-ricker-anti", lambda: reference_podium(6.0), "podium-2dof", "exact", "ricker-anti",
     "omega_p/p:1:6:4", "ap/up:1.5:5:3", "static"),
    ("podium-rigid-ricker-anti", lambda: reference_podium(6.0), "rigid-superstructure", "exact", "ricker-anti",
     "omega_p/p:1:6:5", "ap/up:1:6:4", "static"),
]


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_grid_points_equal_simulate(case):
    _, make, structure, equations, pulse, x, y, overturn = case
    system = make()
    req = SpectrumRequest(pulse, parse_axis(x, "x"), parse_axis(y, "y"), equations=equations, structure=structure,
                          overturn=overturn)
    spec = compute_spectrum(system, req)
    assert spec.theta_max_over_alpha.shape == (req.y.n, req.x.n)
    assert spec.overturned.any() and (~spec.overturned).any()   # the grid spans both outcomes
    rng = np.random.default_rng(len(pulse) + req.x.n)
    points = [(i, j) for i in range(req.y.n) for j in range(req.x.n)]
    picks = [points[k] for k in rng.choice(len(points), size=min(len(points), 10), replace=False)]
    for i, j in picks:
        motion = pulse_motion(pulse, float(spec.amplitudes[i]), float(spec.periods[j]))
        for energy_stop in (True, False):
            r = simulate(system, motion, model=equations, structure=structure, overturn=overturn,
                         energy_stop=energy_stop, record_history=False)
            assert r.theta_max == spec.theta_max[i, j], (i, j, energy_stop)
            assert r.theta_max_over_alpha == spec.theta_max_over_alpha[i, j]
            assert r.overturned == bool(spec.overturned[i, j])
            assert (r.overturn_mode != "none") == bool(spec.exceeded[i, j])
            assert (r.overturn_mode == "dynamic") == bool(spec.dynamic[i, j])
            expected = r.impacts_before_overturn if r.overturned else None
            got = int(spec.impacts_before_overturn[i, j])
            assert (got if got >= 0 else None) == expected


def test_scattered_points_equal_grid_points():
    # the pointwise kernel (margins, samples) runs exactly the analyses of the grid kernel
    from rockdesign.planar.spectra.kernel import pulse_points
    from rockdesign.planar.spectra.spectrum import prepare
    system = table34_column("B2ec")
    req = SpectrumRequest("cycloidal-a", parse_axis("omega_p/p:1:9:7", "x"), parse_axis("ap/up:0.5:8:6", "y"))
    spec = compute_spectrum(system, req)
    _, sp, kind, shape, periods, amplitudes, opts, _ = prepare(system, req)
    iy, ix = np.meshgrid(np.arange(6), np.arange(7), indexing="ij")
    pts = pulse_points(sp, kind, shape, periods[ix.ravel()], amplitudes[iy.ravel()], opts, req.t_free)
    np.testing.assert_array_equal(pts.reshape(spec.out.shape), spec.out)


def test_pulses_of_the_grid_follow_the_axes():
    # ω_p/p axis → T_p = 2π/(x p), p of one column (Eq 3.13); ap/up → a_p = y g tan α
    s = block_from_p(2.2, 0.1)
    spec = compute_spectrum(s, SpectrumRequest("ricker-anti", parse_axis("omega_p/p:1:4:4", "x"),
                                               parse_axis("ap/up:0:3:4", "y")))
    np.testing.assert_allclose(spec.periods, 2 * math.pi / (np.array([1.0, 2.0, 3.0, 4.0]) * 2.2), rtol=1e-12)
    np.testing.assert_allclose(spec.amplitudes, np.array([0.0, 1.0, 2.0, 3.0]) * 9.81 * 0.1, rtol=1e-12)
    # below the uplift acceleration nothing moves (a_p < g tan α), at 2–3 g tan α everything rocks
    assert np.all(spec.theta_max[0] == 0.0)
    assert np.all(spec.theta_max[2:] > 0.0)


def test_table_3_4_point_read_from_a_spectrum():
    # Example 3.5: B1 under the antisymmetric Ricker a_p = 0.38 g, T_p = 0.95 s: θ_max/α of case tab3.4_B1_thmax
    # (SPEC §7, exact EOMs; thesis reads 1.10–1.20 α off Fig 3.19a)
    s = table34_column("B1")
    spec = compute_spectrum(s, SpectrumRequest("ricker-anti", parse_axis("Tp:0.95", "x"),
                                               parse_axis("ap/g:0.38", "y")))
    assert spec.theta_max_over_alpha[0, 0] == pytest.approx(expected("tab3.4_B1_thmax"), abs=2e-5)


def test_stop_at_capacity_keeps_the_static_verdict():
    from rockdesign.planar.spectra.kernel import OUT_IMPACTS_BEFORE_EXCEEDED
    system = table34_column("B2ec")
    base = dict(pulse="ricker-sym", x=parse_axis("omega_p/p:0.6:8:15", "x"), y=parse_axis("ap/up:0:9:10", "y"))
    full = compute_spectrum(system, SpectrumRequest(**base))
    fast = compute_spectrum(system, SpectrumRequest(**base, stop_at_capacity=True))
    np.testing.assert_array_equal(fast.overturned, full.overturned)
    assert full.overturned.any()
    safe = ~full.overturned
    np.testing.assert_array_equal(fast.theta_max[safe], full.theta_max[safe])
    np.testing.assert_array_equal(fast.theta_max[~safe], full.scales.theta_c)
    np.testing.assert_array_equal(fast.impacts_before_overturn[~safe],
                                  full.out[:, :, OUT_IMPACTS_BEFORE_EXCEEDED][~safe])
    assert fast.steps.sum() < full.steps.sum()
    with pytest.raises(Exception, match="stop_at_capacity"):
        SpectrumRequest(**base, overturn="dynamic", stop_at_capacity=True).validate()
