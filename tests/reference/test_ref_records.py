"""The scipy reference on piecewise-linear records: exact uplift inside a segment, rest and
re-uplift (SPEC §3.6), integration split at samples vs across samples (SPEC §9), cost.

The record of cases.json record_block_exact (synthetic_record_dt0.01_30s.txt) is not shipped, so a
deterministic synthetic record of the same kind (dt = 0.01 s, 30 s) is generated here; the block is
the one of that case (R = 1.5 m, tan α = 0.15, λ = 1/3).
"""
import math

import numpy as np
import pytest

from rockdesign.motions.motion import record_motion
from rockdesign.bench.baseline import simulate_scipy
from rockdesign.planar.system import Column, RockingSystem, Superstructure, block

G = 9.81
ALPHA = math.atan(0.15)
BLOCK = block(1.5 * math.cos(ALPHA), 1.5 * math.sin(ALPHA))


def synthetic_record(duration=30.0, dt=0.01, pga=0.26 * G, seed=1):
    """Enveloped, smoothed white noise (m/s²) — deterministic for a seed."""
    n = int(round(duration / dt)) + 1
    t = np.arange(n) * dt
    a = np.convolve(np.random.default_rng(seed).standard_normal(n), np.ones(8) / 8, mode="same")
    a *= np.minimum(1.0, t / 3.0) * np.exp(-np.maximum(0.0, t - 12.0) / 6.0)
    return record_motion(f"synthetic-{seed}", a * pga / np.max(np.abs(a)), dt)


RECORD30 = synthetic_record()


@pytest.fixture(scope="module")
def block_run():
    return simulate_scipy(BLOCK, RECORD30, t_end=30.0, rtol=1e-10, atol=1e-12)


def test_block_on_record_uplifts_exactly_and_rests(block_run):
    """Every uplift happens where the linear segment crosses ∓g tan α (side = −sign ü_g, SPEC §0);
    impacts with |θ̇⁺| < 5e-4 rad/s and ü_g inside the band end in rest, then re-uplift on a fresh
    crossing (SPEC §3.6)."""
    res = block_run
    uplifts = res.events_of("uplift")
    n_rest = len(res.events_of("rest"))
    assert n_rest >= 1 and len(uplifts) >= 2 and n_rest <= len(uplifts) <= n_rest + 1
    for k, e in enumerate(uplifts):
        a = RECORD30.acceleration(e.t)[0]
        hysteresis = 0.0 if k == 0 else 1e-9 * G       # re-uplift needs a fresh crossing
        assert abs(a) == pytest.approx(G * 0.15 + hysteresis, abs=1e-13)
        assert e.side == -int(math.copysign(1, a))
    for e in res.events_of("rest"):
        assert abs(e.before[1]) < 5e-4 and abs(RECORD30.acceleration(e.t)[0]) < G * 0.15
    assert res.uplift_time == uplifts[0].t
    assert not res.dynamic and res.n_impacts > 100
    assert not res.events_of("restart")
    rests = [e.t for e in res.events_of("rest")] + [res.t_end]
    rocking_time = sum(r - u.t for u, r in zip(uplifts, rests))
    assert res.n_solver_calls >= rocking_time / RECORD30.dt - len(uplifts)   # one call per sample interval
    print(f"\n30-s record, block, DOP853 rtol 1e-10: theta_max = {res.theta_max:.6f} rad, "
          f"{res.n_impacts} impacts, nfev = {res.nfev}, {res.n_solver_calls} calls, {res.wall_time:.2f} s")


def test_impacts_flip_side_and_scale_velocity(block_run):
    """θ̇⁺ = √c_r θ̇⁻ and the side flips at every impact (Eq 2.15, SPEC §3.4)."""
    for e in block_run.events_of("impact"):
        assert e.before[0] == pytest.approx(0.0, abs=1e-12)
        assert e.after[1] == pytest.approx(math.sqrt(block_run.c_r) * e.before[1], rel=1e-14)
        assert e.side == int(math.copysign(1, e.before[1]))


def test_tolerance_and_method_agree_on_peaks(block_run):
    """Split at samples, DOP853 at 1e-12 and 1e-10 agree on θ_max and on the impact sequence."""
    fine = simulate_scipy(BLOCK, RECORD30, t_end=30.0, rtol=1e-12, atol=1e-13)
    assert fine.theta_max == pytest.approx(block_run.theta_max, rel=1e-7)
    assert fine.n_impacts == block_run.n_impacts
    t_fine = np.array([e.t for e in fine.events_of("impact")])
    t_run = np.array([e.t for e in block_run.events_of("impact")])
    assert np.max(np.abs(t_fine - t_run)) < 1e-6


def test_integration_across_samples_is_one_call_per_stretch():
    """split_at_samples=False integrates each event-free stretch in one call (the benchmark's
    failure mode, SPEC §9): far fewer calls, many more function evaluations (kinks at samples)."""
    record = synthetic_record(duration=8.0, pga=0.26 * G)
    split = simulate_scipy(BLOCK, record, t_end=8.0)
    across = simulate_scipy(BLOCK, record, t_end=8.0, split_at_samples=False)
    assert across.uplift_time == split.uplift_time
    assert across.n_solver_calls <= across.n_impacts + 1     # every call ends at an impact or t_end
    assert split.n_solver_calls > 3 * across.n_solver_calls
    assert across.nfev > split.nfev
    assert across.theta_max == pytest.approx(split.theta_max, rel=1e-2)


def test_podium_on_record_rests_and_reuplifts_with_eq_4_7():
    """A podium (γ = 10, η = 5, ω_s/p = 6, ζ_s = 2 %) on a 10-s record: the fixed-base phase and the
    Eq 4.7 uplift event run between rocking episodes; ü_g meets the threshold at each uplift."""
    H = 1.5
    col = Column(H, 0.15 * H, 1000.0, 1 / 3)
    p = math.sqrt(G / (math.hypot(H, 0.15 * H) * 4 / 3))
    system = RockingSystem("podium", "podium", col, 4, 40000.0, Superstructure(200000.0, 6 * p, 0.02))
    record = synthetic_record(duration=10.0, pga=0.35 * G, seed=2)
    res = simulate_scipy(system, record, t_end=10.0, record_every_step=True)
    assert len(res.events_of("uplift")) >= 2 and res.n_impacts > 5
    assert np.all(np.diff(res.t) >= 0.0)
    rest = res.theta == 0.0
    assert np.any(rest & (res.u_T != 0.0))          # superstructure vibrates on the resting podium
