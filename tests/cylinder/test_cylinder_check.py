"""``check`` for a cylinder: statistics over the far-field pairs, the planar comparison, excitation errors."""
from __future__ import annotations

import json

import numpy as np
import pytest
from scipy import stats
from scipy.stats import binomtest
from typer.testing import CliRunner

from casedata import expected
from rockdesign.cylinder.check import planar_block
from rockdesign.cli import app
from rockdesign.cylinder.engine import simulate_cylinder
from rockdesign.errors import ProjectError
from rockdesign.cylinder.pairs import load_pair
from rockdesign.kinds import parse_document as parse_project

runner = CliRunner()
TOML = ('[project]\nname = "check cylinder"\n[cylinder]\nheight = "3 m"\nslenderness = 0.2\nmass = "2 t"\n'
        '[excitation]\nscale = { method = "resultant_pga", target = "0.3 g" }\n')


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    d = tmp_path_factory.mktemp("cyl")
    p = d / "cyl.toml"
    p.write_text(TOML)
    r = runner.invoke(app, ["check", str(p), "-o", str(d / "out"), "--json"])
    assert r.exit_code in (0, 1), r.output
    data = json.loads(r.stdout)
    assert r.exit_code == (0 if data["verdict"] == "PASS" else 1)
    assert (d / "out" / "results.csv").exists() and (d / "out" / "cylinder_vs_planar.png").exists()
    assert (d / "out" / "wobbling_period.png").exists()
    return data


@pytest.mark.slow   # the module fixture is a full cylinder check (≈ 20 s)
def test_statistics_are_clopper_pearson_over_22_pairs(result):
    s = result["summary"]
    assert s["n_records"] == 22 and len(result["records"]) == 22
    k = sum(r["overturned"] for r in result["records"])
    assert s["n_overturned"] == k and s["p_overturn"] == pytest.approx(k / 22)
    ci = binomtest(k, 22).proportion_ci(0.90, method="exact")
    assert s["p_overturn_ci90"] == pytest.approx([ci.low, ci.high], abs=1e-12)
    assert all(r["resultant_pga"] == pytest.approx(0.3 * 9.81, rel=1e-12) for r in result["records"])
    assert s["difference_p_overturn"] == pytest.approx(s["p_overturn"] - s["planar"]["p_overturn"])
    # the verdict is criteria.decide's: every analysis completed and the ASCE 7-22 §16.4.1.1 count over the
    # pairs (each one ground motion), at the design level and on the first overturning intensity
    gov = {c["criterion"]: c for c in result["checks"] if c["governs_verdict"]}
    assert set(gov) == {"analyses_completed", "unacceptable_responses", "incremental_margin", "collapse_margin"}
    assert result["acceptance"]["method"] == "asce7" and result["acceptance"]["n_ground_motions"] == 22
    assert result["acceptance"]["n_unacceptable"] == k
    assert result["verdict"] == ("PASS" if all(c["passed"] for c in gov.values()) else "FAIL")
    assert result["verdict_reason"].startswith(result["verdict"])


@pytest.mark.slow   # the module fixture is a full cylinder check (≈ 20 s)
def test_one_row_reproduces_simulate(result):
    row = next(r for r in result["records"] if r["id"] == "p695-ff/12")
    proj = parse_project({"project": {"name": "x"}, "cylinder": {"height": "3 m", "slenderness": 0.2,
                                                                "mass": "2 t"}})
    pair = load_pair("p695-ff/12")
    a = proj.analysis          # the check integrates at the project's tolerances (default rtol 1e-8)
    r = simulate_cylinder(proj.system, pair.scaled(row["scale"]), rtol=a.rtol, atol=a.atol,
                          rest_velocity=a.rest_velocity)
    assert row["theta_max_over_alpha"] == pytest.approx(r.theta_max / proj.system.alpha, rel=1e-12)
    assert row["quasi_impacts"] == r.quasi_impacts
    # the planar model is the block of equal inertia with Eq 5.41's restitution
    block = planar_block(proj.system)
    assert block.column.mass_distribution == pytest.approx((3 + np.cos(proj.system.alpha) ** 2) / 12)
    assert block.restitution == pytest.approx(expected("eq5.41") ** 2, abs=2e-5)


@pytest.mark.slow   # the module fixture is a full cylinder check (≈ 20 s)
def test_margins_below_the_design_level_are_real(result):
    """Each overturning factor ≤ 1 the scan reports overturns the cylinder when analysed alone (at the
    scan's tolerance); a pair without one does not overturn at the design level; the incremental
    criterion counts exactly the pairs overturning at some factor ≤ 1."""
    proj = parse_project({"project": {"name": "x"}, "cylinder": {"height": "3 m", "slenderness": 0.2,
                                                                "mass": "2 t"}})
    a = proj.analysis
    rows = [r for r in result["records"] if r["overturn_scale"] is not None and r["overturn_scale"] <= 1.0]
    assert rows, "the 0.3 g suite has pairs that overturn at or below the design level"
    # the scan goes on past the first overturning factor (safe-again bands), up to margin_max_scale at most
    top = result["settings"]["margin_max_scale"]
    assert all(r["overturn_scale"] < r["margin_scanned_up_to"] <= top * (1 + 1e-12) for r in rows)
    assert all(r["overturn_intervals"][0][0] == r["overturn_scale"] for r in rows)
    for r in rows[:3]:
        pair = load_pair(r["id"]).scaled(r["scale"] * r["overturn_scale"])
        run = simulate_cylinder(proj.system, pair, rtol=max(a.rtol, a.scan_rtol), atol=a.atol,
                                rest_velocity=a.rest_velocity)
        assert run.overturned, r["id"]
    assert all(r["overturn_scale"] is not None for r in result["records"] if r["overturned"])
    inc = next(c for c in result["checks"] if c["criterion"] == "incremental_margin")
    assert inc["detail"].startswith(f"{len(rows)} of 22 record pairs overturn at some intensity")


@pytest.mark.slow   # the module fixture is a full cylinder check (≈ 20 s)
def test_fragility_and_collapse_margin_of_the_pairs(result):
    """One acceptance for every kind: each pair's capacity is its first overturning factor times its
    design-level resultant PGA (censored at margin_max_scale); the fragility against scipy on these
    capacities, Ŝ_CT counted (FEMA P695 §6.4) against numpy's inverted-CDF quantile, and the margin at the
    risk category's target governs."""
    f, cm, acc = result["fragility"], result["collapse_margin"], result["acceptance"]
    rows = result["records"]
    first = [1.0 if r["overturned"] and (r["overturn_scale"] is None or r["overturn_scale"] > 1.0)
             else r["overturn_scale"] for r in rows]
    top = result["settings"]["margin_max_scale"]
    x = np.array([(s if s is not None else top) * r["resultant_pga"] for s, r in zip(first, rows)])
    cens = np.array([s is None for s in first])
    assert f["im"] == "resultant_pga" and f["unit"] == "m/s^2" and f["n_censored"] == int(cens.sum())
    assert [c["capacity"] for c in f["capacities"]] == pytest.approx(list(x), rel=1e-12)
    assert f["design_intensity"] == pytest.approx(0.3 * 9.81, rel=1e-12)
    if cens.any():
        mu, sigma = stats.norm.fit(stats.CensoredData.right_censored(np.log(x), cens))
    else:
        mu, sigma = np.log(x).mean(), np.log(x).std(ddof=1)
    assert f["median"] == pytest.approx(np.exp(mu), rel=1e-4) and f["beta"] == pytest.approx(sigma, rel=1e-3)
    counted = float(np.quantile(np.where(cens, np.inf, x), 0.5, method="inverted_cdf"))
    assert cm["median_definition"] == "counted" and cm["median_capacity"] == pytest.approx(counted, rel=1e-12)
    acmr = counted / (0.3 * 9.81)
    need = np.exp(-0.525 * stats.norm.ppf(0.10))
    assert acc["acmr"] == pytest.approx(acmr, rel=1e-12) and acc["acmr_required"] == pytest.approx(need, rel=1e-12)
    assert acc["p_collapse_design"] == pytest.approx(stats.norm.cdf(-np.log(acmr) / 0.525), rel=1e-9)
    assert acc["acmr_fitted"] == pytest.approx(np.exp(mu) / (0.3 * 9.81), rel=1e-4)
    assert acc["median_definition"] == "counted" and "collapse margin" in acc["method_label"]
    item = next(c for c in result["checks"] if c["criterion"] == "collapse_margin")
    assert item["governs_verdict"] and item["passed"] is bool(acmr >= need)


def test_a_cylinder_refuses_a_planar_intensity_measure():
    """The fragility of a pair is in its resultant PGA: fragility_im and fragility_period are refused."""
    with pytest.raises(ProjectError) as err:
        parse_project({"project": {"name": "x"}, "cylinder": {"height": "3 m", "slenderness": 0.2, "mass": "2 t"},
                       "analysis": {"fragility_im": "sa", "fragility_period": "1 s"}}, file="c.toml")
    assert err.value.key == "analysis.fragility_im" and "resultant PGA" in str(err.value)


@pytest.mark.parametrize("excitation, key", [
    ({"scale": {"method": "sdmax", "target": "0.2 m"}}, "excitation.scale"),
    ({"suites": ["p695-farfield"]}, "excitation.suites"),
    ({"scale": {"method": "resultant_pga", "target": "0.3"}}, "excitation.scale.target"),
    ({"spectrum": "ec8"}, "excitation.spectrum"),
])
def test_excitation_errors(excitation, key):
    """[excitation] is parsed once, at load: every command refuses the same input."""
    with pytest.raises(ProjectError) as err:
        parse_project({"project": {"name": "x"}, "cylinder": {"height": "3 m", "slenderness": 0.2, "mass": "2 t"},
                       "excitation": excitation}, file="c.toml")
    assert err.value.key == key and err.value.file == "c.toml"


BAD_TARGET = """[project]
name = "bad target"
[cylinder]
height = "3 m"
slenderness = 0.2
mass = "2 t"
[excitation]
scale = { method = "resultant_pga", target = "0.3" }
"""


@pytest.mark.parametrize("command", [["quantities"], ["quantities", "--json"],
                                     ["simulate", "--motion", "free:theta0=0.5alpha"], ["check", "--no-pdf"]])
def test_a_bad_scale_target_fails_every_command(tmp_path, command):
    """A cylinder's [excitation] is validated by quantities and simulate as by check: exit 2, one message."""
    from typer.testing import CliRunner

    from rockdesign.cli import app
    path = tmp_path / "bad.toml"
    path.write_text(BAD_TARGET, encoding="utf-8")
    args = [command[0], str(path), *command[1:]] + (["-o", str(tmp_path / "out")] if command[0] == "check" else [])
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 2, result.output
    assert "excitation.scale.target" in result.output and "Traceback" not in result.output


def test_default_scaling_is_one_and_a_half_uplift():
    proj = parse_project({"project": {"name": "x"}, "cylinder": {"height": "3 m", "slenderness": 0.2, "mass": "2 t"}})
    e = proj.excitation
    assert e.suites == ("p695-farfield-pairs",) and e.method == "resultant_pga" and e.default_used
    assert e.target == pytest.approx(1.5 * 9.81 * 0.2)
