"""Limits and bounds that SPEC §2 states, as property tests (hypothesis)."""
from __future__ import annotations

import math

import numpy as np

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from rockdesign.planar.design.equivalence import frame_size_factor
from rockdesign.planar.design.frequencies import frame_frequency_parameter, frequency_parameter, uplifted_frequency_ratio
from rockdesign.planar.design.geometry import (critical_curvature, displacement_capacity, rocking_geometry,
                                        rotation_capacity_curved, wedge_angle)
from rockdesign.planar.design.pushover import post_uplift_stiffness_linear, restoring_force_ratio, restoring_stiffness_ratio
from rockdesign.planar.design.quantities import design_quantities
from rockdesign.planar.design.restitution import restitution_block, restitution_frame, restitution_podium
from rockdesign.planar.system import Column, RockingSystem, Superstructure

SET = settings(max_examples=60, deadline=None)
tan_a = st.floats(0.03, 0.5)
lam = st.floats(0.2, 0.6)


@SET
@given(tan_a, st.floats(0.05, 0.6), st.floats(0.0, 0.95), lam)
def test_curved_capacity_between_alpha_and_alpha_ext(ta, extra, frac, lam_):
    # any curved extension: α ≤ θc; instability while rolling (ρ ≤ ρc) gives θc ≤ α'… and ρ > ρc gives θc ≥ α'
    tae = ta + extra
    need = (tae - ta) / 2
    rho = need + frac * 3.0
    tc = rotation_capacity_curved(ta, tae, rho)
    assert tc >= math.atan(ta) - 1e-12
    if rho <= critical_curvature(ta, tae):
        assert tc <= math.atan(tae) + 1e-12
    else:
        assert tc >= math.atan(tae) - 1e-12
    # the restoring force vanishes at θc (F_R = 0 defines the capacity, Eq 3.56)
    geo = rocking_geometry(Column(1.0, ta, 1.0, lam_, "curved", tae, 2.0 * rho))
    assert abs(restoring_force_ratio(geo.theta_c, geo)) < 1e-9


@SET
@given(tan_a, st.floats(0.05, 0.6), lam)
def test_huge_radius_is_the_flat_extended_block(ta, extra, lam_):
    # ρ → ∞: β → 0, rocking about 2B' from the start: pushover and capacity of flat extensions
    tae = ta + extra
    curved = rocking_geometry(Column(1.0, ta, 1.0, lam_, "curved", tae, 1e7))
    flat = rocking_geometry(Column(1.0, ta, 1.0, lam_, "flat", tae))
    assert curved.beta < 1e-6
    assert curved.theta_c == pytest.approx(flat.theta_c, abs=1e-6)
    for frac in (0.1, 0.5, 0.9):
        th = frac * flat.theta_c
        assert restoring_force_ratio(th, curved) == pytest.approx(restoring_force_ratio(th, flat), abs=1e-6)


@SET
@given(tan_a, lam, st.floats(0.0, 2.0))
def test_small_radius_stiffness_tends_to_the_block(ta, lam_, rho):
    # ρ = 0 is Housner's block: k*_I = 2ρ − 1 → −1 (Eq 3.50); exact stiffness at θ = 0 → −1/cos²α (Eq 3.19)
    assert post_uplift_stiffness_linear(0.0, 1) == -1.0
    block = rocking_geometry(Column(1.0, ta, 1.0, lam_))
    assert restoring_stiffness_ratio(0.0, block) == pytest.approx(-1 / math.cos(math.atan(ta)) ** 2)
    assert post_uplift_stiffness_linear(rho, 1) - post_uplift_stiffness_linear(rho, 2) == pytest.approx(2 * rho)


@SET
@given(tan_a, lam, st.floats(0.0, 50.0), st.floats(0.0, 12.0))
def test_restitution_in_unit_interval_and_limits(ta, lam_, gamma, eta):
    a = math.atan(ta)
    for c in (restitution_block(a, lam_), restitution_frame(a, lam_, gamma), restitution_podium(a, lam_, gamma, eta)):
        assert 0.0 < c <= 1.0
    # γ = 0: the frame is the solitary column; η = 0: the podium is the frame; podium = frame with γ(1+η)
    assert restitution_frame(a, lam_, 0.0) == pytest.approx(restitution_block(a, lam_), rel=1e-14)
    assert restitution_podium(a, lam_, gamma, 0.0) == pytest.approx(restitution_frame(a, lam_, gamma))
    assert restitution_podium(a, lam_, gamma, eta) == pytest.approx(restitution_frame(a, lam_, gamma * (1 + eta)))


@SET
@given(st.floats(0.5, 5.0), lam, st.floats(0.0, 100.0))
def test_frame_limits(R, lam_, gamma):
    g = 9.81
    assert frame_frequency_parameter(R, lam_, 0.0, g) == pytest.approx(frequency_parameter(R, lam_, g))
    # R̂ = R at γ = 0 and tends to 2R/(1+λ) as γ → ∞ (Eq 3.81); p̂ of the frame equals p of R̂ (Eq 3.89)
    assert frame_size_factor(lam_, 0.0) == pytest.approx(1.0)
    assert frame_size_factor(lam_, gamma) <= 2.0 / (1 + lam_) + 1e-12
    r_hat = frame_size_factor(lam_, gamma) * R
    assert frame_frequency_parameter(R, lam_, gamma, g) == pytest.approx(frequency_parameter(r_hat, lam_, g))


@SET
@given(tan_a, lam, st.floats(0.1, 50.0), st.floats(0.0, 12.0))
def test_uplifted_frequency_ratio_bounds(ta, lam_, gamma, eta):
    a = math.atan(ta)
    s = uplifted_frequency_ratio(lam_, gamma, eta, a)
    assert 1.0 <= s <= 1.0 / math.sin(a) + 1e-12
    assert uplifted_frequency_ratio(lam_, gamma, 0.0, a) == pytest.approx(1.0)


@SET
@given(tan_a, st.floats(0.05, 0.5), st.floats(0.0, 2.0))
def test_capacity_displacement_is_the_top_displacement_at_theta_c(ta, extra, frac):
    tae = ta + extra
    rho = (tae - ta) / 2 + frac
    col = Column(1.5, 1.5 * ta, 1.0, 1 / 3, "curved", 1.5 * tae, 3.0 * rho)
    u = displacement_capacity(col)
    assert u >= 2 * 1.5 * ta - 1e-12                  # at least the flat-base 2B
    assert displacement_capacity(Column(1.5, 1.5 * ta, 1.0, 1 / 3)) == pytest.approx(3.0 * ta)


@SET
@given(tan_a, lam, st.integers(1, 40), st.floats(1.0, 30.0), st.floats(0.5, 10.0), st.floats(0.05, 1.0))
def test_quantities_complete_and_finite(ta, lam_, n, gamma, eta, period):
    m_c = 1000.0
    sup = Superstructure(eta * gamma * n * m_c, 2 * math.pi / period, 0.02, True)
    s = RockingSystem("p", "podium", Column(1.5, 1.5 * ta, m_c, lam_), n, gamma * n * m_c, sup, g=9.81)
    q = design_quantities(s)
    assume(q)
    for x in q.values():
        assert math.isfinite(x.value), x.name
    assert q["gamma"].value == pytest.approx(gamma)
    assert q["zeta_su"].value == pytest.approx(0.02)
    assert 0 < q["c_r"].value <= 1


def test_wedge_angle_domain():
    with pytest.raises(ValueError):
        wedge_angle(0.1, 0.3, 0.05)


def test_capacity_just_above_critical_curvature_is_the_rolling_root():
    # found by the property test above with random examples: ρ slightly above ρc, where Eq 3.56's
    # ρ > ρc branch returns an angle below β (outside the rocking phase); F_R vanishes at the rolling root
    ta, tae, rho = 0.1875, 0.4375, 0.2890625
    assert rho > critical_curvature(ta, tae)
    geo = rocking_geometry(Column(1.0, ta, 1.0, 0.5, "curved", tae, 2.0 * rho))
    assert geo.theta_c < geo.beta
    assert geo.theta_c == pytest.approx(math.atan(ta / (1.0 - 2.0 * rho)), rel=1e-14)
    assert abs(restoring_force_ratio(geo.theta_c, geo)) < 1e-12
    # and F_R > 0 everywhere before it (the first zero)
    assert all(restoring_force_ratio(t, geo) > 0 for t in np.linspace(0.0, geo.theta_c, 200)[:-1])
