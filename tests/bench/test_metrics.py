"""Accuracy metrics and timing helpers of the work-precision study, on constructed data."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.planar.dynamics import metrics
from rockdesign.bench.runner import problem_summary
from rockdesign.jsonable import json_ready
from rockdesign.bench.timing import TimingPolicy, time_call


def test_max_abs_difference():
    a = np.array([0.0, 0.1, -0.2, 0.3])
    b = np.array([0.0, 0.1 + 1e-9, -0.2, 0.3 - 3e-9])
    assert metrics.max_abs_difference(a, b) == pytest.approx(3e-9, rel=1e-6)
    assert metrics.max_abs_difference([], []) == 0.0
    assert metrics.max_abs_difference([0.0, math.nan], [0.0, 0.0]) == math.inf
    with pytest.raises(ValueError):
        metrics.max_abs_difference([1.0], [1.0, 2.0])


def test_theta_max_error_and_overturn_agreement():
    assert metrics.theta_max_error(0.12, 0.1) == pytest.approx(0.02)
    assert metrics.theta_max_error(0.1, 0.12) == pytest.approx(0.02)
    assert metrics.overturn_agreement("none", "none")
    assert not metrics.overturn_agreement("dynamic", "exceeded")


def test_impact_time_error_pairs_the_first_impacts():
    ref = np.array([1.0, 1.5, 1.8, 2.0, 2.1, 2.15, 2.17])
    got = ref + np.array([1e-9, -2e-9, 3e-9, 0.0, 0.0, 0.5, 0.5])   # errors after the 5th are not compared
    assert metrics.impact_time_error(got, ref, t_end=10.0) == pytest.approx(3e-9, rel=1e-6)
    assert metrics.impact_time_error(got[::-1], ref, t_end=10.0) == pytest.approx(3e-9, rel=1e-6)  # order-free
    assert metrics.impact_time_error(got, ref, t_end=10.0, count=7) == pytest.approx(0.5)


def test_missed_and_spurious_impacts_are_finite_and_large():
    ref = np.array([1.0, 1.5, 1.8])
    # a missed third impact counts as happening at t_end
    assert metrics.impact_time_error([1.0, 1.5], ref, t_end=10.0) == pytest.approx(10.0 - 1.8)
    # an impact where the reference has none: its distance to the end of the analysis
    assert metrics.impact_time_error([4.0], [], t_end=10.0) == pytest.approx(6.0)
    assert metrics.impact_time_error([], [], t_end=10.0) == 0.0


def test_error_history_is_sorted_by_time():
    t, e = metrics.error_history([2.0, 0.0, 1.0], [0.3, 0.1, 0.2], [0.3, 0.0, 0.25])
    assert list(t) == [0.0, 1.0, 2.0]
    assert e == pytest.approx([0.1, 0.05, 0.0])


def test_cost_at_accuracy_and_summary_ratios():
    pts = [{"seconds": 0.001, "error_theta": 1e-4}, {"seconds": 0.002, "error_theta": 1e-7},
           {"seconds": 0.004, "error_theta": 1e-10}]
    assert metrics.cost_at_accuracy(pts, 1e-6) == 0.002
    assert metrics.cost_at_accuracy(pts, 1e-12) is None
    entry = {"methods": [{"name": "rockdesign", "points": pts},
                         {"name": "scipy DOP853", "points": [{"seconds": 0.2, "error_theta": 1e-7},
                                                             {"seconds": 0.3, "error_theta": 1e-10}]}]}
    s = problem_summary(entry)
    assert s["ratio_to_rockdesign_1e-06"]["scipy DOP853"] == pytest.approx(100.0)
    assert s["ratio_to_rockdesign_1e-09"]["scipy DOP853"] == pytest.approx(75.0)
    assert s["ratio_to_rockdesign_1e-06"]["rockdesign"] == pytest.approx(1.0)


def test_time_call_follows_the_policy(monkeypatch):
    calls = []
    med, n, samples = time_call(lambda: calls.append(1), TimingPolicy(max_repeats=5, min_repeats=3, budget=10.0))
    assert n == len(calls) == len(samples) == 5 and med >= 0.0
    # a fake clock: every call takes exactly 1 s
    import rockdesign.bench.timing as timing
    ticks = iter(range(1000))

    class FakeTime:
        @staticmethod
        def perf_counter():
            return float(next(ticks))
    monkeypatch.setattr(timing, "time", FakeTime)
    med, n, samples = time_call(lambda: None, TimingPolicy(max_repeats=5, min_repeats=2, budget=2.5))
    assert n == 2 and med == 1.0          # 2 runs + the median would exceed the budget
    med, n, samples = time_call(lambda: None, TimingPolicy(max_repeats=5, min_repeats=3, budget=0.5))
    assert n == 1                         # one run longer than the whole budget is timed once
    assert metrics.median_seconds([3.0, 1.0, 2.0]) == 2.0


def test_json_ready_makes_strict_json():
    out = json_ready({"a": math.inf, "b": [np.float64(1.5), math.nan], "c": np.int64(3), "d": np.bool_(True)})
    assert out == {"a": None, "b": [1.5, None], "c": 3, "d": True}
