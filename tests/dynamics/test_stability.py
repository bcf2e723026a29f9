"""Stability where numerical methods fail (issue: dynamics engine, item 7; docs/engine.md).

Each case must finish, keep every event, and return a diagnosed result.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from casedata import expected

from support import G, block_from_p, reference_podium
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import pulse_motion, record_motion
from rockdesign.planar.system import Column, RockingSystem


def test_zeno_free_rocking_ends_in_rest():
    # c_r < 1 makes infinitely many impacts in finite time; the rest velocity ends the sequence
    s = block_from_p(2.0, 0.2).with_restitution(0.6)
    r = simulate(s, None, theta0=0.5 * math.atan(0.2), t_end=30.0)
    assert r.status == "completed"
    assert r.events[-1].kind == "rest"
    assert r.diagnostics["rest_entries"] == 1
    # impacts end within a few dozen (|θ̇| shrinks by √0.6 per impact until below 5e-4 rad/s)
    assert 5 <= r.impacts <= 40
    assert r.diagnostics["steps"] < 5000


@pytest.mark.parametrize("factor,uplifts", [(0.999999, 0), (1.0, None), (1.000001, 1)])
def test_pulse_at_the_uplift_threshold(factor, uplifts):
    # the symmetric Ricker peak sits exactly on (or a hair either side of) g tan α: no chatter
    s = block_from_p(2.0, 0.15)
    r = simulate(s, pulse_motion("ricker-sym", factor * G * 0.15, 1.0))
    assert r.status == "completed"
    n_up = len(r.events_of("uplift"))
    if uplifts is not None:
        assert n_up == uplifts
    assert n_up <= 1 and r.diagnostics["events"] <= 3


def test_tangent_uplift_of_the_podium_criterion_does_not_chatter():
    # Eq 4.7 with a vibrating superstructure: round-off near tangency must not loop uplift→impact→rest
    s = reference_podium(6.0)
    for f in (0.9, 0.95, 1.0, 1.05):
        r = simulate(s, pulse_motion("ricker-anti", f * G * 0.15 / 1.3, 1.2), structure="podium-2dof")
        assert r.status == "completed"
        assert r.diagnostics["events"] < 400


def test_overturning_threshold_is_sharp_and_stable():
    # a hair either side of the minimum overturning amplitude: two different, repeatable answers
    s = block_from_p(2.0, 0.15)
    T = 2 * math.pi / (5 * 2.0)

    def mode(x):
        return simulate(s, pulse_motion("ricker-anti", x * G * 0.15, T), record_history=False).overturn_mode

    lo, hi = 5.0, 6.0
    assert mode(lo) == "none" and mode(hi) == "dynamic"
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if mode(mid) == "dynamic":
            hi = mid
        else:
            lo = mid
        if hi - lo < 1e-9:
            break
    assert mode(lo) != "dynamic" and mode(hi) == "dynamic"
    assert mode(lo) == mode(lo) and mode(hi) == mode(hi)


def test_large_slenderness():
    s = RockingSystem("squat", "column", Column(1.0, 0.5, 1000.0, 1 / 3), g=G)   # tan α = 0.5
    r = simulate(s, pulse_motion("ricker-anti", 1.5 * G * 0.5, 0.8))
    assert r.status == "completed" and r.uplift_time is not None
    assert r.theta_max > 0


def test_very_stiff_superstructure_finishes_and_tracks_the_rigid_model():
    s = reference_podium(200.0, zeta=0.02)
    p = math.sqrt(G / (math.hypot(1.5, 0.225) * 4 / 3))
    pulse = pulse_motion("ricker-anti", 3 * G * 0.15, 2 * math.pi / (4 * p))
    two = simulate(s, pulse, structure="podium-2dof", t_end=4.0)
    rigid = simulate(s, pulse, structure="rigid-superstructure", t_end=4.0)
    assert two.status == "completed"
    assert two.uplift_time == pytest.approx(rigid.uplift_time, abs=2e-4)
    assert two.impact_times[0] == pytest.approx(rigid.impact_times[0], abs=2e-3)


def _ricker_record(dt):
    m = pulse_motion("ricker-anti", 0.38 * G, 0.95)
    t, a = m.sampled(dt)
    return record_motion(f"ricker@{dt}", a, dt)


@pytest.mark.parametrize("dt", [0.02, 0.001])
def test_coarse_and_fine_records(dt):
    from support import table34_column
    s = table34_column("B1")
    r = simulate(s, _ricker_record(dt), t_end=10.0)
    assert r.status == "completed"
    # the record is piecewise linear: output rows fall on every sample
    assert np.all(np.isin(np.round(np.arange(0, 5, dt) / dt), np.round(r.t / dt)))
    # the sampled wavelet approaches the analytic one (Table 3.4 B1, case tab3.4_B1_thmax)
    tol = 0.03 if dt == 0.02 else 2e-4
    assert r.theta_max_over_alpha == pytest.approx(expected("tab3.4_B1_thmax"), abs=tol)


def test_long_record_120_s():
    rng = np.random.default_rng(3)
    n = 24000
    a = np.convolve(rng.standard_normal(n), np.ones(5) / 5, mode="same")
    a *= 0.2 * G / np.abs(a).max()
    s = block_from_p(2.2, 0.15)
    r = simulate(s, record_motion("long", a, 0.005), t_end=125.0)
    assert r.status in ("completed", "overturned (|θ| = π/2)")
    assert r.diagnostics["steps"] < 2_000_000
    assert r.t[-1] == pytest.approx(r.t_end)


def test_resting_block_is_uplifted_again():
    # two pulses 8 s apart: uplift, impacts, rest, then a fresh uplift by the second pulse
    dt = 0.005
    m = pulse_motion("ricker-anti", 0.2 * G, 0.8)
    t, a = m.sampled(dt)
    quiet = np.zeros(int(8.0 / dt))
    rec = record_motion("two pulses", np.concatenate([a, quiet, a]), dt)
    s = block_from_p(2.2, 0.15).with_restitution(0.7)
    r = simulate(s, rec)
    kinds = [e.kind for e in r.events]
    assert kinds.count("uplift") >= 2
    first_rest = kinds.index("rest")
    assert "uplift" in kinds[first_rest:]
    assert r.status == "completed"


def test_event_capacity_overflow_is_reported_not_silent():
    s = block_from_p(2.0, 0.2).with_restitution(0.95)
    r = simulate(s, None, theta0=0.1, t_end=30.0, event_capacity=5)
    assert len(r.events) == 5
    assert r.diagnostics["events"] > 5 and "warning" in r.diagnostics
