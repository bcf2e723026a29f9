"""Spectrum axes (CONTRACT §2): parsing ``AXIS:lo:hi:n`` and the normalisations behind them."""
from __future__ import annotations

import math

import numpy as np
import pytest

from support import reference_podium, table34_column
from rockdesign.errors import RockdesignError
from rockdesign.planar.spectra.axes import (Axis, parse_axis, pulse_amplitudes, pulse_periods, spectrum_scales,
                                     x_from_periods)


def test_parse_inclusive_linear_grids():
    ax = parse_axis("omega_p/p:0.5:12:801", "x")
    assert ax == Axis("omega_p/p", 0.5, 12.0, 801)
    assert ax.values[0] == 0.5 and ax.values[-1] == 12.0 and ax.values.size == 801
    assert parse_axis(" ap/up : 0 : 12 : 401 ", "y").values[200] == pytest.approx(6.0)
    assert parse_axis("Tp:0.95", "x").values.tolist() == [0.95]
    assert parse_axis(ax.text, "x") == ax


@pytest.mark.parametrize("text,which", [
    ("omega_p/q:0.5:12:801", "x"), ("ap/up:0:12:401", "x"), ("omega_p/p:0.5:12", "x"), ("omega_p/p:a:12:5", "x"),
    ("omega_p/p:0.5:12:0", "x"), ("omega_p/p:12:0.5:5", "x"), ("omega_p/p:0:12:5", "x"), ("Tp:-1:2:5", "x"),
    ("ap/up:-1:12:5", "y"), ("ap/up:1:2:1", "y"), ("ap/up:1:1:3", "y"), ("ap/up:0:12:4.5", "y"),
    ("ap/g:0:inf:5", "y"), ("", "y"), ("ap/up:0:12:10000000", "y")])
def test_bad_axes_are_user_errors(text, which):
    with pytest.raises(RockdesignError) as err:
        parse_axis(text, which)
    assert err.value.key == which                      # the library's parameter (the CLI says --x, --y)


def test_axis_normalisations_of_a_block():
    s = table34_column("B1")
    sc = spectrum_scales(s)
    R = math.hypot(1.5, 0.15)
    assert sc.p == pytest.approx(math.sqrt(9.81 / (R * 4 / 3)), rel=1e-14)    # Eq 3.13
    assert sc.p_hat == pytest.approx(sc.p)
    assert sc.uplift_acceleration == pytest.approx(9.81 * 0.1)                # g tan α (Eq 3.34)
    x = Axis("omega_p/p", 1.0, 3.0, 3)
    T = pulse_periods(x, sc)
    np.testing.assert_allclose(T, 2 * math.pi / (np.array([1.0, 2.0, 3.0]) * sc.p))
    np.testing.assert_allclose(x_from_periods("omega_p/p", T, sc), x.values)
    np.testing.assert_allclose(pulse_amplitudes(Axis("ap/g", 0.0, 0.5, 3), sc), [0.0, 0.25 * 9.81, 0.5 * 9.81])


def test_flat_extensions_keep_the_column_axis():
    # thesis Fig 3.21 compares B1–B5 on one a_p/(g tan α) axis: α of the flat contact width, not α'
    sc = spectrum_scales(table34_column("B5ef"))
    assert sc.uplift_acceleration == pytest.approx(9.81 * 0.1)
    assert sc.uplift_acceleration_model == pytest.approx(9.81 * 0.2)          # the true uplift (α')
    assert sc.theta_c == pytest.approx(math.atan(0.2))


def test_podium_p_hat_axis():
    s = reference_podium(6.0)
    sc = spectrum_scales(s)
    assert sc.p_hat != pytest.approx(sc.p)                                   # Eq 4.32
    T1 = pulse_periods(Axis("omega_p/p_hat", 2.0, 2.0, 1), sc)
    assert T1[0] == pytest.approx(2 * math.pi / (2.0 * sc.p_hat))
