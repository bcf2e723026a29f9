"""Scaling rules, design spectra and time scaling (SPEC §5, Eq 6.5), with hand-checked numbers."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.errors import MotionError, ProjectError
from rockdesign.motions.design_spectra import ASCE7Spectrum, EC8Spectrum
from rockdesign.motions.library import load_record
from rockdesign.motions.scaling import (mean_spectrum, parse_scale_rule, scale_factors, similitude_time_factor,
                                        time_scaled)
from rockdesign.motions.spectra import sd_max

G = 9.81
FILE = "project.toml"


@pytest.fixture(scope="module")
def two_records():
    return [load_record("p695-ff/11a", gravity=G), load_record("p695-ff/1b", gravity=G)]


def parse(raw):
    return parse_scale_rule(raw, file=FILE, gravity=G)


def test_factor(two_records):
    assert scale_factors(parse({"method": "factor", "value": 1.5}), two_records) == [1.5, 1.5]


def test_pga(two_records):
    # ff/11a: PGA 0.244803 g -> 0.35 g needs 0.35/0.244803 = 1.42972
    factors = scale_factors(parse({"method": "pga", "target": "0.35 g"}), two_records)
    assert factors[0] == pytest.approx(0.35 / 0.244803, rel=2e-6)
    for motion, factor in zip(two_records, factors):
        assert motion.scaled(factor).pga == pytest.approx(0.35 * G, rel=1e-12)


def test_sdmax(two_records):
    rule = parse({"method": "sdmax", "target": "30 cm", "damping": "2 %", "band": ["0.05 s", "10 s"]})
    assert (rule.value, rule.damping, rule.band) == (pytest.approx(0.3), pytest.approx(0.02), (0.05, 10.0))
    factors = scale_factors(rule, two_records)
    # ff/11a: SD_max(2 %) = 1.13461 m at 8.69 s (reference table, g = 9.80665; SD ∝ g)
    assert factors[0] == pytest.approx(0.3 / (1.13461 * G / 9.80665), rel=1e-4)
    for motion, factor in zip(two_records, factors):
        assert sd_max(motion.scaled(factor))[0] == pytest.approx(0.3, rel=1e-12)


def test_uplift(two_records):
    uplift = G * 0.15  # g tan α for tan α = 0.15
    factors = scale_factors(parse({"method": "uplift", "multiple": 2.5}), two_records, uplift_acceleration=uplift)
    for motion, factor in zip(two_records, factors):
        assert motion.scaled(factor).pga == pytest.approx(2.5 * 0.15 * G, rel=1e-12)
    with pytest.raises(MotionError):
        scale_factors(parse({"method": "uplift", "multiple": 2.5}), two_records)


def test_ec8_type1_values_by_hand():
    # a_g = 0.25 g, ground C: S = 1.15, T_B = 0.2, T_C = 0.6, T_D = 2.0, η = 1
    spectrum = EC8Spectrum(ag=0.25 * G, ground_type="C")
    ag_s = 0.25 * G * 1.15
    expected = [ag_s, ag_s * 1.75, 2.5 * ag_s, 2.5 * ag_s, 2.5 * ag_s * 0.6, 2.5 * ag_s * 0.6 * 2.0 / 9.0]
    np.testing.assert_allclose(spectrum.psa([0.0, 0.1, 0.2, 0.4, 1.0, 3.0]), expected, rtol=1e-12)
    # 2 % damping: η = √(10/7)
    assert EC8Spectrum(ag=1.0, ground_type="A", damping=0.02).eta == pytest.approx(math.sqrt(10 / 7))
    assert EC8Spectrum(ag=1.0, ground_type="A", damping=0.5).eta == 0.55
    assert EC8Spectrum(ag=1.0, ground_type="D", spectrum_type=2).parameters == (1.8, 0.10, 0.30, 1.2)


def test_asce7_values_by_hand():
    # S_DS = 1.0 g, S_D1 = 0.6 g, T_L = 8 s: T_0 = 0.12 s, T_S = 0.6 s
    spectrum = ASCE7Spectrum(SDS=G, SD1=0.6 * G, TL=8.0)
    assert (spectrum.T0, spectrum.TS) == pytest.approx((0.12, 0.6))
    np.testing.assert_allclose(spectrum.psa([0.0, 0.06, 0.3, 1.2, 10.0]) / G, [0.4, 0.7, 1.0, 0.5, 0.048], rtol=1e-12)


def test_spectrum_not_below(two_records):
    rule = parse({"method": "spectrum", "code": "ec8", "ag": "0.25 g", "ground_type": "C",
                  "band": ["0.2 s", "2 s"]})
    assert rule.fraction == 0.9 and rule.fit == "not-below" and rule.damping == 0.05
    factors = scale_factors(rule, two_records)
    assert factors[0] == factors[1]
    periods = np.geomspace(0.2, 2.0, rule.n_periods)
    mean = mean_spectrum([m.scaled(factors[0]) for m in two_records], periods, 0.05)
    ratio = mean / rule.spectrum.psa(periods)
    # the scaled mean touches 90 % of the target at one period and stays above it elsewhere
    assert ratio.min() == pytest.approx(0.9, rel=1e-10)


def test_spectrum_mean_fit_asce(two_records):
    rule = parse({"method": "spectrum", "code": "asce7", "SDS": "1.0 g", "SD1": "0.6 g", "TL": "8 s",
                  "fit": "mean", "band": ["0.5 s", "3 s"]})
    factor = scale_factors(rule, two_records)[0]
    periods = np.geomspace(0.5, 3.0, rule.n_periods)
    mean = mean_spectrum([m.scaled(factor) for m in two_records], periods, 0.05)
    assert np.exp(np.mean(np.log(mean / rule.spectrum.psa(periods)))) == pytest.approx(1.0, rel=1e-10)


@pytest.mark.parametrize("raw,key,fragment", [
    ({"method": "pgaa", "target": "0.3 g"}, "excitation.scale.method", "did you mean 'pga'"),
    ({"method": "pga", "targt": "0.3 g"}, "excitation.scale.targt", "did you mean 'target'"),
    ({"method": "pga", "target": "0.3 m"}, "excitation.scale.target", "acceleration"),
    ({"method": "pga"}, "excitation.scale.target", "needs 'target'"),
    ({"method": "sdmax", "target": "0.3 g"}, "excitation.scale.target", "length"),
    ({"method": "sdmax", "target": "0.3 m", "damping": 2}, "excitation.scale.damping", "[0, 1)"),
    ({"method": "sdmax", "target": "0.3 m", "band": ["10 s", "1 s"]}, "excitation.scale.band", "Tmin < Tmax"),
    ({"method": "factor", "value": "two"}, "excitation.scale.value", "a number"),
    ({"method": "spectrum", "code": "ec9", "ag": "0.2 g"}, "excitation.scale.code", "ec8"),
    ({"method": "spectrum", "code": "ec8", "ag": "0.2 g", "ground_type": "F"}, "excitation.scale.ground_type", "A, B"),
    ({"method": "spectrum", "code": "asce7", "SDS": "1 g", "SD1": "0.6 g", "damping": 0.02},
     "excitation.scale.damping", "5 %"),
    ({"method": "spectrum", "code": "asce7", "SDS": "1 g", "SD1": "0.6 g", "ag": "0.3 g"},
     "excitation.scale.ag", "ASCE"),
])
def test_parse_errors_name_file_key_expected_found(raw, key, fragment):
    with pytest.raises(ProjectError) as info:
        parse(raw)
    err = info.value
    assert err.file == FILE and err.key == key
    assert fragment in str(err)
    assert err.expected is not None and err.found is not None


def test_descriptions_state_damping_and_band():
    text = parse({"method": "sdmax", "target": "0.3 m"}).describe(G)
    assert "2 % damping" in text and "0.05–10 s" in text
    assert "0.35 g" in parse({"method": "pga", "target": "0.35 g"}).describe(G)
    assert "EN 1998-1" in parse({"method": "spectrum", "code": "ec8", "ag": "0.2 g", "ground_type": "B"}).describe(G)


def test_similitude_time_scaling():
    # model R_m = 0.25 m, prototype R_p = 2.5 m: Δt_m = Δt_p √0.1 (Eq 6.5)
    f = similitude_time_factor(0.25, 2.5)
    assert f == pytest.approx(math.sqrt(0.1))
    motion = load_record("p695-ff/11a")
    fast = time_scaled(motion, f)
    assert fast.dt == pytest.approx(0.02 * f) and fast.pga == motion.pga
    assert fast.duration == pytest.approx(motion.duration * f)
    assert fast.meta["time_scale"] == pytest.approx(f)
    # SD_max of the time-scaled record is f² times the original, at f times the period
    sd, period = sd_max(motion, band=(0.05, 10.0))
    sd_fast, period_fast = sd_max(fast, band=(0.05 * f, 10.0 * f))
    assert sd_fast == pytest.approx(f * f * sd, rel=1e-6)
    assert period_fast == pytest.approx(f * period, rel=1e-3)
