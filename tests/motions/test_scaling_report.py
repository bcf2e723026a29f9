"""The ``excitation.scaling`` block (CONTRACT §7.1) and its page-1 sentence, for every scaling method.

The block's numbers are recomputed here from the scaled records: per-component PGA factors by hand
(0.20 g / PGA), the suite average of the pairs' RotD100 spectra with rockdesign.motions.max_direction
(validated in test_max_direction.py) on the block's own periods.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

from rockdesign.motions.asce7_22 import rocking_structure_periods, scaling_period_range
from rockdesign.motions.config import parse_excitation, resolve_motions
from rockdesign.motions.design_spectra import EC8Spectrum
from rockdesign.motions.max_direction import motions_max_direction_spectrum
from rockdesign.motions.scaling_report import scaling_block, scaling_sentence
from rockdesign.motions.targets import MCERSpectrum

G = 9.81
KEYS = {"standard", "method", "period_range", "period_range_basis", "target", "suite_average_max_direction",
        "min_ratio", "conformant", "factors", "note"}
PODIUM = rocking_structure_periods(fixed_base=0.30, uplifted=0.30 / 2.147, rocking=1.364)
RANGE = scaling_period_range(PODIUM)
MCER = MCERSpectrum(0.60 * G, 0.30 * G, 8.0)


def resolved(raw, **kw):
    return resolve_motions(parse_excitation(raw, file="p.toml", gravity=G), gravity=G, **kw)


@pytest.fixture(scope="module")
def pga_suite():
    return resolved({"suites": ["p695-farfield"], "scale": {"method": "pga", "target": "0.20 g"}})


def test_asce7_22_block():
    suite = resolved({"suites": ["p695-farfield"],
                      "scale": {"method": "asce7-22", "SMS": "0.60 g", "SM1": "0.30 g", "TL": "8 s"}},
                     characteristic_periods=PODIUM)
    block = scaling_block(suite, gravity=G)
    assert set(block) == KEYS and json.loads(json.dumps(block)) == block
    assert block["standard"] == "ASCE 7-22 §16.2.3" and block["method"] == "asce7-22"
    assert block["conformant"] is True and block["min_ratio"] == pytest.approx(0.9)
    assert block["period_range"] == [pytest.approx(RANGE.lo), pytest.approx(RANGE.hi)]
    assert "§16.2.1" in block["period_range_basis"]
    assert len(block["factors"]) == 22 and block["factors"] == suite.asce7_22.factors
    for key in ("target", "suite_average_max_direction"):
        assert len(block[key]["periods"]) == len(block[key]["psa"]) > 400
    ratio = np.array(block["suite_average_max_direction"]["psa"]) / np.array(block["target"]["psa"])
    assert ratio.min() == pytest.approx(0.9, rel=1e-12)
    assert "One factor per ground motion (22)" in block["note"]
    sentence = scaling_sentence(block, G)
    assert sentence.startswith("Records scaled per ASCE 7-22 §16.2.3") and sentence.endswith("conformant.")
    assert "\n" not in sentence


def test_pga_without_a_target(pga_suite):
    block = scaling_block(pga_suite, period_range=RANGE, gravity=G)
    assert set(block) == KEYS and block["standard"] is None and block["method"] == "pga"
    assert block["target"] is None and block["conformant"] is None and block["min_ratio"] is None
    assert len(block["factors"]) == 44
    for record in pga_suite.records[:6]:
        assert block["factors"][record.id] == pytest.approx(0.20 * G / (record.motion.pga / record.scale), rel=1e-12)
    assert "scaled to PGA 0.2 g per component" in block["note"] and "not ASCE 7-22 §16.2 scaling" in block["note"]
    assert "per component" in block["note"]
    sentence = scaling_sentence(block, G)
    assert "PGA 0.2 g per component" in sentence and "not ASCE 7-22 §16.2 scaling" in sentence
    assert "no target spectrum" in sentence
    # without a period range there is nothing to compare
    bare = scaling_block(pga_suite, gravity=G)
    assert bare["period_range"] is None and bare["suite_average_max_direction"] is None and bare["conformant"] is None


def test_pga_against_a_known_target(pga_suite):
    block = scaling_block(pga_suite, period_range=RANGE, target=MCER, gravity=G)
    assert block["conformant"] is False and block["standard"] is None
    periods = np.array(block["suite_average_max_direction"]["periods"])
    by_id = {r.id: r.motion for r in pga_suite.records}
    average = np.mean([motions_max_direction_spectrum(by_id[f"p695-ff/{n}a"], by_id[f"p695-ff/{n}b"], periods)[2]
                       for n in range(1, 23)], axis=0)
    np.testing.assert_allclose(block["suite_average_max_direction"]["psa"], average, rtol=1e-12)
    np.testing.assert_allclose(block["target"]["psa"], MCER.psa(periods), rtol=1e-14)
    assert block["min_ratio"] == pytest.approx(np.min(average / MCER.psa(periods)), rel=1e-12)
    assert block["min_ratio"] < 0.9 and "below the 90 %" in block["note"]
    assert scaling_sentence(block, G).endswith("not conformant.")


def test_per_component_factors_cannot_conform_even_above_the_target():
    suite = resolved({"suites": ["p695-farfield"], "scale": {"method": "pga", "target": "1.5 g"}})
    block = scaling_block(suite, period_range=RANGE, target=MCER, gravity=G)
    assert block["min_ratio"] > 0.9 and block["conformant"] is False
    assert "different factors" in block["note"]


def test_spectrum_rule_judged_at_5_percent():
    suite = resolved({"suites": ["p695-farfield"], "scale": {"method": "spectrum", "code": "ec8", "ag": "0.25 g",
                                                             "ground_type": "C", "damping": "2 %"}})
    block = scaling_block(suite, period_range=RANGE, gravity=G)
    assert block["method"] == "spectrum" and block["standard"] is None
    expected = EC8Spectrum(0.25 * G, "C", 1, 0.05).psa(block["target"]["periods"])
    np.testing.assert_allclose(block["target"]["psa"], expected, rtol=1e-14)
    assert len(set(block["factors"].values())) == 1 and len(block["factors"]) == 22   # one factor, per ground motion
    assert block["conformant"] is (block["min_ratio"] >= 0.9)
    # without the structure's range, the rule's own band
    block = scaling_block(suite, gravity=G)
    assert block["period_range"] == [0.05, 4.0] and "band" in block["period_range_basis"]


def test_single_components_cannot_conform():
    suite = resolved({"records": ["p695-ff/1a", "p695-ff/2a", "p695-ff/2b"], "scale": {"method": "factor", "value": 2}})
    block = scaling_block(suite, period_range=RANGE, target=MCER, gravity=G)
    assert block["conformant"] is False and block["min_ratio"] is None
    assert block["suite_average_max_direction"] is None
    assert "p695-ff/1 (p695-ff/1a): one component only" in block["note"] and "at least 11" in block["note"]
    assert block["factors"] == {"p695-ff/1": 2.0, "p695-ff/2": 2.0}
    assert "cannot conform" in scaling_sentence(block, G)
