"""The DOP853 stepper (rockdesign/planar/dynamics/dop853.py) against closed forms, published numbers and DP5(4).

The same event-driven integrator runs either Runge–Kutta pair; these tests force DOP853 and hold it to
the tolerances of the DP5(4) tests (test_closed_form.py, test_published_histories.py), including its
7th-order dense output (events and output between steps come from it) and the event guarantees.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from support import G, block_from_p, reference_podium, table34_column
from rockdesign.planar.dynamics.dop853 import A853, B853, C853, E3, E5, N_STAGES
from rockdesign.planar.dynamics.engine import resolve_method
from rockdesign.planar.dynamics.layout import DOP853_BELOW_RTOL, METHOD_DOP853, METHOD_DP5
from rockdesign.planar.dynamics.linear_exact import sampled_pulse
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.errors import ModelError
from rockdesign.motions.motion import pulse_motion, record_motion


def test_tableau_is_consistent():
    # row sums of A equal C (every stage evaluated at its own time), the weights sum to one
    assert np.allclose(A853.sum(axis=1), C853, atol=1e-14)
    assert B853.sum() == pytest.approx(1.0, abs=1e-14)


def test_tableau_has_its_orders():
    """The coefficients written out from dop853.f satisfy the order conditions a transcription error would
    break: the weights integrate c^k exactly up to k = 7 (order 8) and not for k = 8, and the trees
    b·A·c^k up to order 8 (k ≤ 6); the two error estimates vanish on c^k to their orders (5th: k ≤ 4,
    3rd: k ≤ 2)."""
    b = np.zeros(C853.size)
    b[:N_STAGES] = B853
    for k in range(8):
        assert b @ C853 ** k == pytest.approx(1.0 / (k + 1), abs=1e-15)
    for k in range(7):
        assert b @ (A853 @ C853 ** k) == pytest.approx(1.0 / ((k + 1) * (k + 2)), abs=1e-15)
    assert abs(b @ C853 ** 8 - 1.0 / 9.0) > 1e-6
    c = C853[:N_STAGES + 1]
    for k in range(5):
        assert abs(E5 @ c ** k) <= 1e-15
    assert abs(E5 @ c ** 5) > 1e-5
    for k in range(3):
        assert abs(E3 @ c ** k) <= 1e-15
    assert abs(E3 @ c ** 3) > 1e-3


@pytest.mark.parametrize("name", ["B1", "B3ec"])
@pytest.mark.parametrize("a_p", [0.3, 0.5])
def test_pulse_histories_agree_with_closed_form(name, a_p):
    motion = sampled_pulse(pulse_motion("ricker-anti", a_p * G, 0.95), 200)
    rk = simulate(table34_column(name), motion, model="linear", t_end=10.0, method="dop853")
    cf = simulate(table34_column(name), motion, model="linear-exact", t_end=10.0)
    assert rk.impacts == cf.impacts
    assert [e.kind for e in rk.events] == [e.kind for e in cf.events]
    assert np.max(np.abs(np.interp(cf.t, rk.t, rk.theta) - cf.theta)) <= 1e-8
    if rk.impacts:
        assert np.max(np.abs(rk.impact_times - cf.impact_times)) <= 1e-9
    assert rk.theta_max == pytest.approx(cf.theta_max, abs=1e-9)


def test_dense_output_between_steps():
    # an analytic pulse (no samples): DOP853 takes long steps, the 0.5-ms output grid comes from its
    # 7th-order interpolant — it must match an independent tight solution (DP5(4) at rtol 1e-13) like
    # the step ends do
    s = block_from_p(2.0, 0.15)
    motion = pulse_motion("ricker-anti", 0.3 * G, 1.0)
    rk = simulate(s, motion, model="linear", t_end=4.0, method="dop853", output_dt=5e-4)
    ref = simulate(s, motion, model="linear", t_end=4.0, method="dp5", rtol=1e-13, atol=1e-15, output_dt=5e-4)
    assert rk.impacts == ref.impacts >= 1
    assert rk.diagnostics["steps"] < 0.2 * rk.t.size          # most output points are interpolated
    assert np.max(np.abs(rk.theta - np.interp(rk.t, ref.t, ref.theta))) <= 1e-8
    assert np.max(np.abs(rk.impact_times - ref.impact_times)) <= 1e-9


def test_reference_podium_published_numbers():
    # cases.json podium_rha_ref (as test_published_histories.py, with DOP853)
    s = reference_podium(6.0)
    p = math.sqrt(G / (math.hypot(1.5, 0.225) * 4 / 3))
    pulse = pulse_motion("ricker-anti", 2.5 * G * 0.15, 2 * math.pi / (3 * p))
    r = simulate(s, pulse, structure="podium-2dof", model="exact", method="dop853")
    assert r.uplift_time == pytest.approx(1.08516, abs=2e-5)
    assert r.theta_max_over_alpha == pytest.approx(0.48547, abs=1e-4)
    assert r.drift_max == pytest.approx(0.03576, abs=1e-3)


def test_podium_record_dop853_agrees_with_dp5_at_tight_tolerance():
    # the two pairs converge to the same history; DOP853 at 1e-10 is closer to it than DP5(4) at 1e-10
    rng = np.random.default_rng(7)
    n = 800
    a = np.convolve(rng.standard_normal(n), np.ones(9) / 9, mode="same")
    a *= 0.35 * G / np.abs(a).max()
    motion = record_motion("synthetic", a, 0.01)
    s = reference_podium(6.0)
    ref = simulate(s, motion, structure="podium-2dof", method="dp5", rtol=1e-13, atol=1e-15, t_end=10.0)
    hi = simulate(s, motion, structure="podium-2dof", method="dop853", rtol=1e-10, atol=1e-12, t_end=10.0)
    lo = simulate(s, motion, structure="podium-2dof", method="dp5", rtol=1e-10, atol=1e-12, t_end=10.0)
    assert hi.impacts == ref.impacts
    err_hi = np.max(np.abs(hi.theta - np.interp(hi.t, ref.t, ref.theta)))
    err_lo = np.max(np.abs(lo.theta - np.interp(lo.t, ref.t, ref.theta)))
    assert err_hi <= 1e-8
    assert err_hi < err_lo
    assert hi.diagnostics["steps"] < lo.diagnostics["steps"]


def test_two_extrema_inside_one_step_are_found():
    # free rocking: smooth motion, so the steps are long and θ rises, peaks and falls back to an impact
    # within a few steps — the peak (θ̇ = 0) and the impact must be located on the dense output
    s = block_from_p(2.0, 0.15)
    alpha = math.atan(0.15)
    for method in ("dp5", "dop853"):
        r = simulate(s, None, theta0=0.3 * alpha, thetadot0=0.05, model="linear", t_end=3.0, method=method)
        cf = simulate(s, None, theta0=0.3 * alpha, thetadot0=0.05, model="linear-exact", t_end=3.0)
        assert r.impacts == cf.impacts
        assert r.theta_max == pytest.approx(cf.theta_max, abs=1e-10)
        assert np.max(np.abs(r.impact_times - cf.impact_times)) <= 1e-9


def test_automatic_choice_by_system_and_tolerance():
    assert resolve_method(0, True, 1e-10) == METHOD_DOP853
    assert resolve_method(0, True, 1e-6) == METHOD_DP5
    assert resolve_method(0, False, 1e-12) == METHOD_DP5
    assert resolve_method(METHOD_DOP853, False, 1e-6) == METHOD_DOP853
    assert 1e-8 < DOP853_BELOW_RTOL < 1e-7


def test_unknown_method_is_a_model_error():
    with pytest.raises(ModelError):
        simulate(block_from_p(2.0, 0.15), None, theta0=0.01, t_end=0.5, method="rk4")
