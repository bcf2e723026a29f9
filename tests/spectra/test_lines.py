"""Reading spectra: overturning map by impacts, limit-state lines (Table 3.5), minimum overturning line,
relative spectra (Eq 3.64), the equivalent size (Eq 3.65) and Polyakov's line (Sec 4.2.4, SPEC §5)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from casedata import case, expected

from support import table34_column
from rockdesign.motions.motion import pulse_motion
from rockdesign.motions.spectra import sd_max
from rockdesign.planar.spectra import SpectrumRequest, compute_spectrum, parse_axis
from rockdesign.planar.spectra.lines import (capped_ratio, contour_paths, crossing_abscissa, display_cap, equivalent_size,
                                      first_crossing_line, limit_state_lines, minimum_overturning_line,
                                      overturning_classes, overturning_line, relative_spectrum)
from rockdesign.planar.spectra.output import analyse
from rockdesign.planar.spectra.polyakov import polyakov_amplitudes, unit_pulse_sd_max


def test_overturning_classes_split_by_impacts():
    ot = np.array([[False, True, True, True]])
    n = np.array([[-1, 0, 1, 5]])
    np.testing.assert_array_equal(overturning_classes(ot, n), [[-1, 0, 1, 2]])


def test_first_crossing_is_interpolated_and_takes_the_lowest_branch():
    y = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    f = np.array([[0.0, 0.0, 0.3],
                  [0.1, 0.2, 0.4],
                  [0.3, 0.1, 0.5],     # column 1 dips after rising: the first crossing counts
                  [0.2, 0.6, 0.6],
                  [0.9, 0.7, 0.7]])
    line = first_crossing_line(y, f, 0.25)
    assert line[0] == pytest.approx(1.0 + (0.25 - 0.1) / (0.3 - 0.1))
    assert line[1] == pytest.approx(2.0 + (0.25 - 0.1) / (0.6 - 0.1))
    assert line[2] == 0.0                                 # already reached on the first row
    assert math.isnan(first_crossing_line(y, f, 5.0)[0])  # never reached


def test_overturning_and_minimum_lines():
    y = np.array([0.0, 1.0, 2.0, 3.0])
    ot = np.array([[False, False, True],
                   [False, False, True],
                   [True, False, True],
                   [True, False, True]])
    np.testing.assert_array_equal(minimum_overturning_line(y, ot), [2.0, np.nan, 0.0])
    np.testing.assert_array_equal(overturning_line(y, ot), [1.5, np.nan, 0.0])


def test_limit_states_with_capped_overturned_points():
    y = np.array([0.0, 1.0, 2.0])
    psi = np.array([[0.0], [0.2], [50.0]])   # the last row overturned dynamically: θ_max = π/2
    ot = np.array([[False], [False], [True]])
    ls = limit_state_lines(y, psi, ot, cap=1.5)
    assert ls["I"][0] == pytest.approx(1.0 + 0.05 / 1.3)
    assert ls["III"][0] == pytest.approx(1.0 + 0.8 / 1.3)
    assert ls["IV"][0] == 1.5
    assert display_cap(1.0) == 1.5 and display_cap(1.0, 2.3) == 2.3


def test_relative_spectrum_caps_overturning():
    a = np.array([[0.4, 0.9, 3.0]])
    b = np.array([[0.5, 40.0, 0.6]])
    ot_a = np.array([[False, False, True]])
    ot_b = np.array([[False, True, False]])
    np.testing.assert_allclose(relative_spectrum(a, ot_a, b, ot_b, 1.5), [[-0.1, -0.6, 0.9]])
    np.testing.assert_array_equal(capped_ratio(b, ot_b, 1.5), [[0.5, 1.5, 0.6]])


def test_crossing_and_equivalent_size_of_scaled_lines():
    # a project whose overturning line is the reference's stretched by 1.5 in y ↔ shrunk in x:
    # line_p(x) = line_r(1.5 x) with line_r(x) = x² → at any y0, x_r/x_p = 1.5 → R̂/R = 2.25
    x = np.linspace(0.5, 12, 2301)
    line_r = x ** 2
    line_p = (1.5 * x) ** 2
    eq = equivalent_size(x, line_p, line_r, [4.0, 9.0, 25.0], 2.0)
    np.testing.assert_allclose(eq["R_hat_over_R"], 2.25, rtol=2e-3)
    np.testing.assert_allclose(eq["R_hat"], 4.5, rtol=2e-3)
    assert crossing_abscissa(x, line_r, 0.1) is None        # no overturning that low
    assert crossing_abscissa(x, line_r, 1000.0) is None     # crossing beyond the grid


def test_contours_of_a_plane():
    x = np.linspace(0, 1, 11)
    y = np.linspace(0, 2, 21)
    paths = contour_paths(x, y, np.add.outer(y, 0 * x), 0.55)
    assert len(paths) == 1
    np.testing.assert_allclose(paths[0][:, 1], 0.55)


def test_unit_pulse_sd_max_scales_with_the_square_of_the_period():
    # SD of a pulse family is a_p T_p² f(T/T_p): inside the band SD_max/T_p² is a shape constant
    T = np.array([0.4, 0.8, 1.6])
    sd = unit_pulse_sd_max("ricker-anti", T, damping=0.02, band=(0.01, 50.0))
    np.testing.assert_allclose(sd / T ** 2, sd[0] / T[0] ** 2, rtol=2e-3)


def test_polyakov_amplitude_reaches_the_capacity():
    T = np.array([0.5, 1.0, 2.0, 3.5])
    a_p, sd_unit = polyakov_amplitudes("ricker-sym", T, 0.3, damping=0.02, band=(0.05, 10.0))
    for a, Tp in zip(a_p, T):
        assert sd_max(pulse_motion("ricker-sym", a, Tp), 0.02, (0.05, 10.0))[0] == pytest.approx(0.3, rel=1e-9)
    # the interpolated line (max_points) agrees with exact evaluations
    Tf = np.linspace(0.4, 4.0, 60)
    exact, _ = polyakov_amplitudes("sine", Tf, 0.3)
    interp, _ = polyakov_amplitudes("sine", Tf, 0.3, max_points=25)
    np.testing.assert_allclose(interp, exact, rtol=2e-3)


def test_equivalent_size_of_b2_from_two_spectra():
    # Sec 3.3.2 / Eq 3.65: at a_p/(g tan α) = 5 the overturning lines of B1 and B2ec (antisymmetric
    # Ricker) read x1, x2 → R̂ = (x1/x2)² R (tests/validation/data/cases.json eq3.65)
    req = SpectrumRequest("ricker-anti", parse_axis("omega_p/p:2.5:5.5:121", "x"), parse_axis("ap/up:4.8:5.2:3", "y"))
    b1 = compute_spectrum(table34_column("B1"), req)
    b2 = compute_spectrum(table34_column("B2ec"), req)
    prod = analyse(b2, b1, polyakov=False, ordinates=[5.0])
    eq = prod.equivalent
    read = case("eq3.65")["inputs"]     # the abscissae read from the thesis figure
    assert eq["x_reference"][0] == pytest.approx(read["x1"], abs=0.04)
    assert eq["x_project"][0] == pytest.approx(read["x2"], abs=0.04)
    assert eq["R_hat_over_R"][0] == pytest.approx(expected("eq3.65"), abs=0.06)
    # B2ec is the more stable column: no point overturns it that leaves B1 standing
    assert not np.any(b2.overturned & ~b1.overturned)
    assert prod.delta.min() < -0.4 and np.mean(prod.delta > 0.05) < 0.05
