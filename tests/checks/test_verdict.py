"""The verdict of ``rockdesign check``: criteria classes and the one ``decide`` on constructed suites
whose answers are known (ground-motion counts per risk category, collapse margins, c_r perturbations,
failed analyses, skipped criteria), the binomial bound against scipy, and one full check of the
example whose verdict must say what the run found."""
from __future__ import annotations

import json
import math
from types import SimpleNamespace

import pytest
from scipy.stats import binomtest, norm

from rockdesign.acceptance.rule import AcceptanceRule, minimum_records, probability_bound
from rockdesign.planar.checks.criteria import CRITERIA, criteria_for
from rockdesign.acceptance.criteria import (GOVERNS, NOT_DECIDED, ROBUSTNESS, CheckContext, Criterion,
                                        decide, evaluate_criteria)
from rockdesign.acceptance.scans import Margin
from rockdesign.planar.checks.runner import analysis_failed
from rockdesign.planar.project import AnalysisSettings

A = AnalysisSettings()


def outcome(i, *, overturned=False, margin=None, status="completed", theta=0.5, ratio=0.4, klass="a1", gm=None):
    run = SimpleNamespace(overturned=overturned, status=status, failed=analysis_failed(status),
                          theta_max_over_theta_c=1.2 if overturned else theta)
    return SimpleNamespace(id=f"r{i}", run=run, margin=margin, polyakov_ratio=ratio, klass=klass,
                           ground_motion=gm or f"gm{i // 2}", meta={})


def safe_margin(scale=4.0):
    return Margin(scale, [(scale, None)], 8.0, 10)


def sensitivity(n, minus=(), plus=()):
    runs = {}
    for f, recs in ((0.98, minus), (1.02, plus)):
        runs[f"{f:.4g}"] = {"restitution_factor": f, "n_overturned": len(recs), "n_records": n, "records": list(recs),
                            "verdict_changes": len(recs)}
    return {"variation": 0.02, "runs": runs}


def collapse(acmr, lower=False):
    return {"ACMR": acmr, "CMR": acmr, "beta_tot": 0.525, "CMR_is_lower_bound": lower, "median_capacity": acmr * 2.0,
            "design_intensity": 2.0, "im": "pga", "unit": "m/s^2"}


def suite(n=44, **kw):
    return [outcome(i, margin=safe_margin(), **kw) for i in range(n)]


def run(outcomes, sens=None, margins=True, q=None, cm=2.5, rule=None, analysis=A):
    extra = {"collapse_margin": collapse(cm) if isinstance(cm, (int, float)) else cm}
    ctx = CheckContext(outcomes, analysis, q or {}, sens or sensitivity(len(outcomes)), margins, extra, rule)
    items, skipped = evaluate_criteria(ctx, criteria_for(ctx.rule))
    return items, decide(items, skipped, ctx.rule)


def test_minimum_records_is_the_smallest_suite_whose_bound_can_pass():
    # k = 0: the one-sided 95 % Clopper–Pearson bound is 1 − 0.05^(1/n) (scipy's exact interval)
    for limit in (0.10, 0.05, 0.025, 0.2):
        n = minimum_records(limit)
        hi = binomtest(0, n).proportion_ci(confidence_level=0.90, method="exact").high
        hi_less = binomtest(0, n - 1).proportion_ci(confidence_level=0.90, method="exact").high
        assert hi <= limit < hi_less
        assert probability_bound(0, n) == pytest.approx(hi, abs=1e-12)
    assert minimum_records(0.10) == 29 and minimum_records(0.05) == 59 and minimum_records(0.025) == 119
    assert minimum_records(0.0) is None


def test_a_safe_suite_passes_robustly_and_says_which_method_decided():
    items, v = run(suite())
    assert v.verdict == "PASS" and v.robust and v.exit_code == 0
    p = norm.cdf(-math.log(2.5) / 0.525)
    assert v.reason == (f"PASS (ASCE 7-22 §16.4, risk category II): 0 of 22 ground motions "
                        f"unacceptable (1 allowed); ACMR 2.5 ≥ 1.96 (P(collapse) {100 * p:.2g} % ≤ 10 %)")
    by_key = {i.key: i for i in items}
    assert {k for k, i in by_key.items() if i.role == GOVERNS} == {"analyses_completed", "unacceptable_responses",
                                                                  "collapse_margin"}
    for i in items:                 # utilisation and result agree for every item
        assert (i.utilisation <= 1.0) == i.passed, i
        assert set(i.as_json()) >= {"name", "utilisation", "passed", "governs_verdict", "detail", "verdict_reason"}


@pytest.mark.parametrize("category,allowed,target", [("I", 1, 0.10), ("II", 1, 0.10), ("III", 0, 0.05),
                                                     ("IV", 0, 0.025)])
@pytest.mark.parametrize("pattern", ["none", "one-pair-both", "one-component", "two-stations"])
def test_count_rule_per_ground_motion_each_risk_category(category, allowed, target, pattern):
    """ASCE 7-22 §16.4.1.1 counted per ground motion: both components of one station overturning count once."""
    over = {"none": [], "one-pair-both": [6, 7], "one-component": [9], "two-stations": [3, 30]}[pattern]
    outcomes = suite()
    for i in over:
        outcomes[i] = outcome(i, overturned=True, margin=Margin(1.0, [(1.0, None)], 8.0, 10))
    analysis = AnalysisSettings(risk_category=category)
    items, v = run(outcomes, analysis=analysis, cm=5.0)
    stations = {i // 2 for i in over}                      # independent count of the unacceptable ground motions
    expected = len(stations) <= allowed
    item = next(i for i in items if i.key == "unacceptable_responses")
    assert item.passed is expected and f"{len(stations)} of 22 ground motions unacceptable ({allowed} allowed)" in \
        item.verdict_reason
    assert v.verdict == ("PASS" if expected else "FAIL")
    assert f"risk category {category}" in v.reason
    cm = next(i for i in items if i.key == "collapse_margin")
    assert f"ACMR 5 ≥ {math.exp(-0.525 * norm.ppf(target)):.3g}" in cm.verdict_reason


@pytest.mark.parametrize("acmr", [1.5, 1.9, 1.96, 2.0, 2.37, 2.5, 2.8, 3.0])
@pytest.mark.parametrize("category", ["II", "III", "IV"])
def test_collapse_margin_at_the_category_target_against_scipy(acmr, category):
    target = {"II": 0.10, "III": 0.05, "IV": 0.025}[category]
    items, v = run(suite(), cm=acmr, analysis=AnalysisSettings(risk_category=category))
    item = next(i for i in items if i.key == "collapse_margin")
    need = math.exp(-0.525 * norm.ppf(target))            # FEMA P695 Eq 7-4 with x = the category's target
    p = norm.cdf(-math.log(acmr) / 0.525)
    assert item.passed == (acmr >= need) == bool(p <= target + 1e-12)
    assert item.utilisation == pytest.approx(need / acmr)
    text = f"P(collapse) {100 * p:.2g} %" if p < 0.1 else f"P(collapse) {100 * p:.3g} %"
    assert text in item.verdict_reason
    assert v.verdict == ("PASS" if acmr >= need else "FAIL")


def test_a_lower_bound_margin_passes_only_when_it_suffices():
    _, v = run(suite(), cm=collapse(8.0, lower=True))
    assert v.verdict == "PASS" and "ACMR ≥ 8 ≥ 1.96" in v.reason
    items, v = run(suite(), cm=collapse(1.5, lower=True))
    assert v.verdict == NOT_DECIDED and v.exit_code == 4 and "raise [analysis] margin_max_scale" in v.reason
    assert not next(i for i in items if i.key == "collapse_margin").evaluated


def test_without_margins_the_verdict_is_not_decided():
    """--no-margins: the collapse margin (governing) is not evaluated, so no PASS and no exit 0."""
    _, v = run(suite(), margins=False)
    assert v.verdict == NOT_DECIDED and v.exit_code == 4
    assert v.reason.startswith("NOT DECIDED (ASCE 7-22 §16.4, risk category II): collapse margin not evaluated")
    assert "0 of 22 ground motions unacceptable" in v.reason
    # a failure that is certain stays a FAIL (exit 1), and says what was not evaluated
    outcomes = suite()
    for i in (0, 2):
        outcomes[i] = outcome(i, overturned=True)
    _, v = run(outcomes, margins=False)
    assert v.verdict == "FAIL" and v.exit_code == 1 and "not evaluated: collapse margin" in v.reason


def test_a_component_pair_suite_of_22_passes_where_the_component_binomial_could_not():
    """The issue's shipped-suite case: 0 of 22 overturn; the binomial bound 0.127 > 0.10 is informative."""
    items, v = run(suite())
    b = next(i for i in items if i.key == "overturning_probability")
    assert b.role == "informative" and not b.passed
    assert b.utilisation == pytest.approx(binomtest(0, 22).proportion_ci(0.90, "exact").high / 0.10)
    assert v.verdict == "PASS"


def test_a_check_without_incremental_analysis_is_decided_by_the_count():
    """A kind whose check has no incremental analysis (a rule built with ``with_collapse_margin(False)``, each
    outcome one ground motion): the count rule alone decides, and says so."""
    pairs = [outcome(i, gm=f"p695-ff/{i + 1}") for i in range(22)]
    for o in pairs:
        o.id = o.ground_motion
        o.margin = None
    rule = AcceptanceRule().with_collapse_margin(False)
    items, v = run(pairs, margins=False, cm=None, rule=rule)
    assert v.verdict == "PASS" and v.exit_code == 0 and "0 of 22 ground motions unacceptable (1 allowed)" in v.reason
    assert "collapse_margin" not in {i.key for i in items}
    pairs[3].run.overturned = pairs[5].run.overturned = True
    _, v = run(pairs, margins=False, cm=None, rule=rule)
    assert v.verdict == "FAIL" and "2 of 22 ground motions unacceptable" in v.reason


def test_a_fragile_pass_is_flagged_not_robust():
    outcomes = suite()
    outcomes[3] = outcome(3, overturned=True, margin=Margin(1.0, [(1.0, None)], 8.0, 10))
    # c_r − 2 %: r8 overturns too → 2 ground motions; c_r + 2 %: r3 survives → 0
    items, v = run(outcomes, sensitivity(44, minus=["r8"], plus=["r3"]))
    assert v.verdict == "PASS" and not v.robust
    assert v.reason.startswith("PASS (ASCE 7-22 §16.4, risk category II): 1 of 22 ground motions unacceptable")
    assert v.reason.endswith("; not robust: fails with c_r − 2 %")
    rob = next(i for i in items if i.key == "restitution_robustness")
    assert not rob.passed and rob.utilisation == pytest.approx(2.0)
    assert rob.perturbations == (("c_r − 2 %", False), ("c_r + 2 %", True))


def test_a_fail_that_a_perturbation_would_pass_is_not_robust():
    outcomes = suite()
    for i in (0, 4):
        outcomes[i] = outcome(i, overturned=True, margin=Margin(1.0, [(1.0, None)], 8.0, 10))
    _, v = run(outcomes, sensitivity(44, minus=["r9"], plus=["r0"]))
    assert v.verdict == "FAIL" and not v.robust and "passes with c_r + 2 %" in v.reason
    _, v = run(outcomes, sensitivity(44, minus=["r9"], plus=["r11"]))
    assert v.verdict == "FAIL" and v.robust and "also fails with c_r − 2 % and c_r + 2 %" in v.reason


def test_ensemble_members_are_further_draws_of_the_count_rule():
    import numpy as np
    outcomes = suite(24)
    rows = np.zeros((3, 24), dtype=bool)
    rows[1, [0, 5]] = True                   # member 2: ground motions gm0 and gm2 → 2 > 1
    rows[2, [0, 1]] = True                   # member 3: both components of gm0 → 1
    ens = {"overturned": rows, "restitution": np.array([1.0, 1.01, 0.99]), "robust": np.ones(24, bool)}
    ctx = CheckContext(outcomes, A, {}, sensitivity(24), True, {"collapse_margin": collapse(2.5), "ensemble": ens})
    items, _ = evaluate_criteria(ctx, criteria_for(ctx.rule))
    item = next(i for i in items if i.key == "ensemble_robustness")
    assert [h for _, h in item.perturbations] == [True, False, True]
    assert "unacceptable ground motions per run 0, 2, 1 of 12" in item.detail


@pytest.mark.parametrize("n,k,limit", [(29, 0, 0.10), (44, 1, 0.10), (100, 3, 0.10), (100, 6, 0.10), (59, 0, 0.05),
                                       (120, 0, 0.025), (4, 0, 0.8)])
def test_binomial_rule_counts_ground_motions_against_scipy(n, k, limit):
    """acceptance = "binomial": trials are ground motions (here pairs of records)."""
    outcomes = [outcome(i, margin=safe_margin()) for i in range(2 * n)]
    for g in range(k):
        outcomes[2 * g] = outcome(2 * g, overturned=True, margin=Margin(1.0, [(1.0, None)], 8.0, 10))
    analysis = AnalysisSettings(acceptance="binomial", overturn_probability_limit=limit,
                                overturn_probability_limit_set=True)
    items, v = run(outcomes, analysis=analysis)
    hi = binomtest(k, n).proportion_ci(confidence_level=0.90, method="exact").high
    assert v.verdict == ("PASS" if hi <= limit else "FAIL")
    gov = {i.key for i in items if i.governs_verdict}
    assert gov == {"analyses_completed", "overturning_probability", "incremental_margin"}
    b = next(i for i in items if i.key == "overturning_probability")
    assert f"{k} of {n} ground motions ({2 * n} records)" in b.detail


def test_binomial_limit_defaults_to_the_category_target():
    rule = CheckContext([], AnalysisSettings(acceptance="binomial", risk_category="IV"), {}).rule
    assert rule.binomial_limit == 0.025 and rule.minimum_ground_motions == 119


def test_nonmonotonic_band_below_design_is_reported_and_counted_by_the_fragility():
    # one record overturns at 0.92× design but survives 1.0×: the count rule (at the design level) does not see
    # it; the fragility's first-crossing capacity does, and the incremental item reports it
    outcomes = suite()
    outcomes[7].margin = Margin(0.9172, [(0.9172, 1.58), (1.9, None)], 8.0, 30)
    items, v = run(outcomes)
    assert v.verdict == "PASS"
    inc = next(i for i in items if i.key == "incremental_margin")
    assert inc.role == "informative" and "overturning at 0.92× design (r7)" in inc.verdict_reason


def test_failed_analyses_are_never_counted_safe():
    outcomes = suite()
    outcomes[5] = outcome(5, status="event limit reached", margin=safe_margin(), theta=0.0)
    items, v = run(outcomes)
    assert v.verdict == "FAIL"
    assert "1 analysis(es) failed (r5 (event limit reached))" in v.reason
    count = next(i for i in items if i.key == "unacceptable_responses")
    assert "(43 records)" in count.detail                   # left out of the statistics


def test_failed_incremental_run_below_design_fails():
    outcomes = suite()
    m = safe_margin()
    m.failed_scales.append(0.6)
    outcomes[2].margin = m
    _, v = run(outcomes)
    assert v.verdict == "FAIL" and "incremental analyses failed" in v.reason and "r2" in v.reason


def test_adding_a_criterion_is_one_class():
    class Drift(Criterion):
        key = "drift"
        name = "superstructure drift"
        role = GOVERNS
        source = "test"

        def evaluate(self, ctx):
            return self.item(1.5, False, "too much drift", "drift 1.5× the limit")

    ctx = CheckContext(suite(), A, {}, sensitivity(44), True, {"collapse_margin": collapse(2.5)})
    items, skipped = evaluate_criteria(ctx, CRITERIA + [Drift])
    v = decide(items, skipped)
    assert v.verdict == "FAIL" and v.reason == "FAIL: drift 1.5× the limit"
    assert items[-1].as_json()["governs_verdict"] is True


def test_a_failed_perturbed_analysis_is_not_robust():
    sens = sensitivity(44)
    sens["runs"]["1.02"]["failed"] = ["r9"]
    items, v = run(suite(), sens)
    assert v.verdict == "PASS" and not v.robust and "fails with c_r + 2 %" in v.reason
    rob = next(i for i in items if i.role == ROBUSTNESS)
    assert "analyses failed: r9" in rob.detail and rob.utilisation > 1.0


def test_polyakov_rule_1_item():
    q = {"omega_s_over_p": SimpleNamespace(value=7.5)}
    items, v = run(suite(), q=q)
    r1 = next(i for i in items if i.key == "polyakov_rule_1")
    assert not r1.passed and r1.utilisation == pytest.approx(10 / 7.5) and r1.role == "informative"
    assert v.verdict == "PASS"                   # informative items do not decide


@pytest.mark.slow
def test_example_verdict_and_fragility_agree(tmp_path):
    """examples/podium_flat.toml: p695-ff/11a overturns at 0.92× design (non-monotonic response) but no record
    overturns at the design level; the fragility built on first overturning intensities gives an ACMR above
    ACMR10% — the verdict is the ASCE 7 rule's PASS, quotes the margin, and the report shows the band."""
    from typer.testing import CliRunner

    from rockdesign.cli import app
    from rockdesign.paths import REPO_ROOT
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["check", str(REPO_ROOT / "examples" / "podium_flat.toml"), "-o", str(out),
                                   "--no-pdf", "--html"])
    data = json.loads((out / "results.json").read_text(encoding="utf-8"))
    acc = data["acceptance"]
    assert res.exit_code == (0 if data["verdict"] == "PASS" else 1), res.output
    assert acc["n_ground_motions"] == 22 == data["summary"]["n_ground_motions"]
    assert acc["risk_category"] == "II" and acc["target_p_collapse"] == 0.10
    cm = data["collapse_margin"]
    assert acc["acmr"] == cm["ACMR"] and acc["p_collapse_design"] == pytest.approx(norm.cdf(-math.log(cm["ACMR"])
                                                                                             / cm["beta_tot"]))
    # verdict and fragility agree: PASS exactly when both governing numbers hold
    ok = acc["n_unacceptable"] <= 1 and cm["ACMR"] >= cm["ACMR_target"]
    assert (data["verdict"] == "PASS") is ok and data["verdict"] in ("PASS", "FAIL")
    assert f"ACMR {cm['ACMR']:.3g}" in data["verdict_reason"]
    inc = next(c for c in data["checks"] if c["criterion"] == "incremental_margin")
    assert "overturning at 0.92× design (p695-ff/11a" in inc["verdict_reason"]
    html = (out / "report.html").read_text(encoding="utf-8")
    assert "ASCE 7-22 §16.4, risk category II" in html and "p695-ff/11" in html
