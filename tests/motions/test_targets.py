"""MCE_R target spectra (rockdesign.motions.targets) and the ``asce7-22`` scale rule's parsing (CONTRACT §7.1).

Values by hand from the two-period shape (ASCE 7-22 §11.4.5.2 at the MCE_R level, SPEC §16) with
S_MS = 0.60 g, S_M1 = 0.30 g, T_L = 8 s: T0 = 0.2·0.30/0.60 = 0.1 s, TS = 0.5 s; Sa(0) = 0.4·0.60 = 0.24 g,
Sa(0.05 s) = 0.60·(0.4 + 0.6·0.5) = 0.42 g, Sa(1 s) = 0.30 g, Sa(2 s) = 0.15 g, Sa(10 s) = 0.30·8/100 = 0.024 g.
"""
from __future__ import annotations

import numpy as np
import pytest

from rockdesign.errors import MotionError, ProjectError
from rockdesign.motions.scaling import parse_scale_rule, scale_factors
from rockdesign.motions.targets import MCERSpectrum, TabulatedSpectrum, read_target_spectrum

G = 9.81


def test_two_period_mcer_by_hand():
    s = MCERSpectrum(0.60 * G, 0.30 * G, 8.0)
    assert (s.T0, s.TS) == (pytest.approx(0.1), pytest.approx(0.5))
    T = [0.0, 0.05, 0.1, 0.3, 0.5, 1.0, 2.0, 8.0, 10.0]
    expected = [0.24, 0.42, 0.60, 0.60, 0.60, 0.30, 0.15, 0.0375, 0.024]
    np.testing.assert_allclose(s.psa(T) / G, expected, rtol=1e-12)
    # continuous at the corners
    for corner in s.corner_periods:
        below, above = s.psa([corner * (1 - 1e-9), corner * (1 + 1e-9)])
        assert below == pytest.approx(above, rel=1e-8)
    assert "T_L = 8 s" in s.describe(G) and "0.6 g" in s.describe(G)


def write(tmp_path, text, name="mce_r.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_table_read_and_log_log_interpolation(tmp_path):
    # rows on the SM1/T branch of the spectrum above: log-log interpolation reproduces 1/T exactly between them
    path = write(tmp_path, "# site-specific MCE_R, 5 % damping\nperiod [s], Sa [g]\n0, 0.24\n0.1, 0.60\n"
                           "0.5, 0.60   # TS\n1.0, 0.30\n4.0, 0.075\n")
    table = read_target_spectrum(path, gravity=G)
    assert table.periods.tolist() == [0.0, 0.1, 0.5, 1.0, 4.0]          # the PGA row is kept
    np.testing.assert_allclose(table.psa([0.7, 2.0, 3.3]) / G, [0.3 / 0.7, 0.15, 0.3 / 3.3], rtol=1e-12)
    np.testing.assert_allclose(table.psa([0.2, 0.4]) / G, [0.6, 0.6], rtol=1e-12)
    assert table.covers(0.1, 4.0) and not table.covers(0.05, 4.0) and not table.covers(0.1, 5.0)
    with pytest.raises(ValueError, match="no extrapolation"):
        table.psa([5.0])
    assert "mce_r.csv" in table.describe(G)


def test_table_units_and_separators(tmp_path):
    path = write(tmp_path, "T (ms);\tSa (cm/s^2)\n100; 588.6\n1000\t294.3\n2000 147.15\n")
    table = read_target_spectrum(path, gravity=G)
    np.testing.assert_allclose(table.periods, [0.1, 1.0, 2.0], rtol=1e-12)
    np.testing.assert_allclose(table.values, [5.886, 2.943, 1.4715], rtol=1e-12)


@pytest.mark.parametrize("text,line,fragment", [
    ("period, Sa\n0.1, 0.6\n1.0, 0.3\n", 1, "header must name both columns with units"),
    ("Sa [g], period [s]\n0.6, 0.1\n0.3, 1.0\n", 1, "first column must be the period"),
    ("period [s], Sa [m]\n0.1, 0.6\n1.0, 0.3\n", 1, "second column must be the spectral acceleration"),
    ("period [s], Sa [g]\n0.1, 0.6\n0.1, 0.5\n", 3, "periods must increase"),
    ("period [s], Sa [g]\n0.1, 0.6\n1.0, -0.3\n", 3, "must be positive"),
    ("period [s], Sa [g]\n0.1, 0.6, 7\n1.0, 0.3\n", 2, "a row needs two numbers"),
    ("period [s], Sa [g]\n0.1, x\n", 2, "a row needs two numbers"),
    ("period [s], Sa [g]\n0, 0.24\n0.1, 0.6\n", 3, "too few rows"),
])
def test_table_errors_name_file_line_and_key(tmp_path, text, line, fragment):
    path = write(tmp_path, text)
    with pytest.raises(ProjectError) as info:
        read_target_spectrum(path, gravity=G)
    err = info.value
    assert err.file == str(path) and err.line == line and err.key == "excitation.scale.target"
    assert fragment in str(err)


def parse(raw, file="project.toml"):
    return parse_scale_rule(raw, file=file, gravity=G)


def test_rule_from_sms_sm1_tl():
    rule = parse({"method": "asce7-22", "SMS": "0.60 g", "SM1": "0.30 g", "TL": "8 s"})
    assert rule.method == "asce7-22" and rule.damping == 0.05 and rule.periods is None
    assert isinstance(rule.spectrum, MCERSpectrum) and not rule.spectrum.TL_default
    assert (rule.spectrum.SMS, rule.spectrum.SM1, rule.spectrum.TL) == (pytest.approx(0.6 * G),
                                                                        pytest.approx(0.3 * G), 8.0)
    assert "ASCE 7-22 §16.2.3" in rule.describe(G) and "structure's §16.2.1 range" in rule.describe(G)
    # TL left out: 8 s, and the description says it was a default
    rule = parse({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "periods": ["0.08 s", "3.0 s"]})
    assert rule.spectrum.TL_default and "default" in rule.describe(G)
    assert rule.periods == (pytest.approx(0.08), pytest.approx(3.0)) and "0.08–3 s (given)" in rule.describe(G)


def test_rule_from_target_file_relative_to_the_project(tmp_path):
    (tmp_path / "site").mkdir()
    write(tmp_path / "site", "period [s], Sa [g]\n0.01, 0.3\n0.5, 0.75\n5.0, 0.06\n")
    rule = parse({"method": "asce7-22", "target": "site/mce_r.csv"}, file=str(tmp_path / "project.toml"))
    assert isinstance(rule.spectrum, TabulatedSpectrum)
    assert rule.spectrum.psa([0.5])[0] == pytest.approx(0.75 * G)


@pytest.mark.parametrize("raw,key,fragment", [
    ({"method": "asce7-22"}, "excitation.scale.SMS", "needs the MCE_R target"),
    ({"method": "asce7-22", "SMS": "0.6 g"}, "excitation.scale.SM1", "needs the MCE_R target"),
    ({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "target": "x.csv"}, "excitation.scale.SMS",
     "one way"),
    ({"method": "asce7-22", "target": "nowhere.csv"}, "excitation.scale.target", "not found"),
    ({"method": "asce7-22", "target": 3}, "excitation.scale.target", "invalid target"),
    ({"method": "asce7-22", "SMS": "0.6 m", "SM1": "0.3 g"}, "excitation.scale.SMS", "acceleration"),
    ({"method": "asce7-22", "SMS": "-0.6 g", "SM1": "0.3 g"}, "excitation.scale.SMS", "SMS > 0"),
    ({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "TL": "0.4 s"}, "excitation.scale.TL", "T_S"),
    ({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "periods": ["3 s"]}, "excitation.scale.periods",
     "two periods"),
    ({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "periods": ["3 s", "0.1 s"]},
     "excitation.scale.periods", "lower bound < upper bound"),
    ({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "periods": ["0.1 g", "1 s"]},
     "excitation.scale.periods", "time"),
    ({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "band": ["0.1 s", "1 s"]}, "excitation.scale.band",
     "periods = ["),
    ({"method": "asce7-22", "SDS": "0.4 g", "SD1": "0.2 g"}, "excitation.scale.SDS", "SMS = 1.5 SDS"),
    ({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "damping": "5 %"}, "excitation.scale.damping",
     "5 %-damped"),
])
def test_rule_errors(raw, key, fragment):
    with pytest.raises(ProjectError) as info:
        parse(raw)
    assert info.value.file == "project.toml" and info.value.key == key, str(info.value)
    assert fragment in str(info.value)


def test_records_alone_cannot_be_scaled_per_asce7_22():
    from rockdesign.motions.library import load_record
    rule = parse({"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g"})
    with pytest.raises(MotionError, match="ground motions"):
        scale_factors(rule, [load_record("p695-ff/1a")])
