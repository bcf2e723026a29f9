"""The example inputs of calibrate and validate (examples/, made by scripts/make_examples.py) are what
README says: the calibration recovers the c_r and p they were made with, the validation reads both files."""
from __future__ import annotations

import pytest

from rockdesign.planar.experiments.calibrate import calibrate
from rockdesign.experiments.free_vibration import read_tilt_csv
from rockdesign.experiments.validate import read_results_csv, validate
from rockdesign.paths import REPO_ROOT
from rockdesign.library import load_project

EXAMPLES = REPO_ROOT / "examples"


def test_free_vibration_example_recovers_what_it_was_made_with():
    text = (EXAMPLES / "free_vibration.csv").read_text(encoding="utf-8")
    assert "NOT A MEASUREMENT" in text             # the header says where the data come from
    project = load_project(EXAMPLES / "specimens" / "free_rocking_block.toml")
    cal = calibrate(project.system, read_tilt_csv(EXAMPLES / "free_vibration.csv"))
    assert cal.c_r_right == pytest.approx(0.93, abs=0.01)
    assert cal.c_r_left == pytest.approx(0.93 * 1.05, abs=0.01)
    assert cal.offset == pytest.approx(0.004, abs=5e-4)
    assert cal.lam == pytest.approx(0.543, abs=0.02)


def test_validation_examples_read_and_compare():
    for name in ("validation_tests.csv", "validation_analyses.csv"):
        assert "NOT MEASUREMENTS" in (EXAMPLES / name).read_text(encoding="utf-8") or name.endswith("analyses.csv")
    tests = read_results_csv(EXAMPLES / "validation_tests.csv", "tests")
    analyses = read_results_csv(EXAMPLES / "validation_analyses.csv", "analyses")
    data = validate(tests, analyses, None, seed=1).as_json()
    assert len(tests.values) == len(analyses.values) == 44
    assert sum(v == float("inf") for v in tests.values) == 13 and sum(v == float("inf") for v in analyses.values) == 19
    assert data
