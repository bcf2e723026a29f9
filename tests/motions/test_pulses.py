"""Analytic pulses of rockdesign.motions.motion (SPEC §4): peak amplitudes, the Ricker peak
frequency (validation case eqA.1_peak_freq), Makris' cycloidal pulses, sampling/engine agreement."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.motions.excitation import RICKER_ANTI_BETA
from rockdesign.motions.measures import velocity_displacement
from rockdesign.motions.motion import cycloidal_c_phase, no_motion, pulse_motion


def _fine(motion, n=200001):
    t = np.linspace(0.0, motion.duration, n)
    return t, motion.acceleration(t)


@pytest.mark.parametrize("pulse", ["ricker-sym", "ricker-anti", "sine", "cycloidal-a", "cycloidal-b", "cycloidal-c"])
def test_peak_is_a_p(pulse):
    motion = pulse_motion(pulse, 3.7, 0.95)
    _, accel = _fine(motion)
    tol = 1e-6 if pulse == "ricker-anti" else 1e-8
    assert np.max(np.abs(accel)) == pytest.approx(3.7, rel=tol)
    assert motion.pga == 3.7


def test_antisymmetric_beta():
    # β_R = max |(x²−3)x e^(−x²/2)| at x² = 3 − √6 (validation case eqA.2_beta: 1.380119)
    x = math.sqrt(3 - math.sqrt(6))
    assert abs((x * x - 3) * x * math.exp(-x * x / 2)) == pytest.approx(RICKER_ANTI_BETA, abs=1e-6)


def test_symmetric_ricker_shape_and_centre():
    motion = pulse_motion("ricker-sym", 1.0, 0.8)
    assert motion.params[2] == pytest.approx(1.2)  # t_m = 1.5 T_p
    assert motion.acceleration(1.2)[0] == pytest.approx(-1.0)
    # zero crossings at τ = ±T_p/(π√2)
    assert motion.acceleration(1.2 + 0.8 / (math.pi * math.sqrt(2)))[0] == pytest.approx(0.0, abs=1e-12)


def test_ricker_peak_fourier_frequency():
    """Validation case eqA.1_peak_freq: the Fourier amplitude of Eq A.1 peaks at 1/T_p = 1.25 Hz (T_p = 0.8 s)."""
    motion = pulse_motion("ricker-sym", 1.0, 0.8)
    t = np.linspace(0.0, 2 * motion.params[2], 4001)
    accel = motion.acceleration(t)
    dt = t[1] - t[0]
    freqs = np.linspace(0.2, 4.0, 1901)
    spectrum = np.abs(np.exp(-2j * np.pi * np.outer(freqs, t)) @ accel) * dt
    assert freqs[np.argmax(spectrum)] == pytest.approx(1.25, rel=0.03)
    assert freqs[np.argmax(spectrum)] == pytest.approx(1.25, abs=2e-3)


def test_cycloidal_c1_returns_to_rest():
    """Makris' C1 pulse: zero final ground velocity and displacement (phase from 2cos φ = sin φ (3π − 2φ))."""
    phi = cycloidal_c_phase(1)
    assert 2 * math.cos(phi) == pytest.approx(math.sin(phi) * (3 * math.pi - 2 * phi), abs=1e-10)
    a_p, T_p = 2.0, 0.7
    motion = pulse_motion("cycloidal-c", a_p, T_p)
    assert motion.duration == pytest.approx((1.5 - phi / math.pi) * T_p)
    t, accel = _fine(motion)
    v, d = velocity_displacement(np.ascontiguousarray(accel), t[1] - t[0])
    v_scale, d_scale = a_p * T_p / (2 * math.pi), a_p * T_p ** 2 / (4 * math.pi ** 2)
    assert abs(v[-1]) < 1e-8 * v_scale
    assert abs(d[-1]) < 1e-7 * d_scale
    assert np.max(np.abs(d)) > 0.1 * d_scale


def test_cycloidal_a_and_b_residuals():
    # type A: a = a_p sin(ωτ) on one period: v_end = 0, d_end = a_p T_p²/(2π) · ... ≠ 0 (a drift)
    a_p, T_p = 1.0, 1.0
    t, accel = _fine(pulse_motion("cycloidal-a", a_p, T_p))
    v, d = velocity_displacement(np.ascontiguousarray(accel), t[1] - t[0])
    assert v[-1] == pytest.approx(0.0, abs=1e-9)
    assert d[-1] == pytest.approx(a_p * T_p ** 2 / (2 * math.pi), rel=1e-8)
    t, accel = _fine(pulse_motion("cycloidal-b", a_p, T_p))
    v, d = velocity_displacement(np.ascontiguousarray(accel), t[1] - t[0])
    assert v[-1] == pytest.approx(0.0, abs=1e-9) and d[-1] == pytest.approx(0.0, abs=1e-9)


def test_sine_pulse_eq_2_20_and_zero_outside():
    motion = pulse_motion("sine", 2.0, 0.5, t_0=0.1)
    assert motion.acceleration(0.1 + 0.125)[0] == pytest.approx(-2.0)
    assert motion.acceleration([0.05, 0.7]).tolist() == [0.0, 0.0]
    assert no_motion().acceleration([0.0, 1.0]).tolist() == [0.0, 0.0] and no_motion().pga == 0.0


def test_scaled_pulse():
    motion = pulse_motion("ricker-anti", 1.0, 1.0).scaled(2.5)
    assert motion.pga == 2.5


def test_cycloidal_c1_phase_constant_matches_its_equation():
    # φ of Makris' type-C1 pulse: root of 2 cos φ = sin φ (3π − 2φ) (zero final displacement)
    from rockdesign.motions.excitation import CYCLOIDAL_C1_PHASE
    from rockdesign.motions.motion import cycloidal_c_phase
    assert abs(cycloidal_c_phase(1) - CYCLOIDAL_C1_PHASE) < 1e-4
