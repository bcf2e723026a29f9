"""Reference equations of motion: kinematics derivatives, the generic equation against the thesis's
explicit forms, energy conservation, and the closed-form inputs (SPEC §2, §3).

Sources: SPEC.md §3.1 (Example 4.1 check), thesis Eqs 3.12, 3.37/3.38, 3.57/3.58, 3.75/3.76,
3.85/3.86, A.5/A.6 (correct expanded podium form), 3.15, 3.59–3.61, 3.87/3.88, 4.32;
validation/cases.json ids cited per test.
"""
import math

import numpy as np
import pytest

from casedata import expected
from rockdesign.planar.design.restitution import restitution_flat_extensions

from rockdesign.motions.motion import no_motion
from rockdesign.bench.baseline import simulate_scipy
from rockdesign.bench.baseline.equations import (accelerations_exact, accelerations_linear,
                                            cap_beam_kinematics)
from rockdesign.bench.baseline.parameters import (model_parameters, restitution_coefficient,
                                             rotation_capacity, uplift_thresholds,
                                             uplifted_frequency_ratio, wedge_angle)
from rockdesign.planar.system import Column, RockingSystem, Superstructure

G = 9.81


def make_system(extension="none", tan_alpha=0.1, tan_alpha_ext=0.2, rho=0.5, H=1.5, lam=1 / 3,
                gamma=0.0, eta=0.0, omega_s=None, zeta=0.0, **kw):
    """A column (γ = 0), frame (γ > 0) or podium (η > 0) with N = 4, m_C = 1000 kg."""
    B = tan_alpha * H
    if extension == "none":
        col = Column(H, B, 1000.0, lam)
    elif extension == "flat":
        col = Column(H, B, 1000.0, lam, "flat", tan_alpha_ext * H)
    else:
        col = Column(H, B, 1000.0, lam, "curved", tan_alpha_ext * H, 2 * H * rho)
    n = 4
    m_B = gamma * n * col.mass
    sup = None
    if eta > 0:
        sup = Superstructure(eta * m_B, omega_s, zeta, damping_correction=False)
    kind = "podium" if gamma > 0 else "column"
    return RockingSystem("test", kind, col, n if gamma > 0 else 1, m_B if gamma > 0 else 0.0, sup, **kw)


KINEMATIC_CASES = [("none", 1, 1), ("none", -1, 1), ("flat", 1, 1), ("flat", -1, 1),
                   ("curved", 1, 1), ("curved", -1, 1), ("curved", 1, 2), ("curved", -1, 2)]


@pytest.mark.parametrize("extension,side,phase", KINEMATIC_CASES)
def test_kinematics_derivatives_match_finite_differences(extension, side, phase):
    """u_B', u_B'', w_B', w_B'' (derived by hand from SPEC §3.1) = central differences of u_B, w_B."""
    params = model_parameters(make_system(extension, rho=0.5))
    h = 1e-5
    for theta in side * np.array([0.0, 0.03, 0.09, 0.15, 0.4]):
        u, du, ddu, w, dw, ddw = cap_beam_kinematics(theta, side, phase, params)
        up = cap_beam_kinematics(theta + h, side, phase, params)
        um = cap_beam_kinematics(theta - h, side, phase, params)
        assert du == pytest.approx((up[0] - um[0]) / (2 * h), rel=1e-8, abs=1e-10)
        assert dw == pytest.approx((up[3] - um[3]) / (2 * h), rel=1e-8, abs=1e-10)
        assert ddu == pytest.approx((up[1] - um[1]) / (2 * h), rel=1e-7, abs=1e-9)
        assert ddw == pytest.approx((up[4] - um[4]) / (2 * h), rel=1e-7, abs=1e-9)
        assert ddu == pytest.approx((up[0] - 2 * u + um[0]) / h**2, rel=1e-4, abs=1e-5)


def test_kinematics_start_values_and_phase_continuity():
    """u_B(0) = 0, w_B(0) = 2H; curved phases I/II agree in u, u', w, w' at |θ| = β (SPEC §3.5);
    phase II is a rotation about the fixed pivot at B + rβ (u_B/2 + w_B'/2 constant)."""
    params = model_parameters(make_system("curved", rho=0.5))
    for side in (1, -1):
        u, du, _, w, dw, _ = cap_beam_kinematics(0.0, side, 1, params)
        assert (u, w) == pytest.approx((0.0, 3.0), abs=1e-15)
        assert dw / du == pytest.approx(side * 0.1, rel=1e-14)   # w'/u' = tan(sα) at uplift
        k1 = cap_beam_kinematics(side * params.beta, side, 1, params)
        k2 = cap_beam_kinematics(side * params.beta, side, 2, params)
        assert k1[:2] + k1[3:5] == pytest.approx(k2[:2] + k2[3:5], abs=1e-14)
        pivots = [(k[0] + k[4]) / 2 for k in (cap_beam_kinematics(side * t, side, 2, params) for t in (0.12, 0.2, 0.5))]
        assert pivots == pytest.approx([side * (0.15 + params.radius * params.beta)] * 3, abs=1e-14)


def housner(theta, a_g, side, alpha, p):
    """Eq 3.12 (exact) and Eq 3.75 with p → p̂ (frame)."""
    return -p**2 * (math.sin(side * alpha - theta) + a_g / G * math.cos(side * alpha - theta))


@pytest.mark.parametrize("gamma", [0.0, 7.5])
def test_generic_equation_without_superstructure_is_housner(gamma):
    """SPEC Example 4.1 check: γ = η = 0 gives Eq 3.12; a frame gives Eq 3.75 with p̂ of Eq 3.76."""
    system = make_system("none", tan_alpha=0.15, gamma=gamma)
    params = model_parameters(system)
    R, alpha, lam = params.R, params.alpha, 1 / 3
    p_hat = math.sqrt((1 + 2 * gamma) / (1 + lam + 4 * gamma) * G / R)
    for side, theta, thd, a_g in [(1, 0.02, 0.3, -1.2), (1, 0.2, -0.5, 2.0), (-1, -0.07, 0.1, 3.3)]:
        thdd, _ = accelerations_exact(theta, thd, 0.0, 0.0, a_g, side, 1, params)
        assert thdd == pytest.approx(housner(theta, a_g, side, alpha, p_hat), rel=1e-13)


def test_generic_equation_flat_extensions_is_eq_3_37():
    """Eq 3.37 with R' = R cos α/cos α', λ' = λ cos²α'/cos²α; p̂ also equals Eq 3.38 (λ = 1/3)."""
    params = model_parameters(make_system("flat"))
    a, ae = math.atan(0.1), math.atan(0.2)
    p = math.sqrt(G / (params.R * (4 / 3)))
    p_hat = math.sqrt(4 * math.cos(ae) * math.cos(a) / (math.cos(ae) ** 2 + 3 * math.cos(a) ** 2)) * p
    for side, theta, thd, a_g in [(1, 0.05, 0.3, -1.2), (-1, -0.18, 0.2, 0.4)]:
        thdd, _ = accelerations_exact(theta, thd, 0.0, 0.0, a_g, side, 1, params)
        assert thdd == pytest.approx(housner(theta, a_g, side, ae, p_hat), rel=1e-13)


def podium_explicit(theta, thd, u_T, ud_T, a_g, side, phase, P, gamma, ge, om, zeta, rho, beta):
    """Thesis Eqs A.5 (phase I) / A.6 (phase II), the expanded podium equation (correct as printed);
    with η = 0 they are Eqs 3.85/3.86 and with γ = 0 Eqs 3.57/3.58."""
    s, al, c, R = side, P.alpha, math.cos(P.alpha), P.R
    r = 2 * rho * c * R
    S, C = math.sin(s * al - theta), math.cos(s * al - theta)
    if phase == 1:
        mass = (P.lam + (1 + 4 * gamma) * (1 + 4 * rho * c * (C - c) + 8 * rho**2 * c**2 * (1 - math.cos(theta)))
                + 4 * ge * (S**2 + 4 * rho * c * S * math.sin(theta) + 4 * rho**2 * c**2 * math.sin(theta) ** 2))
        top = (math.sin(2 * s * al - 2 * theta) - 4 * rho * c * math.sin(s * al - 2 * theta)
               - 4 * rho**2 * c**2 * math.sin(2 * theta))
        centrifugal = -thd**2 * ((1 + 4 * gamma) * (2 * rho * c * S + 4 * rho**2 * c**2 * math.sin(theta)) - 2 * ge * top)
        lever_w = S + 2 * rho * c * math.sin(theta)
        lever_u = C + 2 * rho * c * (1 - math.cos(theta))
        u_B = 2 * R * math.sin(s * al) - 2 * R * S + 2 * r * (theta - math.sin(theta))      # Eq 4.11
    else:
        sb = s * beta
        Sb, Cb = math.sin(sb - theta), math.cos(sb - theta)
        pivot2 = 1 + 4 * rho * c * (math.cos(al - beta) - c) + 8 * rho**2 * c**2 * (1 - math.cos(beta))
        mass = (P.lam + (1 + 4 * gamma) * pivot2
                + 4 * ge * (S**2 + 4 * rho * c * S * (math.sin(theta) + Sb)
                            + 4 * rho**2 * c**2 * (math.sin(theta) ** 2 + 2 * Sb * math.sin(theta) + Sb**2)))
        top = (math.sin(2 * s * al - 2 * theta)
               - 4 * rho * c * (math.sin(s * al - 2 * theta) - math.sin(s * al + sb - 2 * theta))
               - 4 * rho**2 * c**2 * (math.sin(2 * theta) + 2 * math.sin(sb - 2 * theta) - math.sin(2 * sb - 2 * theta)))
        centrifugal = thd**2 * 2 * ge * top
        lever_w = S + 2 * rho * c * (Sb + math.sin(theta))
        lever_u = C + 2 * rho * c * (Cb - math.cos(theta))
        u_B = 2 * R * math.sin(s * al) - 2 * R * S + 2 * r * (sb - Sb - math.sin(theta))    # Eq 4.13
    ud_B = 2 * R * lever_u * thd
    rhs = (centrifugal - G / R * (1 + 2 * gamma + 2 * ge) * lever_w - a_g / R * (1 + 2 * gamma) * lever_u
           + 2 * ge * om / R * lever_u * (om * (u_T - u_B) + 2 * zeta * (ud_T - ud_B)))
    return rhs / mass


@pytest.mark.parametrize("gamma,eta", [(0.0, 0.0), (6.0, 0.0), (10.0, 5.0)])
@pytest.mark.parametrize("rho", [0.25, 1.0])
def test_generic_curved_equation_matches_expanded_thesis_forms(gamma, eta, rho):
    """Generic SPEC §3.1 equation = Eqs 3.57/3.58 (column), 3.85/3.86 (frame), A.5/A.6 (podium)."""
    om, zeta = 13.2, 0.03
    system = make_system("curved", tan_alpha=0.15, tan_alpha_ext=0.3, rho=rho, gamma=gamma, eta=eta,
                         omega_s=om if eta else None, zeta=zeta)
    P = model_parameters(system)
    ge = P.gamma_eta
    for side in (1, -1):
        for phase, theta in [(1, 0.3 * P.beta), (1, 0.9 * P.beta), (2, 1.2 * P.beta), (2, P.beta + 0.1)]:
            th = side * theta
            for thd, u_T, ud_T, a_g in [(0.4, 0.01, -0.2, 1.5), (-0.7, -0.03, 0.5, -2.5)]:
                got, _ = accelerations_exact(th, thd, u_T, ud_T, a_g, side, phase, P)
                want = podium_explicit(th, thd, u_T, ud_T, a_g, side, phase, P, gamma, ge, om, zeta, rho, P.beta)
                assert got == pytest.approx(want, rel=1e-12, abs=1e-12)


def test_linearized_equations_are_spec_3_2():
    """Eq 3.15 (block), 3.40 (flat, p̂ = p), 3.59/3.61 (curved, linearized β), 3.87/3.88 (frame with
    p̂ of Eq 3.76), and the podium with p̂² = g/R (1+2γ+2γη)/(1+λ+4γ) of Eq 4.32."""
    a_g, thd = -0.8, 0.3
    P = model_parameters(make_system("none"), linear=True)
    p2 = G / (P.R * (4 / 3))
    for side, th in [(1, 0.04), (-1, -0.08)]:
        assert accelerations_linear(th, thd, 0, 0, a_g, side, 1, P)[0] == pytest.approx(
            -p2 * (side * P.alpha - th + a_g / G), rel=1e-14)
    P = model_parameters(make_system("flat"), linear=True)
    assert accelerations_linear(0.1, thd, 0, 0, a_g, 1, 1, P)[0] == pytest.approx(
        -p2 * (math.atan(0.2) - 0.1 + a_g / G), rel=1e-14)
    gamma, rho = 6.0, 1.0
    P = model_parameters(make_system("curved", rho=rho, gamma=gamma), linear=True)
    assert P.beta == pytest.approx((math.atan(0.2) - math.atan(0.1)) / (2 * rho), rel=1e-15)
    p_hat2 = (1 + 2 * gamma) / (1 + 1 / 3 + 4 * gamma) * G / P.R
    for side in (1, -1):
        th1, th2 = side * 0.5 * P.beta, side * 1.5 * P.beta
        assert accelerations_linear(th1, thd, 0, 0, a_g, side, 1, P)[0] == pytest.approx(
            -p_hat2 * (side * P.alpha - th1 * (1 - 2 * rho) + a_g / G), rel=1e-14)
        assert accelerations_linear(th2, thd, 0, 0, a_g, side, 2, P)[0] == pytest.approx(
            -p_hat2 * (side * P.alpha_ext - th2 + a_g / G), rel=1e-14)
    gamma, eta, om, zeta = 10.0, 5.0, 13.2, 0.02
    P = model_parameters(make_system("none", tan_alpha=0.15, gamma=gamma, eta=eta, omega_s=om, zeta=zeta), linear=True)
    p_hat2 = (1 + 2 * gamma + 2 * gamma * eta) / (1 + 1 / 3 + 4 * gamma) * G / P.R
    th, u_T, ud_T = 0.05, 0.2, -0.1
    F = om**2 * (u_T - 2 * P.R * th) + 2 * zeta * om * (ud_T - 2 * P.R * thd)
    got = accelerations_linear(th, thd, u_T, ud_T, a_g, 1, 1, P)
    want = -p_hat2 * (P.alpha - th) + (-(1 + 2 * gamma) * a_g + 2 * gamma * eta * F) / (P.R * (1 + 1 / 3 + 4 * gamma))
    assert got[0] == pytest.approx(want, rel=1e-13)
    assert got[1] == pytest.approx(-F - a_g, rel=1e-14)


def energy(params, state):
    """Total energy / (N m_C R²) of a free (ü_g = 0), undamped system (Lagrangian of SPEC §3.1)."""
    theta, thd, u_T, ud_T = state
    side = 1 if theta >= 0 else -1
    phase = 2 if params.curved and abs(theta) > params.beta else 1
    u, du, _, w, dw, _ = cap_beam_kinematics(theta, side, phase, params)
    R, gamma, ge = params.R, params.gamma, params.gamma_eta
    kinetic = 0.5 * thd**2 * (params.lam + (1 + 4 * gamma) * (du**2 + dw**2) / (4 * R**2))
    kinetic += 0.5 * ge * (ud_T**2 + (dw * thd) ** 2) / R**2
    potential = G / R * (1 + 2 * gamma + 2 * ge) * w / (2 * R) + 0.5 * ge * params.omega_s**2 * (u_T - u) ** 2 / R**2
    return kinetic + potential


@pytest.mark.parametrize("gamma,eta", [(0.0, 0.0), (10.0, 5.0)])
def test_energy_is_conserved_in_free_rocking_with_elastic_impacts(gamma, eta):
    """With ü_g = 0, ζ_s = 0 and c_r = 1 the Lagrangian system conserves energy through phase
    changes and impacts: checks the θ̇² term (sign corrected in SPEC §8, Eq 4.8) and Eq 4.21."""
    system = make_system("curved", tan_alpha=0.15, tan_alpha_ext=0.3, rho=0.5, gamma=gamma, eta=eta,
                         omega_s=20.0 if eta else None)
    params = model_parameters(system)
    res = simulate_scipy(system, no_motion(), theta0=0.25, t_end=6.0, restitution_formula=1.0,
                         record_every_step=True, rtol=1e-11, atol=1e-13)
    assert res.n_impacts >= 2 and len(res.events_of("phase")) >= 4
    e = np.array([energy(params, s) for s in zip(res.theta, res.theta_dot, res.u_T, res.u_T_dot)])
    assert np.max(np.abs(e - e[0])) < 1e-8 * abs(e[0])


# ------------------------------------------------------------------ closed-form inputs (SPEC §2)

def test_restitution_coefficients():
    """cases tab3.4_B1_cr/B2ec_cr (0.97052), tab3.4_B5ef_cr (printed Eq 3.39: 0.97031; CoAM 0.8872),
    eq4.20_podium_cr (0.914034), eq6.22_crth_frame_gamma3.692 (0.92764), ex2.1_cr (0.970518);
    a measured c_r overrides (SPEC §2)."""
    assert restitution_coefficient(make_system("none")) == pytest.approx(expected("tab3.4_B1_cr"), abs=5e-6)
    assert restitution_coefficient(make_system("curved", rho=0.25)) == pytest.approx(expected("tab3.4_B2ec_cr"), abs=5e-6)
    b5 = make_system("flat", restitution_rule="thesis-eq-3.39")
    assert restitution_coefficient(b5) == pytest.approx(expected("tab3.4_B5ef_cr"), abs=5e-6)
    assert restitution_coefficient(b5, "theory") == pytest.approx(
        restitution_flat_extensions(math.atan(0.1), math.atan(0.2), 1 / 3), abs=5e-5)   # CoAM, closed form
    podium = make_system("none", tan_alpha=0.15, gamma=10, eta=5, omega_s=13.2)
    assert restitution_coefficient(podium) == pytest.approx(expected("eq4.20_podium_cr"), abs=1e-6)
    frame = make_system("none", tan_alpha=0.1394, lam=0.54, gamma=3.692)
    assert restitution_coefficient(frame) == pytest.approx(expected("eq6.22_crth_frame_gamma3.692"), abs=5e-6)
    assert restitution_coefficient(make_system("none").with_restitution(0.81)) == 0.81
    assert restitution_coefficient(make_system("none"), 0.9) == 0.9


def test_uplift_thresholds_and_superstructure_frequency_ratio():
    """cases eq4.7_thresholds ([-6.831786, 10.1255]) and eq4.25_Sr_eta5 (2.29714)."""
    system = make_system("none", tan_alpha=0.15, gamma=10, eta=5, omega_s=13.2, zeta=0.01)
    params = model_parameters(system)
    f = 13.2**2 * 0.002 + 2 * 0.01 * 13.2 * (-0.01)
    assert uplift_thresholds(params, f) == pytest.approx((-6.831786, 10.1255), abs=1e-4)
    assert uplift_thresholds(model_parameters(make_system("none", tan_alpha=0.15))) == pytest.approx(
        (-G * 0.15, G * 0.15), rel=1e-15)
    assert uplifted_frequency_ratio(system.column, 10.0, 50.0) == pytest.approx(expected("eq4.25_Sr_eta5"), abs=5e-6)


@pytest.mark.parametrize("case,tan_a,rho", [
    ("tab6.5_F02", 0.1, 0.25), ("tab6.5_F03", 0.1, 0.5), ("tab6.5_F04", 0.1, 1.0),
    ("tab6.5_F06", 0.15, 0.25), ("tab6.5_F07", 0.15, 0.5), ("tab6.5_F08", 0.15, 1.0)])
def test_wedge_angle_and_capacity(case, tan_a, rho):
    """Table 6.5 (tan α' = 0.3): β (Eq 3.44) and θc (corrected Eq 3.56) to 5e-4."""
    beta, theta_c = expected(case)
    assert wedge_angle(tan_a, 0.3, rho) == pytest.approx(beta, abs=5e-4)
    assert rotation_capacity(tan_a, 0.3, rho, "curved") == pytest.approx(theta_c, abs=5e-4)
