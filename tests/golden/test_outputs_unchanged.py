"""The numbers a user sees do not change under a restructuring: ``results.json`` of every example's
check and ``simulate --json`` on fixed motions equal the stored files (tests/golden/data)."""
from __future__ import annotations

import json

import pytest

from golden_cases import CHECKS, DATA, SIMULATIONS, differences, run_check, run_simulation

pytestmark = pytest.mark.slow


@pytest.mark.parametrize("name", CHECKS)
def test_check_results_json_unchanged(name, tmp_path):
    expected = json.loads((DATA / "check" / f"{name}.json").read_text())
    diff = differences(expected, run_check(name, tmp_path / name))
    assert not diff, f"{len(diff)} differences, first: " + "; ".join(diff[:8])


@pytest.mark.parametrize("key", sorted(SIMULATIONS))
def test_simulate_json_unchanged(key):
    expected = json.loads((DATA / "simulate" / f"{key}.json").read_text())
    diff = differences(expected, run_simulation(key))
    assert not diff, f"{len(diff)} differences, first: " + "; ".join(diff[:8])


def test_comparison_sees_a_change_in_the_last_reported_digits():
    base = {"a": [1.0, {"b": 0.123456789012}], "s": "PASS", "n": 3}
    assert differences(base, json.loads(json.dumps(base))) == []
    assert differences(base, {"a": [1.0, {"b": 0.123456790}], "s": "PASS", "n": 3})
    assert differences(base, {"a": [1.0, {"b": 0.123456789012}], "s": "FAIL", "n": 3})
    assert differences(base, {"a": [1.0, {"b": 0.123456789012}], "s": "PASS", "n": 4})
