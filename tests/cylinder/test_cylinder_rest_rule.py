"""The cylinder's rest and seed rules (issue 43, docs/cylinder.md "Rest, uplift and the seed").

* Rest: at a quasi-impact or planar crossing whose rocking energy is below ½ M R² v_rest², both contacts —
  at a planar crossing the planar engine's |θ̇⁺| < v_rest for the block of equal inertia (SPEC §3.6).
* Uplift at g tan α plus the planar engine's hysteresis; the seed phase starts at θ = 0.

Compared with the planar engine (the block of the cylinder's p and α, λ = (3 + cos²α)/12, c_r = 1 for the
rigid contact, the same rest velocity), closed forms, and the engine's own convergence as the seed → 0.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rockdesign.cylinder.engine import DEFAULT_REST_VELOCITY, rest_energy, seed_tilt, simulate_cylinder, uplift_level
from rockdesign.cylinder.eom import energy, parameters
from rockdesign.cylinder.system import cylinder
from rockdesign.planar.dynamics.engine import _rigid_uplift_thresholds
from rockdesign.planar.dynamics.model import ModelChoice, system_parameters
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import record_motion
from rockdesign.cylinder.pairs import parse_pair, suite_pairs
from rockdesign.planar.system import Column, RockingSystem

V_REST = DEFAULT_REST_VELOCITY
EXAMPLE = cylinder(3.0, 0.6)                       # 2H = 3 m, tan α = 0.2 (thesis Ch. 5, examples/cylinder.toml)
THRESHOLD = cylinder(2.5, 0.75)                    # tan α = 0.30: the project, design PGA = g tan α


def block_of(cyl, c_r=1.0):
    """The planar engine's block with the cylinder's p and α: λ = I1*/R² = (3 + cos²α)/12 (Eq 5.20)."""
    lam = (3 + math.cos(cyl.alpha) ** 2) / 12
    system = RockingSystem("cylinder as a block", "column", Column(cyl.half_height, cyl.base_radius, cyl.mass, lam),
                           g=cyl.g)
    return system.with_restitution(c_r)


def potential(theta, cyl):
    """gR(cos(α−θ) − cos α) [J/kg] (Eq 5.22's potential)."""
    return cyl.g * cyl.R * (math.cos(cyl.alpha - theta) - math.cos(cyl.alpha))


# ---------------------------------------------------------------- the rules against the planar engine's
def test_rest_energy_is_the_planar_rest_velocity_of_the_equal_block():
    # at a planar crossing θ = 0, φ̇ = 0: E = ½ M R² θ̇², and the block's I_O/m = (1 + λ) R² = M R²
    for cyl in (EXAMPLE, THRESHOLD):
        lam = (3 + math.cos(cyl.alpha) ** 2) / 12
        assert rest_energy(cyl.R, cyl.alpha, V_REST) == pytest.approx(0.5 * (1 + lam) * cyl.R ** 2 * V_REST ** 2,
                                                                       rel=1e-14)


def test_uplift_level_is_the_planar_engines_threshold():
    for cyl in (EXAMPLE, THRESHOLD):
        sp = system_parameters(block_of(cyl), ModelChoice("block", "exact"))
        lo, hi = _rigid_uplift_thresholds(sp[16], sp)
        assert uplift_level(cyl.alpha, cyl.g) == pytest.approx(-lo, rel=1e-13)
        assert uplift_level(cyl.alpha, cyl.g) == pytest.approx(hi, rel=1e-13)
        # the hysteresis is ≈ 5e-9 of g tan α: a chatter guard, not a change of the threshold (Eq 5.24)
        assert 0 < uplift_level(cyl.alpha, cyl.g) / (cyl.g * cyl.tan_alpha) - 1 < 1e-8


def test_seed_carries_one_percent_of_the_rest_energy():
    for cyl in (EXAMPLE, THRESHOLD):
        seed = seed_tilt(cyl.R, cyl.alpha, cyl.g, V_REST)
        assert potential(seed, cyl) == pytest.approx(0.01 * rest_energy(cyl.R, cyl.alpha, V_REST), rel=1e-6)


# ---------------------------------------------------------------- planar reduction
@pytest.mark.parametrize("record, n_equal", [("p695-ff/15b", 150), ("p695-ff/1a", None), ("p695-ff/20b", None),
                                             ("p695-ff/11a", None)])
def test_planar_reduction_is_the_planar_engines_block_with_the_same_rest_rule(record, n_equal):
    # one component, no initial spin: the rigid-contact cylinder is the c_r = 1 block of its p and α, and now
    # rests as that block does (|θ̇⁺| < v_rest at an impact).  Before, on 15b at 0.3 g the cylinder never
    # rested and overturned after 2,654 crossings at 38.7 s while the block rested and survived.
    cyl = EXAMPLE
    pair = parse_pair(f"record:{record},resultant_pga=0.3g", gravity=cyl.g).pair
    r = simulate_cylinder(cyl, pair, rest_velocity=V_REST)
    assert r.planar
    x, y = pair.acceleration(np.arange(len(pair.x)) * pair.dt)
    motion = record_motion(record, x if np.any(x) else y, pair.dt)
    p = simulate(block_of(cyl), motion, model="exact", t_end=pair.duration + 10.0, rest_velocity=V_REST,
                 overturn="dynamic", rtol=1e-10, atol=1e-12)
    assert r.uplift_time == pytest.approx(p.uplift_time, abs=1e-12)
    crossings, impacts = r.times_of("planar-crossing"), p.impact_times
    n = min(crossings.size, impacts.size) if n_equal is None else n_equal
    assert crossings.size >= n and impacts.size >= n
    if n_equal is None:
        assert crossings.size == impacts.size
    # the integration tolerance (rtol 1e-10) until grazing impacts amplify the difference (chaos)
    np.testing.assert_allclose(crossings[:n], impacts[:n], atol=1e-6)
    assert r.theta_max == pytest.approx(p.theta_max, rel=1e-5) or r.overturned
    # the same verdict: the cylinder overturns at θ_ot = 1.5α, the block's history passes it
    assert r.overturned == (p.theta_max >= cyl.theta_overturn)
    assert r.times_of("rest").size == p.diagnostics["rest_entries"]
    if record == "p695-ff/15b":
        assert r.times_of("rest").size >= 1 and not r.overturned


# ---------------------------------------------------------------- the threshold (issue 43)
@pytest.mark.parametrize("contact", ["rigid", "spring-dashpot"])
def test_a_pair_just_above_the_uplift_acceleration_rests_after_its_first_crossing(contact):
    # resultant PGA 1.001 g tan α (the perturbation ensemble of a project designed at g tan α): the cylinder
    # uplifts, barely moves and rests at its first crossing or quasi-impact, as the planar engine's block does.
    # Before: 130,000-220,000 quasi-impacts and 5-14 million steps per pair (rigid contact).
    cyl = cylinder(2.5, 0.75, contact=contact)
    for pair in suite_pairs("p695-farfield-pairs", gravity=cyl.g)[:6]:
        scaled = pair.scaled(1.001 * cyl.g * cyl.tan_alpha / pair.resultant_pga)
        r = simulate_cylinder(cyl, scaled)
        uplifts, rests = r.times_of("uplift"), r.times_of("rest")
        assert r.status == "completed" and uplifts.size >= 1
        assert rests.size == uplifts.size                   # every uplift ends in rest
        assert r.quasi_impacts <= 2 * uplifts.size
        assert r.solver["steps"] < 3000 * uplifts.size
        assert r.theta_max < 1e-6 * cyl.alpha


def test_below_the_rest_energy_the_rigid_cylinder_rests_above_it_rocks_for_ever():
    # planar free rocking of the rigid contact (no loss, c_r = 1) from θ0 with V(θ0) = 0.9 and 1.1 E_rest
    cyl = EXAMPLE
    e_rest = rest_energy(cyl.R, cyl.alpha, V_REST)
    for ratio, rests in ((0.9, True), (1.1, False)):
        theta0 = brentq(lambda th: potential(th, cyl) - ratio * e_rest, 0.0, 1e-3, xtol=1e-20)
        r = simulate_cylinder(cyl, None, t_end=0.2, theta0=theta0)
        assert r.planar and r.status == "completed"
        assert (r.times_of("rest").size == 1) == rests
        if rests:
            assert r.quasi_impacts == 1 and r.theta[-1] == 0.0
        else:
            # energy conserved through the crossings: |θ̇| at each is √(2E/(M R²)) > v_rest (to atol = 1e-12 rad
            # on θ0 ≈ 8e-8 rad, 1e-5 relative)
            rates = np.abs([e[2] for e in r.events if e[0] == "planar-crossing"])
            assert rates.size > 10
            np.testing.assert_allclose(rates, math.sqrt(1.1) * V_REST, rtol=1e-5)


def test_a_spinning_cylinder_below_the_rest_energy_rests_on_its_way_to_its_first_quasi_impact():
    # 3D: below 0.01 α, approaching (θ̇ < 0) with E < E_rest, the cylinder rests at the end of the step — the
    # minimum of an orbit of tiny angular momentum can lie below what the step control resolves (a falling body
    # with L ≈ 1e-22 collapsed the step size at θ ≈ 1e-19 before this test was added to the rule)
    cyl = EXAMPLE
    e_rest = rest_energy(cyl.R, cyl.alpha, V_REST)
    par = parameters(cyl.R, cyl.alpha, cyl.g)
    theta0 = brentq(lambda th: potential(th, cyl) - 0.5 * e_rest, 0.0, 1e-3, xtol=1e-20)
    fall = math.sqrt(2 * theta0 / (cyl.g * math.sin(cyl.alpha) / (cyl.R * par[11])))   # to θ = 0 without spin
    for spin in (1.0, 1e-12):
        assert energy(np.array([theta0, 0.0, 0.0, spin, 0.0, 0.0]), par) < e_rest
        r = simulate_cylinder(cyl, None, t_end=0.2, theta0=theta0, phidot0=spin)
        assert not r.planar and r.status == "completed"
        assert r.quasi_impacts <= 1 and r.times_of("rest").size == 1
        assert r.times_of("rest")[0] < fall
    # above the rest energy it does not rest (E = 1.5 E_rest; a circular orbit keeps it for ever)
    theta1 = brentq(lambda th: potential(th, cyl) - 1.5 * e_rest, 0.0, 1e-3, xtol=1e-20)
    r = simulate_cylinder(cyl, None, t_end=0.05, theta0=theta1, phidot0=1.0)
    assert r.times_of("rest").size == 0 and r.quasi_impacts >= 1


# ---------------------------------------------------------------- the seed
@pytest.mark.parametrize("contact, pga_g, pairs, rel", [
    # damped pair 13 (24 quasi-impacts) moves by 3e-4; with the old seed (θ_seed = 1e-7, θ̇ = φ̇ = 0, from
    # θ_seed at the uplift instant) pair 9 moved by 2.8 % between θ_seed = 1e-7 and 1e-11
    ("spring-dashpot", 0.3, (9, 2, 13), 1e-3),
    ("rigid", 0.3, (9, 2, 13, 4), 1e-5),
])
def test_theta_max_does_not_depend_on_the_seed_over_two_decades(contact, pga_g, pairs, rel):
    cyl = cylinder(3.0, 0.6, contact=contact)
    seed = seed_tilt(cyl.R, cyl.alpha, cyl.g, V_REST)
    suite = suite_pairs("p695-farfield-pairs", gravity=cyl.g)
    for k in pairs:
        pair = suite[k - 1]
        scaled = pair.scaled(pga_g * cyl.g / pair.resultant_pga)
        runs = [simulate_cylinder(cyl, scaled, theta_seed=s) for s in (0.1 * seed, seed, 10 * seed)]
        peaks = np.array([r.theta_max for r in runs])
        assert np.ptp(peaks) <= rel * peaks[1], (pair.name, peaks)
        assert len({r.overturned for r in runs}) == 1
        assert len({r.quasi_impacts for r in runs}) == 1


def test_the_threshold_verdict_does_not_depend_on_the_seed():
    cyl = THRESHOLD
    seed = seed_tilt(cyl.R, cyl.alpha, cyl.g, V_REST)
    for pair in suite_pairs("p695-farfield-pairs", gravity=cyl.g)[:4]:
        for amplitude in (1.0, 1.001):
            scaled = pair.scaled(amplitude * 0.3 * cyl.g / pair.resultant_pga)
            runs = [simulate_cylinder(cyl, scaled, theta_seed=s) for s in (0.1 * seed, seed, 10 * seed)]
            assert all(r.status == "completed" and not r.overturned for r in runs)
            assert all(r.theta_max < 1e-6 * cyl.alpha for r in runs)


def test_cost_reason_names_micro_rocking():
    # rigid planar free rocking just above the rest energy: thousands of crossings at θ ≈ 1e-7 rad, for ever
    cyl = EXAMPLE
    e_rest = rest_energy(cyl.R, cyl.alpha, V_REST)
    theta0 = brentq(lambda th: potential(th, cyl) - 1.1 * e_rest, 0.0, 1e-3, xtol=1e-20)
    r = simulate_cylinder(cyl, None, t_end=3.0, theta0=theta0)
    assert r.quasi_impacts > 1000
    reason = r.cost_reason()
    assert "micro-rocking" in reason and "rigid contact dissipates nothing" in reason
    assert f"{r.quasi_impacts:,} quasi-impacts" in reason
    # an ordinary record pair is not called micro-rocking
    ordinary = simulate_cylinder(cyl, parse_pair("record:p695-ff/1,resultant_pga=0.3g", gravity=cyl.g).pair)
    assert "micro-rocking" not in ordinary.cost_reason()


def test_without_a_rest_rule_a_seed_phase_that_comes_back_crosses_to_the_other_side():
    # rest_velocity = 0: the pair at 1.001 g tan α uplifts (4.54 s), comes back within the seed phase and
    # crosses; on the other side the inertia force restores (the seed phase keeps the force on its side), so
    # the body rocks at seed level, without loss (c_r = 1), instead of being driven away.  (Like the planar
    # engine's block without a rest velocity, it never stops: 419,566 crossings to the end of the record.)
    cyl = THRESHOLD
    pair = suite_pairs("p695-farfield-pairs", gravity=cyl.g)[0]
    scaled = pair.scaled(1.001 * cyl.g * cyl.tan_alpha / pair.resultant_pga)
    r = simulate_cylinder(cyl, scaled, rest_velocity=0.0, theta_seed=1e-9, t_end=5.0)
    assert r.status == "completed" and r.times_of("rest").size == 0
    assert r.times_of("planar-crossing").size >= 2
    assert r.theta_max < 1e-6 * cyl.alpha
