"""Each stability case finishes and returns a diagnosed result for our engine (engine-only runs)."""
from __future__ import annotations

import pytest

from rockdesign.bench.stability import VERDICTS, StabilityCase, case_functions, stability_markdown

ENGINE_ONLY = ("rockdesign",)


@pytest.fixture(scope="module")
def cases():
    return {key: fn(quick=True, methods=ENGINE_ONLY) for key, fn in case_functions().items()}


def test_all_eight_conditions_are_covered(cases):
    assert set(cases) == {"missed-events", "zeno", "stiff-superstructure", "overturning-threshold",
                          "long-record-drift", "coarse-sampling", "event-location-crash", "planar-azimuth"}


@pytest.mark.parametrize("key", ["missed-events", "zeno", "stiff-superstructure", "overturning-threshold",
                                 "long-record-drift", "coarse-sampling", "event-location-crash", "planar-azimuth"])
def test_case_returns_a_diagnosed_engine_result(cases, key):
    case = cases[key]
    assert isinstance(case, StabilityCase)
    assert case.diagnosed
    assert case.engine["status"] in ("completed", "overturned (|θ| = π/2)", "event limit reached",
                                     "overturned (θ reached θ_ot)")
    assert isinstance(case.engine["steps"], int) and case.engine["function_evaluations"] > 0
    ours = case.outcome("rockdesign")
    assert ours is not None and ours.verdict in VERDICTS and ours.detail
    assert case.engine_behaviour and case.setup


def test_engine_keeps_every_impact_and_ends_zeno(cases):
    assert cases["missed-events"].outcome("rockdesign").verdict == "ok"
    zeno = cases["zeno"]
    assert zeno.outcome("rockdesign").verdict == "ok"
    # without a rest threshold the event bound stops the run: diagnosed, not hung
    assert zeno.engine["status"] == "event limit reached" and zeno.engine["events"] == 100_000


def test_the_cylinder_analyses_a_planar_motion_along_any_azimuth(cases):
    case = cases["planar-azimuth"]
    assert case.outcome("rockdesign").verdict == "ok"
    rows = case.outcome("rockdesign").data["rows"]
    assert {r["azimuth"] for r in rows} == {0.0, 45.0, 200.0} and {r["contact"] for r in rows} == {"rigid",
                                                                                                 "spring-dashpot"}
    assert {(r["uplifted"], r["overturned"]) for r in rows} == {(False, False), (True, False), (True, True)}
    assert all(not r["failed"] and r["planar"] and r["same_outcome"] for r in rows)
    assert all(r["d_theta"] <= r["bound"] for r in rows if not r["chaotic"])
    # the 3D equations alone collapse on the same motion: the case provokes what it claims
    assert case.engine["without_reduction"] == "step size collapsed"
    # a real cross component ends in a result or a reported failure, never in a wrong planar answer
    cross = case.data["cross"]
    assert cross[0]["fraction"] == 0.0 and cross[0]["status"].startswith("overturned")
    assert all(c["status"].startswith("overturned") or c["status"] == "step size collapsed" for c in cross)


def test_markdown_table_and_a_figure(cases, tmp_path):
    from rockdesign.bench.stability import write_stability_figures
    picked = [cases["missed-events"], cases["zeno"]]
    figs = write_stability_figures(picked, tmp_path)
    assert all(p.stat().st_size > 1000 for paths in figs.values() for p in paths)
    md = stability_markdown(list(cases.values()), figs)
    assert md.count("\n| ") >= 9          # header + one row per condition
    assert "Zeno" in md and "stability_zeno.png" in md
