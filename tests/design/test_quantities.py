"""Closed-form design quantities against published numbers (read from tests/validation/data/cases.json).

Sources: thesis Examples 2.1, 3.7–3.10, Table 6.5, Eqs 3.81/4.20/4.25/4.7, Sec 3.4.1, Sec 6.3.
"""
from __future__ import annotations

import math

import pytest

from casedata import case, expected
from rockdesign.planar.design.equivalence import equivalent_size, equivalent_size_from_spectra, frame_size_factor
from rockdesign.planar.design.frequencies import (critical_rolling_frequency_parameter, frame_frequency_parameter,
                                           frequency_parameter, rocking_period, uplifted_frequency_ratio)
from rockdesign.planar.design.geometry import (critical_curvature, rocking_geometry, rotation_capacity_curved,
                                        wedge_angle)
from rockdesign.planar.design.pushover import restoring_force_ratio, restoring_stiffness_ratio
from rockdesign.planar.design.quantities import design_quantities
from rockdesign.planar.design.restitution import (restitution_block, restitution_flat_extensions, restitution_frame,
                                           restitution_podium)
from rockdesign.planar.design.uplift import podium_uplift_thresholds
from rockdesign.planar.system import Column, RockingSystem, Superstructure

G = 9.81


def test_example_2_1_restitution_and_rocking_period():
    # Example 2.1: tan α = 0.1, p = 2.2, θ0 = 0.08 → c_r = 0.97052 (Eq 2.15), T_R/4 = 1.04822 s (Eq 2.8)
    alpha = math.atan(0.1)
    assert restitution_block(alpha, 1 / 3) == pytest.approx(expected("ex2.1_cr"), abs=5e-6)
    assert rocking_period(2.2, alpha, 0.08) / 4 == pytest.approx(expected("ex2.1_TR_quarter"), abs=5e-6)


def test_size_effect_frequency_parameters():
    # Sec 3.2.1: R = 2 m and 3 m, λ = 1/3 → p = 1.918007, 1.566046
    assert frequency_parameter(2.0, 1 / 3, G) == pytest.approx(expected("sec3.2.1_p1"), abs=1e-6)
    assert frequency_parameter(3.0, 1 / 3, G) == pytest.approx(expected("sec3.2.1_p2"), abs=1e-6)


@pytest.mark.parametrize("name,tan_a,tan_ap,rho", [
    ("F02", 0.10, 0.30, 0.25), ("F03", 0.10, 0.30, 0.50), ("F04", 0.10, 0.30, 1.00),
    ("F06", 0.15, 0.30, 0.25), ("F07", 0.15, 0.30, 0.50), ("F08", 0.15, 0.30, 1.00),
])
def test_table_6_5_wedge_angle_and_capacity(name, tan_a, tan_ap, rho):
    beta, theta_c = expected(f"tab6.5_{name}")
    # Table 6.5 with the corrected Eq 3.56 (atan, SPEC §8); tolerance 5e-4 as printed
    assert wedge_angle(tan_a, tan_ap, rho) == pytest.approx(beta, abs=5e-4)
    assert rotation_capacity_curved(tan_a, tan_ap, rho) == pytest.approx(theta_c, abs=5e-4)


def test_critical_curvature_section_6_4_2():
    assert critical_curvature(0.1, 0.3) == pytest.approx(1 / 3, abs=1e-12)
    assert critical_curvature(0.15, 0.3) == pytest.approx(0.25, abs=1e-12)


def test_capacity_examples_3_7_and_3_10():
    # ρ = 0.165 (linearized ρc) → θc = 0.1483 (thesis prints 0.149 = α'), β = 0.1521
    assert rotation_capacity_curved(0.1, 0.15, 0.165) == pytest.approx(expected("ex3.10_beta_thetac")[1], abs=1e-3)
    assert wedge_angle(0.1, 0.15, 0.165) == pytest.approx(expected("ex3.10_beta_thetac")[0], abs=5e-4)


@pytest.mark.parametrize("lam,gamma,case_id", [(0.422, 10, "ex3.8_Rhat"), (1 / 3, 5, "sec3.4.1_Rhat_lam0.333_gam5"),
                                               (1 / 3, math.inf, "sec3.4.1_Rhat_lam0.333_gaminf"),
                                               (0.49, math.inf, "sec3.4.1_Rhat_lam0.490_gaminf")])
def test_equivalent_frame_size(lam, gamma, case_id):
    # Example 3.8 and Sec 3.4.1 (Eq 3.81)
    assert frame_size_factor(lam, gamma) == pytest.approx(expected(case_id), abs=5e-5)


def test_equivalent_size_identities():
    # Eq 2.24 = Eq 3.81 at λ = 1/3 (γ = 5): (1+4γ)... = 1.454545; Eq 3.71: α'/α for tan 0.1/0.2
    assert frame_size_factor(1 / 3, 5) == pytest.approx(16 / 11, abs=1e-12)
    assert equivalent_size(1.0, 1 / 3, 0.0, math.atan(0.2) / math.atan(0.1)) == pytest.approx(expected("eq3.71_B2a"), abs=1e-5)
    assert equivalent_size_from_spectra(4.53, 3.21) == pytest.approx(expected("eq3.65"), abs=5e-4)


def test_frame_restitution_and_frequency_examples():
    # Example 3.9 F1: λ = 0.42, γ = 15, R = 2 m, tan α = 0.1 → c_r 0.9611, p̂ 1.5734
    a = math.atan(0.1)
    assert restitution_frame(a, 0.42, 15) == pytest.approx(expected("ex3.9_F1")[0], abs=5e-4)
    assert frame_frequency_parameter(2.0, 0.42, 15, G) == pytest.approx(expected("ex3.9_F1")[1], abs=5e-4)
    # Example 3.10 F1ec: curved at ρ = ρc (linearized 0.165), λ = 0.38, γ = 10 → p̂ 1.2909 (Eq 3.94)
    p_hat = critical_rolling_frequency_parameter(2.0, 0.38, 10, a, math.atan(0.15), G)
    assert p_hat == pytest.approx(expected("ex3.10_F1ec")[1], abs=6e-4)
    # Example 3.10 B3ec: solitary, λ = 0.36, R = 3 m → 1.2687
    assert critical_rolling_frequency_parameter(3.0, 0.36, 0, a, math.atan(0.15), G) == pytest.approx(expected("ex3.10_B3ec")[1], abs=6e-4)


def test_specimen_section_6_3():
    # Eq 6.18: S_r = 1.5198; Eqs 6.22/6.23: frame c_r 0.93000 (γ = 1.682), 0.92764 (γ = 3.692)
    a = math.atan(0.1394)
    assert uplifted_frequency_ratio(0.54, 2.1637, 1.6141, a) == pytest.approx(expected("sec6.3_Sr"), abs=5e-4)
    assert restitution_frame(a, 0.54, 1.682) == pytest.approx(expected("eq6.22_crth_frame_gamma1.682"), abs=5e-5)
    assert restitution_frame(a, 0.54, 3.692) == pytest.approx(expected("eq6.22_crth_frame_gamma3.692"), abs=5e-5)


@pytest.mark.parametrize("eta", [1, 5, 10])
def test_uplifted_frequency_ratio_eq_4_25(eta):
    a = math.atan(0.15)
    assert uplifted_frequency_ratio(1 / 3, 10, eta, a) == pytest.approx(expected(f"eq4.25_Sr_eta{eta}"), abs=1e-5)
    # γ → ∞ (Eq 4.26): S_r = √((1+η)/(1+η sin²α)), written out independently of Eq 4.25
    limit = math.sqrt((1 + eta) / (1 + eta * math.sin(a) ** 2))
    assert uplifted_frequency_ratio(1 / 3, math.inf, eta, a) == pytest.approx(limit, abs=1e-9)


def test_uplifted_frequency_ratio_eta_limit():
    a = math.atan(0.15)
    assert uplifted_frequency_ratio(1 / 3, 10, 1e9, a) == pytest.approx(1 / math.sin(a), rel=1e-6)


def test_podium_restitution_and_uplift_thresholds():
    a = math.atan(0.15)
    assert restitution_podium(a, 1 / 3, 10, 5) == pytest.approx(expected("eq4.20_podium_cr"), abs=1e-6)
    lo, hi = podium_uplift_thresholds(0.15, G, 10, 5, 13.2, 0.01, 0.002, -0.01)
    assert lo == pytest.approx(expected("eq4.7_thresholds")[0], abs=1e-6)
    assert hi == pytest.approx(expected("eq4.7_thresholds")[1], abs=1e-4)


def test_flat_extension_restitution_corrected_and_printed():
    # Table 3.4 B5ef: printed Eq 3.39 → 0.97031; CoAM about the extended pivots → 0.8872
    a, ap = math.atan(0.1), math.atan(0.2)
    assert restitution_flat_extensions(a, ap, 1 / 3, printed=True) == pytest.approx(expected("tab3.4_B5ef_cr"), abs=5e-5)
    assert restitution_flat_extensions(a, ap, 1 / 3) == pytest.approx(0.8872, abs=5e-4)


@pytest.mark.parametrize("case_id", ["pushover_rho0.25", "pushover_rho0.5", "pushover_rho1.0"])
def test_pushover_curves(case_id):
    # F_R/m [N/kg] for 2H = 3 m, tan α 0.1, tan α' 0.2 (Eqs 3.48, phase II) at the case's θ points
    rho, thetas = case(case_id)["inputs"]["rho"], case(case_id)["inputs"]["theta_rad"]
    geo = rocking_geometry(Column(1.5, 0.15, 1.0, 1 / 3, "curved", 0.3, rho * 3.0))
    for th, f in zip(thetas, expected(case_id)):
        # θ points are printed to 6 decimals: |dF/dθ|·5e-7 rad ≤ 1e-5 N/kg
        assert G * restoring_force_ratio(th, geo) == pytest.approx(f, abs=1e-5)


def test_phase_one_stiffness_corrected_eq_3_49():
    # cases.json: k/(m g) at θ = 0 for ρ = 0.25, 0.5, 1.0 → −0.51, −0.01, 0.99 (→ 2ρ − 1 linearized)
    for rho, k0 in ((0.25, -0.51), (0.5, -0.01), (1.0, 0.99)):
        geo = rocking_geometry(Column(1.5, 0.15, 1.0, 1 / 3, "curved", 0.3, rho * 3.0))
        assert restoring_stiffness_ratio(0.0, geo) == pytest.approx(k0, abs=2e-6)


def test_quantity_set_for_a_podium_has_contract_names():
    sup = Superstructure(5 * 10 * 1000.0, 13.2, 0.01, True)
    s = RockingSystem("p", "podium", Column(1.5, 0.225, 1000.0, 1 / 3), 1, 10 * 1000.0, sup, g=G)
    q = design_quantities(s)
    for name in ("alpha", "R", "p", "lambda", "c_r", "uplift_acceleration", "uplift_acceleration_linear",
                 "theta_c", "k_phase2", "R_hat", "p_hat", "gamma", "eta", "omega_s", "omega_su", "S_r", "zeta_su",
                 "omega_s_over_p", "u_capacity"):
        assert name in q, name
    assert q["c_r"].value == pytest.approx(expected("eq4.20_podium_cr"), abs=1e-6)
    assert q["zeta_su"].value == pytest.approx(0.01, abs=1e-12)  # damping correction
    assert q["u_capacity"].value == pytest.approx(0.45, abs=1e-12)
