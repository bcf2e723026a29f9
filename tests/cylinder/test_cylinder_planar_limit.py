"""Planar limit: no spin and a one-directional excitation make the cylinder Housner's planar cylinder
(Eq 5.26, p of Eq 5.27) — compared with the planar engine on a block of the same inertia
(λ = I1*/R² = (3 + cos²α)/12, Eq 5.20): undamped with c_r = 1, damped with Eq 5.41's c_r."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.cylinder.engine import simulate_cylinder
from rockdesign.cylinder.quantities import frequency_parameter, restitution_root
from rockdesign.cylinder.system import cylinder
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import pulse_motion
from rockdesign.cylinder.pairs import pulse_pair
from rockdesign.planar.system import Column, RockingSystem


def housner_block(cyl, c_r):
    lam = (3 + math.cos(cyl.alpha) ** 2) / 12
    system = RockingSystem("cylinder as a block", "column", Column(cyl.half_height, cyl.base_radius, cyl.mass, lam),
                           g=cyl.g)
    return system.with_restitution(c_r)


def test_block_of_equal_inertia_has_the_cylinders_frequency_parameter():
    cyl = cylinder(3.0, 0.6)
    lam = (3 + math.cos(cyl.alpha) ** 2) / 12
    assert math.sqrt(cyl.g / (cyl.R * (1 + lam))) == pytest.approx(frequency_parameter(cyl.R, cyl.alpha), rel=1e-14)


# rigid: the same equation, to the integration tolerance; spring–dashpot: the contact compliance changes
# the motion by ~(p/ω_n)² ≈ 1.2e-4 relative, so the damped planar cylinder is Housner's to that order
@pytest.mark.parametrize("contact, t_tol, theta_tol", [("rigid", 1e-7, 1e-7), ("spring-dashpot", 2e-3, 2e-4)])
def test_planar_cylinder_is_housners(contact, t_tol, theta_tol):
    cyl = cylinder(3.0, 0.6, contact=contact)
    motion = pulse_motion("ricker-sym", 0.30 * cyl.g, 1.0)     # 1.5 × the uplift acceleration g tan α
    azimuth = math.radians(40.0)
    r = simulate_cylinder(cyl, pulse_pair(motion, azimuth), t_end=8.0, output_dt=0.01)
    assert r.planar and r.status == "completed"
    c_r = restitution_root(cyl.alpha) ** 2 if cyl.damped else 1.0
    p = simulate(housner_block(cyl, c_r), motion, t_end=8.0, output_dt=0.01, rest_velocity=1e-9)
    assert r.uplift_time == pytest.approx(p.uplift_time, abs=1e-8)
    # the tilt stays on the pulse's line: φ ∈ {φ0, φ0 + π}, φ0 = azimuth or azimuth + π
    tilted = r.theta > 0
    assert np.allclose(np.cos(r.phi[tilted] - azimuth) ** 2, 1.0, atol=1e-12)
    crossings = r.times_of("planar-crossing")
    assert crossings.size >= 3
    np.testing.assert_allclose(crossings, p.impact_times[:crossings.size], atol=t_tol)
    assert r.theta_max == pytest.approx(p.theta_max, abs=theta_tol)
    # signed tilt along the pulse line against the planar history on the common grid
    grid = np.arange(1, 800) * 0.01
    mine = np.isin(r.t, grid)
    theirs = np.isin(p.t, grid)
    signed = r.theta[mine] * np.cos(r.phi[mine] - azimuth)
    ref = p.theta[theirs]
    sign = np.sign(ref[np.argmax(np.abs(ref))] * signed[np.argmax(np.abs(signed))])
    np.testing.assert_allclose(sign * signed, ref, atol=theta_tol)
