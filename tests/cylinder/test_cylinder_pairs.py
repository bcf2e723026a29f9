"""Bidirectional motion strings and record pairs for the cylinder (rockdesign.cylinder.pairs)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.errors import MotionError, RecordError
from rockdesign.motions.library import load_record
from rockdesign.cylinder.pairs import PAIR_SUITES, parse_pair, suite_pairs

G = 9.81


def test_builtin_pair_is_components_a_and_b():
    spec = parse_pair("record:p695-ff/11", gravity=G)
    a = load_record("p695-ff/11a", gravity=G)
    b = load_record("p695-ff/11b", gravity=G)
    pair = spec.pair
    assert not pair.planar and pair.dt == a.dt
    n = min(a.samples.size, b.samples.size)
    np.testing.assert_array_equal(pair.x[:a.samples.size], a.samples)
    np.testing.assert_array_equal(pair.y[:b.samples.size], b.samples)
    assert pair.x.size == pair.y.size == max(a.samples.size, b.samples.size) >= n
    t, ax, ay = pair.sampled()
    np.testing.assert_allclose(ax[:5], a.samples[:5])


def test_resultant_pga_scaling_and_rotation():
    pair = parse_pair("record:p695-ff/11,resultant_pga=0.3g", gravity=G).pair
    t, ax, ay = pair.sampled()
    assert np.max(np.hypot(ax, ay)) == pytest.approx(0.3 * G, rel=1e-12)
    assert parse_pair("record:p695-ff/11,resultant_pga=1.5up", gravity=G, uplift_acceleration=0.2 * G
                      ).pair.resultant_pga == pytest.approx(0.3 * G, rel=1e-12)
    rot = parse_pair("record:p695-ff/11,resultant_pga=0.3g,azimuth=30deg", gravity=G).pair
    t2, bx, by = rot.sampled()
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    np.testing.assert_allclose(bx, c * ax - s * ay, atol=1e-12)
    np.testing.assert_allclose(by, s * ax + c * ay, atol=1e-12)
    # the resultant is invariant under rotation
    assert rot.resultant_pga == pytest.approx(pair.resultant_pga, rel=1e-12)
    scaled = parse_pair("record:p695-ff/11,scale=2", gravity=G).pair
    assert scaled.resultant_pga == pytest.approx(2 * parse_pair("record:p695-ff/11", gravity=G).pair.resultant_pga)


def test_files_pair_and_single_component(tmp_path):
    a = load_record("p695-ff/1a", gravity=G)
    fx = tmp_path / "x.txt"
    fy = tmp_path / "y.txt"
    np.savetxt(fx, np.column_stack([np.arange(a.samples.size) * a.dt, a.samples / G]))
    np.savetxt(fy, np.column_stack([np.arange(300) * a.dt, -a.samples[:300] / G]))
    spec = parse_pair(f"files:{fx},{fy},units=g", gravity=G)
    pair = spec.pair
    assert pair.x.size == pair.y.size == a.samples.size
    np.testing.assert_allclose(pair.x, a.samples, rtol=1e-6)
    assert np.all(pair.y[300:] == 0.0)
    single = parse_pair("record:p695-ff/1a,azimuth=90deg", gravity=G).pair
    assert single.planar
    np.testing.assert_allclose(single.y, a.samples, atol=1e-12)
    np.testing.assert_allclose(single.x, 0.0, atol=1e-9)


def test_pulse_along_an_azimuth_and_free_vibration():
    spec = parse_pair("ricker-anti:ap=0.4g,Tp=0.9s,azimuth=30deg", gravity=G)
    pair = spec.pair
    assert pair.planar
    t = np.linspace(0, 3, 50)
    ax, ay = pair.acceleration(t)
    np.testing.assert_allclose(ay, math.tan(math.radians(30)) * ax, atol=1e-12)
    assert np.max(np.hypot(ax, ay)) <= 0.4 * G + 1e-9
    free = parse_pair("free:theta0=0.1rad,phidot0=1e-3rad/s", gravity=G)
    assert (free.theta0, free.phidot0) == (0.1, 1e-3) and not free.pair.planar
    assert parse_pair("free:theta0=0.5alpha", gravity=G, alpha=0.2).theta0 == pytest.approx(0.1)


def test_suites_of_pairs():
    assert {k: len(v[1]) for k, v in PAIR_SUITES.items()} == {
        "p695-farfield-pairs": 22, "p695-nearfield-pulse-pairs": 14, "p695-nearfield-nopulse-pairs": 14}
    pairs = suite_pairs("p695-nearfield-pulse-pairs", gravity=G)
    assert len(pairs) == 14 and all(not p.planar for p in pairs)


@pytest.mark.parametrize("text, words", [
    ("record:p695-ff/11,scale=2,resultant_pga=0.3g", "conflicting"),
    ("record:p695-ff/11,azimuth=north", "azimuth"),
    ("record:p695-ff/11,resultant_pga=0.3", "resultant_pga"),
    ("record:p695-ff/11,spin=1", "unknown motion parameter"),
    ("files:a.AT2", "two record files"),
    ("free:phidot0=1e-3rad/s", "initial tilt"),
    ("quake:p695-ff/11", "unknown motion kind"),
])
def test_motion_errors(text, words):
    with pytest.raises(MotionError) as err:
        parse_pair(text, gravity=G)
    assert words in str(err.value)


def test_unknown_pair_is_a_record_error():
    with pytest.raises((RecordError, MotionError)):
        parse_pair("record:p695-ff/99", gravity=G)
