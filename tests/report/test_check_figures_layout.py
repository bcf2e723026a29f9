"""The check report's figures laid out and read back (tests/report/figure_layout.py), drawn from small synthetic
results shaped like a check's (fast) and, in the slow tests, from real checks of the examples.

What the issue found on the example reports, each made again here: the fragility legend over ~10 capacity
points, "peak 0.5819 (dotted)" printed over the superstructure's trace, the ECDF's legend on its curve and
"1 record(s)", the time histories' legends on the ±θc/α lines.  The §16.2 figure is drawn from the
``excitation.scaling`` block of the ASCE 7-22 example's pinned results.json (tests/golden).
"""
from __future__ import annotations

import json
from types import SimpleNamespace

import numpy as np
import pytest

from figure_layout import drawn_texts, layout_problems
from rockdesign.paths import REPO_ROOT

RNG = np.random.default_rng(11)


def _margin(first: float | None, safe_again: bool = False):
    """A record's incremental-analysis result: first overturning factor and its bands (up to the scan limit 8)."""
    if first is None:
        return SimpleNamespace(overturn_scale=None, intervals=[], scanned_up_to=8.0)
    bands = [(first, first * 1.6), (first * 2.0, None)] if safe_again else [(first, None)]
    return SimpleNamespace(overturn_scale=first, intervals=bands, scanned_up_to=8.0)


def fragility_result(n: int = 44):
    """A check result with a fragility of ``n`` records (capacities log-normal around 2.4× design, one censored)."""
    design = 1.962
    firsts = np.exp(RNG.normal(np.log(2.4), 0.5, n))
    records = [SimpleNamespace(id=f"p695-ff/{k // 2 + 1}{'ab'[k % 2]}", run=SimpleNamespace(overturned=False),
                               margin=_margin(None if k == n - 1 else float(s), safe_again=k % 3 == 0))
               for k, s in enumerate(firsts)]
    caps = [{"id": o.id, "capacity": (o.margin.overturn_scale or 8.0) * design, "censored": o.margin.overturn_scale is None}
            for o in records]
    levels = [design * f for f in (0.694, 0.833, 1.0, 1.2, 1.44, 1.728, 2.07, 2.49, 2.99, 3.58)]
    fragility = {"unit": "m/s^2", "capacities": caps, "design_intensity": design, "im_label": "PGA", "period": None,
                 "method": "censored-mle", "median": 2.4 * design, "beta": 0.5, "p_overturn_design": 0.04,
                 "p_overturn_empirical": 0.0,
                 "stripes": {"levels": levels, "n": [n] * len(levels), "median": 2.6 * design, "beta": 0.55,
                             "overturned": [int(n * min(1.0, max(0.0, (f / design - 0.9) / 3))) for f in levels]}}
    margin = {"CMR_is_lower_bound": False, "median_capacity": 2.3 * design, "beta_tot": 0.525, "unit": "m/s^2",
              "p_collapse_design": 0.054, "ACMR": 2.32}
    return SimpleNamespace(records=records, fragility=fragility, collapse_margin=margin,
                           acceptance={"target_p_collapse": 0.1, "risk_category": "II"})


def test_the_fragility_legend_covers_no_capacity_point():
    from rockdesign.report.fragility_figures import fragility_figure
    assert layout_problems(fragility_figure(fragility_result())) == []


def _response(overturning: bool = False, superstructure: bool = True):
    """A 40-s response shaped like the engine's (θ in rad, α = 0.15 rad, impacts every 0.35 s from 12 s)."""
    t = np.linspace(0.0, 40.0, 8001)
    alpha = 0.15
    envelope = np.exp(-((t - 18.0) / 6.0) ** 2)
    theta = 0.7 * alpha * envelope * np.sin(2 * np.pi * t / 0.7)
    if overturning:
        theta = np.where(t > 30.0, np.minimum(1.6, (t - 30.0) * 0.3), theta)
    impacts = [SimpleNamespace(kind="impact", time=float(x)) for x in np.arange(12.0, 26.0, 0.35)]
    uplift = [SimpleNamespace(kind="uplift", time=11.8)]
    a_t = 0.55 * 9.81 * envelope * np.sin(2 * np.pi * t / 0.38)
    return SimpleNamespace(t=t, ground_acceleration=1.9 * envelope * np.sin(2 * np.pi * t / 0.5), theta=theta,
                           alpha=alpha, theta_c=alpha, events=impacts + uplift, u_B=1.5 * theta,
                           u_rel=0.02 * envelope * np.sin(2 * np.pi * t / 0.38) if superstructure else 0 * t,
                           u_capacity=0.45, a_T_abs=a_t, superstructure_acceleration_max=float(np.max(np.abs(a_t))),
                           fixed_base_acceleration_max=0.47 * 9.81)


def test_the_superstructure_peaks_are_not_printed_over_the_trace():
    from rockdesign.planar.report.demand_figures import demand_history_figure
    result = SimpleNamespace(demand_history=("p695-ff/18a", _response()),
                             project=SimpleNamespace(system=SimpleNamespace(g=9.81)))
    fig = demand_history_figure(result)
    assert layout_problems(fig) == []
    assert any("peak" in t.text and "dotted" in t.text for t in drawn_texts(fig))     # still said, off the trace


@pytest.mark.parametrize("overturning", [False, True])
def test_the_time_histories_keep_their_legends_off_the_traces(overturning):
    from rockdesign.planar.report.figures import history_figure
    response = _response(overturning)
    record = SimpleNamespace(id="p695-ff/11a", motion=SimpleNamespace(meta={"event": "Landers"}), meta={},
                             scale=0.817)
    result = SimpleNamespace(histories={"p695-ff/11a": response}, records=[record],
                             project=SimpleNamespace(system=SimpleNamespace(g=9.81)))
    fig = history_figure(result, "p695-ff/11a")
    assert layout_problems(fig) == []
    assert any("clipped" in t.text for t in drawn_texts(fig)) is overturning


def test_the_ecdf_says_how_many_records_exceed_the_capacity_in_words_and_off_its_curve():
    from rockdesign.planar.report.figures import ecdf_figure
    x = np.sort(np.concatenate([RNG.uniform(0.02, 0.7, 43), [1.3]]))
    result = SimpleNamespace(statistics={"theta_max_over_alpha_ecdf": {"x": x.tolist(),
                                                                       "F": (np.arange(1, 45) / 44).tolist()}},
                             quantities={"alpha": SimpleNamespace(value=0.15), "theta_c": SimpleNamespace(value=0.15)})
    fig = ecdf_figure(result)
    assert layout_problems(fig) == []
    texts = " ".join(t.text for t in drawn_texts(fig))
    assert "1 record with" in texts and "(s)" not in texts


def _scaling_block() -> dict:
    data = json.loads((REPO_ROOT / "tests" / "golden" / "data" / "check" / "podium_asce7_22.json").read_text())
    return data["excitation"]["scaling"], data["settings"]["g"]


def test_the_16_2_figure_draws_the_pinned_block_and_marks_the_lowest_ratio():
    """Suite average, target, its 90 % and the period range of results.json; the governing period is where the
    block's own minimum ratio (0.900) is reached."""
    from rockdesign.report.scaling_figures import governing_period, scaling_figure
    block, g = _scaling_block()
    fig = scaling_figure(block, g)
    assert layout_problems(fig) == []
    period, ratio = governing_period(block)
    assert ratio == pytest.approx(block["min_ratio"], rel=1e-6)
    assert f"{period:.3g} s" in block["note"]                 # "… at its lowest (0.073 s)"
    texts = " ".join(t.text for t in drawn_texts(fig))
    lo, hi = block["period_range"]
    assert f"{lo:.3g}–{hi:.3g} s" in texts and f"governing period {period:.3g} s" in texts
    ax = fig.axes[0]
    curves = {line.get_label(): line.get_ydata() for line in ax.get_lines()}
    target = next(v for k, v in curves.items() if k.startswith("target"))
    assert np.allclose(target * g, block["target"]["psa"])
    assert np.allclose(curves["90 % of the target"], 0.9 * target)


def test_a_suite_without_a_target_has_no_16_2_figure():
    from rockdesign.report.scaling_figures import has_target
    block, _ = _scaling_block()
    assert has_target(block)
    assert not has_target(dict(block, target=None)) and not has_target(None)
