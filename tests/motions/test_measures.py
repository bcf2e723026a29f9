"""Intensity measures (thesis Table 5.6, Eqs 5.44–5.46) on signals with hand-computed values,
exact for piecewise-linear acceleration."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.motions.library import load_record
from rockdesign.motions.measures import (arias_intensity, bracketed_duration, cumulative_absolute_velocity,
                                         intensity_measures, motion_measures, peak_displacement_ground,
                                         peak_velocity, predominant_frequency, rms_acceleration,
                                         significant_duration, velocity_displacement)

A, DT, G = 2.0, 0.1, 9.81


def test_triangle_pulse_by_hand():
    # a = [0, A, 0]: v_end = A dt, d_end = A dt², ∫a² = 2A²dt/3, ∫|a| = A dt
    accel = np.array([0.0, A, 0.0])
    v, d = velocity_displacement(accel, DT)
    assert v[-1] == pytest.approx(A * DT)
    assert d[1] == pytest.approx(A * DT ** 2 / 6)
    assert d[-1] == pytest.approx(A * DT ** 2)
    assert peak_velocity(accel, DT) == pytest.approx(A * DT)
    assert peak_displacement_ground(accel, DT) == pytest.approx(A * DT ** 2)
    assert arias_intensity(accel, DT, G) == pytest.approx(math.pi / (2 * G) * 2 * A ** 2 * DT / 3)
    assert cumulative_absolute_velocity(accel, DT) == pytest.approx(A * DT)
    # |a| >= A/2 between dt/2 and 3dt/2; ∫ a² there = 7 A² dt / 12
    t_d, t1, t2 = bracketed_duration(accel, DT, A / 2)
    assert (t_d, t1, t2) == pytest.approx((DT, DT / 2, 1.5 * DT))
    assert rms_acceleration(accel, DT, t1, t2) == pytest.approx(math.sqrt(7 / 12) * A)


def test_extrema_inside_steps():
    # a = [0, A, -A, 0]: v peaks at 3A dt/4 in the middle of the second step (samples only see A dt/2)
    accel = np.array([0.0, A, -A, 0.0])
    assert peak_velocity(accel, DT) == pytest.approx(0.75 * A * DT)
    # ∫|a| over a sign change: two triangles of area A dt/4
    assert cumulative_absolute_velocity(np.array([A, -A]), DT) == pytest.approx(A * DT / 2)
    # a = [A, -A]: d(τ) = Aτ²/2 − Aτ³/(3dt); v = 0 at τ = dt: max d at the end = A dt²/6
    assert peak_displacement_ground(np.array([A, -A]), DT) == pytest.approx(A * DT ** 2 / 6)
    # v0 > 0 then decelerating: v = 0 inside the step gives the displacement peak
    accel = np.array([A, A, -A, -3 * A])
    v, d = velocity_displacement(accel, DT)
    fine_t = np.linspace(0, 3 * DT, 30001)
    fine_a = np.interp(fine_t, np.arange(4) * DT, accel)
    fine_v, fine_d = velocity_displacement(fine_a, fine_t[1])
    assert peak_displacement_ground(accel, DT) == pytest.approx(np.max(np.abs(fine_d)), rel=1e-7)
    assert peak_displacement_ground(accel, DT) > np.max(np.abs(d))


def test_constant_motion_significant_duration():
    # ∫a² grows linearly: D5–95 = 0.9 T exactly
    accel = np.full(1001, 0.3)
    duration, t5, t95 = significant_duration(accel, 0.01)
    assert (duration, t5, t95) == pytest.approx((9.0, 0.5, 9.5), rel=1e-12)


def test_sine_measures():
    # analytic values of the continuous sine; the piecewise-linear samples differ by O((ω dt)²)
    f, T = 2.0, 20.0
    t = np.arange(0, T + 1e-9, 0.001)
    accel = A * np.sin(2 * math.pi * f * t)
    assert arias_intensity(accel, 0.001, G) == pytest.approx(math.pi / (2 * G) * A ** 2 * T / 2, rel=1e-4)
    assert cumulative_absolute_velocity(accel, 0.001) == pytest.approx(2 * A * T / math.pi, rel=1e-4)
    assert peak_velocity(accel, 0.001) == pytest.approx(2 * A / (2 * math.pi * f), rel=1e-4)
    assert predominant_frequency(accel, 0.001) == pytest.approx(f, rel=0.015)
    m = intensity_measures(accel, 0.001, G)
    assert m["a_rms"] == pytest.approx(A / math.sqrt(2), rel=1e-3)
    # first/last exceedance of 0.05 g at sin(2πft) = 0.05 g/A, symmetric about the record
    edge = math.asin(0.05 * G / A) / (2 * math.pi * f)
    assert m["bracketed_duration"] == pytest.approx(T - 2 * edge, abs=1e-5)


def test_record_peaks_against_fine_resampling():
    motion = load_record("p695-ff/11a")
    _, accel = motion.sampled()
    k = 40
    n = accel.size
    fine_t = np.arange((n - 1) * k + 1) * motion.dt / k
    fine_a = np.interp(fine_t, np.arange(n) * motion.dt, accel)
    fine_v, fine_d = velocity_displacement(fine_a, motion.dt / k)
    m = motion_measures(motion)
    assert m["pgv"] == pytest.approx(np.max(np.abs(fine_v)), rel=1e-6)
    assert m["pgd"] == pytest.approx(np.max(np.abs(fine_d)), rel=1e-6)
    assert m["pga"] == pytest.approx(motion.pga)
    assert set(m) == {"pga", "pgv", "pgd", "arias", "cav", "bracketed_duration", "significant_duration",
                      "a_rms", "predominant_frequency"}


def test_quiet_record():
    accel = np.full(100, 0.01)
    m = intensity_measures(accel, 0.01, G)
    assert m["bracketed_duration"] == 0.0 and m["a_rms"] == 0.0
