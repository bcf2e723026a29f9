"""Elastic response spectra: the exact Nigam–Jennings recurrence (SPEC §5).

Checks: closed-form SDOF responses to constant and ramp ground acceleration; the analytic
free-vibration tail against a brute-force evaluation of the free decay; agreement with eqsig
(the same recurrence, samples only) to 1e-6 relative; the time-scaling identity of Eq 6.5.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.motions.library import load_record
from rockdesign.motions.spectra import (free_vibration_peak, response_spectrum, sd_max, sd_max_of_samples,
                                        sdof_response)


def test_constant_ground_acceleration_matches_closed_form():
    # ü + 2ζωu̇ + ω²u = −A from rest: u = −A/ω² [1 − e^(−ζωt)(cos ω_d t + ζ/√(1−ζ²) sin ω_d t)]
    A, dt, n = 1.7, 0.013, 800
    for zeta in (0.0, 0.02, 0.3):
        omega = 2 * math.pi / 0.77
        u, v = sdof_response(np.full(n, A), dt, omega, zeta)
        t = np.arange(n) * dt
        root = math.sqrt(1 - zeta ** 2)
        wd = omega * root
        decay = np.exp(-zeta * omega * t)
        u_exact = -A / omega ** 2 * (1 - decay * (np.cos(wd * t) + zeta / root * np.sin(wd * t)))
        v_exact = -A / omega ** 2 * decay * omega / root * np.sin(wd * t)
        assert np.max(np.abs(u - u_exact)) < 1e-12 * A / omega ** 2 * n
        assert np.max(np.abs(v - v_exact)) < 1e-12 * A / omega * n


def test_ramp_ground_acceleration_matches_closed_form():
    # ü_g = c t: u = −(c/ω²)(t − 2ζ/ω) + e^(−ζωt)(C1 cos ω_d t + C2 sin ω_d t), at rest at t = 0
    c, dt, n, zeta = 0.9, 0.01, 600, 0.05
    omega = 2 * math.pi / 1.3
    wd = omega * math.sqrt(1 - zeta ** 2)
    t = np.arange(n) * dt
    u, _ = sdof_response(c * t, dt, omega, zeta)
    c1 = -2 * zeta * c / omega ** 3
    c2 = c * (1 - 2 * zeta ** 2) / (omega ** 2 * wd)
    u_exact = -(c / omega ** 2) * (t - 2 * zeta / omega) + np.exp(-zeta * omega * t) * (
        c1 * np.cos(wd * t) + c2 * np.sin(wd * t))
    assert np.max(np.abs(u - u_exact)) < 1e-10 * np.max(np.abs(u_exact))


@pytest.mark.parametrize("zeta", [0.0, 0.02, 0.2])
@pytest.mark.parametrize("u0,v0", [(0.1, 0.0), (0.0, 0.3), (0.05, -0.4), (-0.2, 0.9), (0.3, 0.01)])
def test_free_vibration_peak_against_brute_force(zeta, u0, v0):
    omega = 2 * math.pi / 2.3
    wd = omega * math.sqrt(1 - zeta ** 2)
    tau = np.linspace(0.0, 4 * 2.3, 400001)
    u = np.exp(-zeta * omega * tau) * (u0 * np.cos(wd * tau) + (v0 + zeta * omega * u0) / wd * np.sin(wd * tau))
    brute = np.max(np.abs(u))
    assert free_vibration_peak(u0, v0, omega, zeta) == pytest.approx(brute, rel=1e-9)


def test_tail_counts_the_free_decay_after_the_record():
    # a short half-sine ends while a long-period oscillator is still swinging up: SD(3 s) lives in
    # the free vibration; the closed-form tail must equal a zero-padded fine-step computation
    dt = 0.0005
    t = np.arange(0, 0.2 + dt / 2, dt)
    accel = 3.0 * np.sin(math.pi * t / 0.2)
    accel[-1] = 0.0
    periods = np.array([3.0])
    with_tail = response_spectrum(accel, dt, periods, 0.02)[0][0]
    without_tail = response_spectrum(accel, dt, periods, 0.02, include_tail=False)[0][0]
    padded = np.concatenate([accel, np.zeros(int(6.0 / dt))])
    brute = response_spectrum(padded, dt, periods, 0.02, include_tail=False)[0][0]
    assert with_tail > 1.5 * without_tail
    assert with_tail == pytest.approx(brute, rel=1e-6)
    assert with_tail >= brute


def test_pseudo_quantities_and_linearity():
    rng = np.random.default_rng(3)
    accel = rng.standard_normal(3000)
    periods = np.geomspace(0.05, 10, 30)
    sd, psv, psa = response_spectrum(accel, 0.01, periods, 0.02)
    omega = 2 * np.pi / periods
    np.testing.assert_allclose(psv, omega * sd, rtol=1e-14)
    np.testing.assert_allclose(psa, omega ** 2 * sd, rtol=1e-14)
    np.testing.assert_allclose(response_spectrum(-2.5 * accel, 0.01, periods, 0.02)[0], 2.5 * sd, rtol=1e-12)


def _eqsig_case(motion_accel, dt, periods, zeta):
    """Relative SD and PSV differences from eqsig where T ≥ 10 Δt.  eqsig takes the peak at the samples
    only; where T < 10 Δt rockdesign sub-steps (the PEER convention, tests/validation), so its peak
    includes eqsig's samples and is never lower."""
    eqsig_sdof = pytest.importorskip("eqsig.sdof")
    sd_ref, psv_ref, _ = eqsig_sdof.pseudo_response_spectra(motion_accel, dt, periods, zeta)
    sd, psv, _ = response_spectrum(motion_accel, dt, periods, zeta, include_tail=False)
    long = periods >= 10 * dt
    assert long.sum() >= 0.7 * periods.size
    assert np.all(sd[~long] >= sd_ref[~long] * (1 - 1e-6)), sd[~long] / sd_ref[~long] - 1
    return np.max(np.abs(sd[long] / sd_ref[long] - 1)), np.max(np.abs(psv[long] / psv_ref[long] - 1))


@pytest.mark.parametrize("zeta", [0.02, 0.05])
def test_matches_eqsig_on_builtin_record(zeta):
    # eqsig runs the same recurrence on the samples (no tail); compare over the record duration
    motion = load_record("p695-ff/11a")
    periods = np.geomspace(0.05, 10, 40)
    _, accel = motion.sampled()
    err_sd, err_psv = _eqsig_case(accel, motion.dt, periods, zeta)
    assert err_sd < 1e-6
    assert err_psv < 1e-6


def test_matches_eqsig_on_el_centro(shared_records):
    from rockdesign.motions.records import read_record_file
    motion = read_record_file(shared_records / "RSN6_IMPVALL.I_I-ELC180.AT2")
    periods = np.geomspace(0.05, 10, 25)
    err_sd, _ = _eqsig_case(motion.samples, motion.dt, periods, 0.02)
    assert err_sd < 1e-6


def test_time_scaling_identity():
    # Δt → f Δt maps SD(T) to f² SD(T/f) exactly (ω dt is invariant), the basis of Eq 6.5 scaling
    rng = np.random.default_rng(7)
    accel = rng.standard_normal(1500)
    periods = np.geomspace(0.1, 5, 12)
    f = math.sqrt(0.1)
    sd = response_spectrum(accel, 0.01, periods, 0.02)[0]
    sd_scaled = response_spectrum(accel, 0.01 * f, periods * f, 0.02)[0]
    np.testing.assert_allclose(sd_scaled, f ** 2 * sd, rtol=1e-9)


def test_sd_max_refinement_finds_the_grid_maximum():
    motion = load_record("p695-ff/11a")
    value, period = sd_max(motion)
    dense = np.linspace(period * 0.97, period * 1.03, 601)
    _, accel = motion.sampled()
    sd_dense = response_spectrum(accel, motion.dt, dense, 0.02)[0]
    assert value >= sd_dense.max() * (1 - 1e-9)
    coarse, _ = sd_max_of_samples(accel, motion.dt, refine=False)
    assert value >= coarse


def test_invalid_inputs_raise():
    with pytest.raises(ValueError):
        response_spectrum(np.zeros(10), 0.0, [1.0])
    with pytest.raises(ValueError):
        response_spectrum(np.zeros(10), 0.01, [1.0], damping=1.0)
    with pytest.raises(ValueError):
        response_spectrum(np.zeros(10), 0.01, [-1.0])
