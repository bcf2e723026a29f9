"""Ch. 7 statistics against independent computations (scipy.stats, brute force, closed forms)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy import stats
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.experiments.free_vibration import ExperimentError
from rockdesign.experiments.validate import (MixedSample, dkw_epsilon, evidence, kolmogorov_distance,
                                             proportions_test, read_results_csv, split_tests, table_7_2, validate)

RNG = np.random.default_rng(2024)
TESTS = np.concatenate([RNG.gamma(2.0, 0.2, 41), np.full(9, np.inf)])       # 9 of 50 overturned
MODEL = np.concatenate([RNG.gamma(2.2, 0.2, 44), np.full(6, np.inf)])


def _brute_ks(a, b):
    grid = np.concatenate([a, b])
    return max(abs(np.mean(a <= x) - np.mean(b <= x)) for x in grid)


def test_ks_and_kolmogorov_distance():
    a, b = MixedSample("a", TESTS), MixedSample("b", MODEL)
    ref = stats.ks_2samp(a.conditional, b.conditional)
    from rockdesign.experiments.validate import ks_test
    res = ks_test(a, b)
    assert res["statistic"] == pytest.approx(_brute_ks(a.conditional, b.conditional), abs=1e-12)
    assert res["p_value"] == pytest.approx(ref.pvalue, rel=1e-12)
    # mixed CDFs: the overturned mass sits at +∞, so the distance counts it at every finite x
    grid = np.concatenate([a.conditional, b.conditional])
    brute = max(abs(np.sum(TESTS <= x) / 50 - np.sum(MODEL <= x) / 50) for x in grid)
    assert kolmogorov_distance(a, b) == pytest.approx(brute, abs=1e-12)


def test_proportions_equal_pooled_z_test():
    a, b = MixedSample("a", TESTS), MixedSample("b", MODEL)
    p1, p2, n1, n2 = 9 / 50, 6 / 50, 50, 50
    pooled = (9 + 6) / 100
    z = (p1 - p2) / math.sqrt(pooled * (1 - pooled) * (1 / n1 + 1 / n2))
    res = proportions_test(a, b)
    assert res["z"] == pytest.approx(z, rel=1e-10)
    assert res["p_value"] == pytest.approx(2 * stats.norm.sf(abs(z)), rel=1e-10)
    assert res["statistic"] == pytest.approx(p1 - p2)
    none = MixedSample("none", np.array([0.1, 0.2, 0.3]))
    assert proportions_test(none, none)["p_value"] == 1.0


def test_table_7_2_percentiles_and_conditional_moments():
    row = table_7_2(MixedSample("t", TESTS))
    ordered = np.sort(TESTS)
    for q in (25, 50, 75):   # inverse empirical CDF: the ⌈q n⌉-th smallest value
        expected = ordered[math.ceil(q / 100 * 50) - 1]
        assert (row[str(q)] is None) if math.isinf(expected) else row[str(q)] == pytest.approx(expected)
    finite = TESTS[np.isfinite(TESTS)]
    assert row["conditional_mean"] == pytest.approx(stats.tmean(finite))
    assert row["conditional_sd"] == pytest.approx(stats.tstd(finite))
    heavy = MixedSample("h", np.concatenate([np.ones(6), np.full(4, np.inf)]))
    assert table_7_2(heavy)["75"] is None                  # "OT": the 75th percentile is an overturning


def test_dkw_band_width_and_coverage():
    assert dkw_epsilon(100, 0.10) == pytest.approx(math.sqrt(math.log(20.0) / 200.0))
    assert dkw_epsilon(600, 0.05) == pytest.approx(0.05544, abs=1e-5)
    # the 90 % band covers the true CDF in at least 90 % of repeated samples (DKW is conservative)
    rng = np.random.default_rng(7)
    n, hits = 60, 0
    for _ in range(400):
        s = MixedSample("s", rng.uniform(size=n))
        x = np.sort(s.values)
        eps = s.dkw_epsilon(0.10)
        below = np.arange(1, n + 1) / n       # F_n at x_i and just before it
        if np.all(np.abs(below - x) <= eps) and np.all(np.abs(below - 1 / n - x) <= eps):
            hits += 1
    assert hits / 400 >= 0.90


def test_evidence_words():
    assert evidence(0.005) == "very strong against H0"
    assert evidence(0.03) == "strong against H0"
    assert evidence(0.07) == "medium-weak against H0"
    assert evidence(0.4) == "small or none against H0"


def test_split_reproducible():
    s = MixedSample("t", TESTS)
    d1, d2 = split_tests(s, 11)
    assert np.array_equal(d1, split_tests(s, 11)[0]) and np.array_equal(d2, split_tests(s, 11)[1])
    assert not np.array_equal(d1, split_tests(s, 12)[0])
    assert sorted(np.concatenate([d1, d2]).tolist()) == list(range(50)) and len(d1) == 25
    r1, r2 = validate(s, MixedSample("m", MODEL), seed=3), validate(s, MixedSample("m", MODEL), seed=3)
    assert r1.as_json() == r2.as_json()


def _write(path, values, ids=True):
    with open(path, "w") as fh:
        fh.write("id,theta_max_over_alpha,overturned\n")
        for k, v in enumerate(values):
            fh.write(f"r{k},{'1.2' if math.isinf(v) else v},{str(math.isinf(v)).lower()}\n")
    return path


def test_csv_reading(tmp_path):
    s = read_results_csv(_write(tmp_path / "a.csv", TESTS), "tests")
    assert s.n == 50 and s.n_overturned == 9 and s.ids[0] == "r0"
    (tmp_path / "b.csv").write_text("theta_max_over_alpha\n0.3\ninf\nOT\n0.5\n")
    assert read_results_csv(tmp_path / "b.csv", "x").n_overturned == 2
    (tmp_path / "c.csv").write_text("id,theta\n1,0.3\n")
    with pytest.raises(ExperimentError, match="missing column"):
        read_results_csv(tmp_path / "c.csv", "x")
    (tmp_path / "d.csv").write_text("theta_max_over_alpha\n0.3\n-1\n")
    with pytest.raises(ExperimentError, match="invalid"):
        read_results_csv(tmp_path / "d.csv", "x")


def test_model_runs_matched_by_id(tmp_path):
    tests = read_results_csv(_write(tmp_path / "t.csv", TESTS), "tests")
    model = read_results_csv(_write(tmp_path / "m.csv", MODEL[::-1]), "analyses")
    model.ids = model.ids[::-1]            # same motions, other row order
    result = validate(tests, model, seed=5)
    assert result.pairing == "id"
    d2 = result.split[1]
    stage2 = proportions_test(tests.subset(result.split[0], "d1"), MixedSample("m", MODEL[d2]))
    assert result.proportions[1]["p_value"] == pytest.approx(stage2["p_value"])


def test_cli_json_and_report(tmp_path):
    t = _write(tmp_path / "tests.csv", TESTS)
    m = _write(tmp_path / "analyses.csv", MODEL)
    runner = CliRunner()
    res = runner.invoke(app, ["validate", "--tests", str(t), "--analyses", str(m), "--analyses-measured-cr", str(m),
                              "--seed", "4", "--json", "-o", str(tmp_path / "out"), "--no-pdf",
                              "--plot", str(tmp_path / "cdf.svg")])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert {"n_tests", "n_analyses", "p_overturn_tests", "p_overturn_analyses", "kolmogorov_distance",
            "proportions", "ks", "percentiles"} <= set(data)
    assert [r["stage"][0] for r in data["ks"]] == ["1", "2", "3"]
    html = (tmp_path / "out" / "report.html").read_text()
    assert "Table 7.2" in html and "Kolmogorov" in html and "data:image/svg+xml" in html
    assert (tmp_path / "out" / "validation.png").exists() and (tmp_path / "cdf.svg").exists()
    res = runner.invoke(app, ["validate", "--tests", str(tmp_path / "missing.csv"), "--analyses", str(m)])
    assert res.exit_code == 2 and "Traceback" not in res.output


def test_pdf_report(tmp_path):
    pypdf = pytest.importorskip("pypdf")
    from rockdesign.experiments.validate_report import write_validation
    result = validate(MixedSample("tests", TESTS), MixedSample("analyses", MODEL), seed=2)
    written = write_validation(result, tmp_path, {"tests": "t.csv", "analyses": "m.csv"}, title="fixed samples")
    text = "".join(page.extract_text() for page in pypdf.PdfReader(written["pdf"]).pages)
    assert "Kolmogorov" in text and "Table 7.2" in text and "small or none" in text
    assert json.loads((tmp_path / "validation.json").read_text()) == json.loads(json.dumps(result.as_json()))
