"""Acceptance rules (SPEC §14): ground motions grouped by station, the suite-size rule refused up front,
the collapse margin computed on constructed capacity sets (non-monotonic and censored records) against
scipy.stats, and the check command's exit codes (4: not decided, 2: undersized suite before analyses)."""
from __future__ import annotations

import json
import math
import textwrap
import tomllib
from types import SimpleNamespace

import numpy as np
import pytest
from scipy import stats
from typer.testing import CliRunner

from rockdesign.acceptance.rule import (AcceptanceRule, acceptance_rule, first_overturn_scale,
                                          require_suite_size)
from rockdesign.acceptance.collapse_margin import collapse_margin
from rockdesign.acceptance.criteria import CheckContext, decide, evaluate_criteria
from rockdesign.planar.checks.criteria import criteria_for
from rockdesign.acceptance.fragility import check_fragility
from rockdesign.acceptance.scans import Margin
from rockdesign.cli import app
from rockdesign.errors import ProjectError
from rockdesign.motions.grouping import count_ground_motions, earthquake_id, ground_motion_id
from rockdesign.motions.suites import load_suite
from rockdesign.kinds import parse_document as parse_project
from rockdesign.planar.project import AnalysisSettings
from support import stocky_podium_toml

runner = CliRunner()
B = {"design_requirements": "B", "test_data": "B", "modeling": "B"}


def test_ground_motion_ids():
    assert ground_motion_id("p695-ff/11a") == ground_motion_id("p695-ff/11b") == "p695-ff/11"
    assert ground_motion_id("p695-nfp/6@90") == "p695-nfp/6"
    assert ground_motion_id("rsn:900:270", {"rsn": 900}) == ground_motion_id("x", {"rsn": 900}) == "RSN 900"
    assert ground_motion_id("file:a.AT2", {"ground_motion": "station A"}) == "station A"
    assert ground_motion_id("file:a.AT2", {}) == "file:a.AT2"           # no station information: its own
    assert earthquake_id({"event": "Northridge", "year": 1994}) == "Northridge 1994"


def test_the_far_field_suite_spans_22_ground_motions_from_14_earthquakes():
    suite = load_suite("p695-farfield")
    gms = [ground_motion_id(i, meta) for i, _, meta in suite.records]
    assert len(gms) == 44 and count_ground_motions(gms) == 22
    assert len({earthquake_id(meta) for _, _, meta in suite.records}) == 14    # FEMA P695 Table A-4
    # the two components of each ground motion share station and RSN
    for g in set(gms):
        metas = [meta for (i, _, meta), gg in zip(suite.records, gms) if gg == g]
        assert len(metas) == 2 and metas[0]["station"] == metas[1]["station"] and metas[0]["rsn"] == metas[1]["rsn"]


def test_risk_category_and_acceptance_keys():
    text = textwrap.dedent(stocky_podium_toml(analysis='risk_category = "III"'))
    rule = acceptance_rule(parse_project(tomllib.loads(text)).analysis)
    assert (rule.method, rule.target, rule.allowed, rule.binomial_limit) == ("asce7", 0.05, 0, 0.05)
    for bad in ('risk_category = "V"', 'risk_category = 2', 'acceptance = "bayes"'):
        with pytest.raises(ProjectError) as exc:
            parse_project(tomllib.loads(textwrap.dedent(stocky_podium_toml(analysis=bad))))
        assert "analysis." + bad.split(" ")[0] in str(exc.value)


@pytest.mark.parametrize("method,limit,n,ok", [("asce7", None, 10, False), ("asce7", None, 11, True),
                                               ("binomial", 0.10, 22, False), ("binomial", 0.10, 29, True)])
def test_suite_size_rule(method, limit, n, ok):
    rule = AcceptanceRule(method, "II", 0.10, 1, limit or 0.10)
    if ok:
        require_suite_size(rule, n, 2 * n, ["s"])
        return
    with pytest.raises(ProjectError) as exc:
        require_suite_size(rule, n, 2 * n, ["my-suite"], file="p.toml")
    text = str(exc.value)
    assert f"my-suite: {n} ground motion(s) from {2 * n} record(s)" in text
    assert f"at least {11 if method == 'asce7' else 29} independent ground motions" in text


def _outcome(i, scale, intervals, overturned=False, pga=2.0):
    m = Margin(scale, intervals, 8.0, 10)
    return SimpleNamespace(id=f"r{i}", ground_motion=f"g{i}", pga=pga, sd_max=0.1, margin=m, meta={},
                           run=SimpleNamespace(overturned=overturned, status="completed", failed=False,
                                              theta_max_over_theta_c=0.5),
                           polyakov_ratio=0.3, klass="a1")


@pytest.mark.parametrize("category", ["I", "II", "III", "IV"])
def test_collapse_margin_from_first_overturning_intensities_against_scipy(category):
    """Non-monotonic records (a band below the design level, safe at 1.0×), a record that overturns at the
    design level although the scan's first crossing is above it, and censored records: the capacities are the
    first overturning intensities; censored MLE and P695 numbers recomputed with scipy.stats."""
    rng = np.random.default_rng(7)
    scales = np.exp(rng.normal(math.log(2.6), 0.45, size=22))
    outcomes = []
    for i, s in enumerate(scales):
        if i < 3:      # censored: no overturning up to the scan limit
            outcomes.append(_outcome(i, None, []))
        elif i == 3:   # non-monotonic: overturns in [0.9, 1.3) and above 2.1, safe at the design level
            outcomes.append(_outcome(i, 0.9, [(0.9, 1.3), (2.1, None)]))
        elif i == 4:   # overturned at the design level (chaos) while the scan crossed first at 1.4
            outcomes.append(_outcome(i, 1.4, [(1.4, None)], overturned=True))
        else:
            outcomes.append(_outcome(i, float(s), [(float(s), None)]))
    a = AnalysisSettings(risk_category=category, ensemble_size=0)
    frag = check_fragility(outcomes, a, empirical=(1, 22), stripe_ratio=1.2)
    # independent: capacities x_i = s_i·IM_i with s_3 = 0.9 (first crossing) and s_4 = 1 (design-level run)
    s_first = [None, None, None, 0.9, 1.0] + [float(s) for s in scales[5:]]
    assert [first_overturn_scale(o) for o in outcomes] == s_first
    x = np.array([(s if s is not None else 8.0) * 2.0 for s in s_first])
    cens = np.array([s is None for s in s_first])
    mu, sigma = stats.norm.fit(stats.CensoredData.right_censored(np.log(x), cens))
    assert frag["method"] == "censored-mle" and frag["n_censored"] == 3
    assert frag["median"] == pytest.approx(math.exp(mu), rel=1e-4) and frag["beta"] == pytest.approx(sigma, rel=1e-3)
    assert frag["n_capacity_below_design"] == 2                     # the 0.9× band and the design-level run
    target = {"I": 0.10, "II": 0.10, "III": 0.05, "IV": 0.025}[category]
    cm = collapse_margin(frag, B, target)
    need = math.exp(-0.525 * stats.norm.ppf(target))
    # the fitted lognormal median (information): ACMR and P(collapse) against scipy's censored fit
    acmr_fitted = math.exp(mu) / 2.0
    assert cm["ACMR_fitted"] == pytest.approx(acmr_fitted, rel=1e-4) and cm["ACMR_target"] == pytest.approx(need, rel=1e-12)
    assert cm["p_collapse_design_fitted"] == pytest.approx(stats.norm.cdf(-math.log(acmr_fitted) / 0.525), rel=1e-3)
    # the counted Ŝ_CT that decides (FEMA P695 §6.4): the 11th of the 22 capacities (the 3 censored ones at
    # 16 m/s² lie above it), numpy's inverted-CDF quantile
    counted = float(np.quantile(x, 0.5, method="inverted_cdf"))
    assert counted == np.sort(x)[10] and counted < 16.0
    acmr = counted / 2.0
    assert cm["median_definition"] == "counted" and cm["ACMR"] == pytest.approx(acmr, rel=1e-12)
    assert cm["p_collapse_design"] == pytest.approx(stats.norm.cdf(-math.log(acmr) / 0.525), rel=1e-12)
    ctx = CheckContext(outcomes, a, {}, {}, True, {"collapse_margin": cm})
    items, skipped = evaluate_criteria(ctx, criteria_for(ctx.rule))
    v = decide(items, skipped, ctx.rule)
    # independent count: r4 overturns at the design level (ground motion g4) → 1 unacceptable
    allowed = {"I": 1, "II": 1, "III": 0, "IV": 0}[category]
    expect = (1 <= allowed) and acmr >= need
    assert v.verdict == ("PASS" if expect else "FAIL"), v.reason
    assert f"1 of 22 ground motions unacceptable ({allowed} allowed)" in v.reason


# ----------------------------------------------------------------------------------------- CLI


def _write(tmp_path, text):
    path = tmp_path / "p.toml"
    path.write_text(textwrap.dedent(text))
    return path


def test_no_margins_is_not_decided_exit_4(tmp_path):
    path = _write(tmp_path, stocky_podium_toml(pga="0.1 g"))
    out = tmp_path / "o"
    result = runner.invoke(app, ["check", str(path), "-o", str(out), "--no-pdf", "--no-margins"])
    assert result.exit_code == 4, result.output
    data = json.loads((out / "results.json").read_text())
    assert data["verdict"] == "NOT DECIDED" and data["acceptance"]["evaluated"] is False
    assert set(data["acceptance"]) >= {"method", "risk_category", "target_p_collapse", "n_ground_motions",   # §6.1
                                       "n_unacceptable", "allowed_unacceptable", "acmr", "acmr_required",
                                       "p_collapse_design", "evaluated", "passed", "reason"}
    assert data["summary"]["n_ground_motions"] == 2 and data["acceptance"]["passed"] is False
    assert "intensities below the design level not analysed" in data["verdict_reason"]
    assert "NOT DECIDED" in result.output


def test_undersized_suite_is_refused_before_any_analysis(tmp_path):
    # the default rule (ASCE 7) needs 11 ground motions; two records of two stations are refused at once
    text = stocky_podium_toml(pga="0.1 g", analysis="")
    out = tmp_path / "o"
    result = runner.invoke(app, ["check", str(_write(tmp_path, text)), "-o", str(out), "--no-pdf"])
    assert result.exit_code == 2, result.output
    flat = " ".join(result.output.split())
    assert "2 ground motion(s) from 2 record(s)" in flat and "at least 11 independent ground motions" in flat
    assert "Traceback" not in result.output and not (out / "results.json").exists()


@pytest.mark.slow
def test_the_column_template_passes_on_its_own_default_suite(tmp_path):
    """`rockdesign init column` (a structure that nothing overturns at its design level) PASSes on the 22-ground-
    motion far-field suite it ships with: exit 0, the ASCE 7 rule with both governing numbers."""
    path = tmp_path / "column.toml"
    assert runner.invoke(app, ["init", "column", str(path)]).exit_code == 0
    out = tmp_path / "o"
    result = runner.invoke(app, ["check", str(path), "-o", str(out), "--no-pdf"])
    assert result.exit_code == 0, result.output
    data = json.loads((out / "results.json").read_text())
    acc = data["acceptance"]
    assert data["verdict"] == "PASS" and acc["n_ground_motions"] == 22 and acc["n_unacceptable"] == 0
    assert acc["acmr"] >= acc["acmr_required"] and acc["evaluated"] is True
    assert data["verdict_reason"].startswith("PASS (ASCE 7-22 §16.4, risk category II; records scaled to PGA, not "
                                             "per ASCE 7-22 §16.2): 0 of 22 ground motions unacceptable (1 allowed); "
                                             "ACMR ")
