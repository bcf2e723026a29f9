"""The design check: classification, statistics and margins on constructed cases with known answers,
and the ``check`` command's outputs, exit codes and input errors (thesis Fig 4.9, Sec 2.2)."""
from __future__ import annotations

import json
import math
import textwrap

import pytest
from scipy.stats import binomtest
from typer.testing import CliRunner

from rockdesign.planar.checks.margins import overturning_margins
from rockdesign.planar.checks.polyakov import PolyakovRule, classify
from rockdesign.acceptance.statistics import empirical_cdf, overturning_probability
from rockdesign.cli import app
from rockdesign.planar.dynamics.model import ModelChoice
from rockdesign.motions.motion import pulse_motion
from support import G, block_from_p, stocky_podium_toml

runner = CliRunner()


@pytest.mark.parametrize("x,y,ot,expected", [
    (0.5, 0.3, False, "a1"), (0.5, 0.5, False, "a1"), (0.5, 0.7, False, "a2"), (0.8, 0.2, True, "b"),
    (0.8, 1.3, False, "b"), (1.2, 0.6, False, "c"), (1.0, 0.99, False, "c"), (1.5, 0.4, True, "d"), (2.0, 3.0, True, "d"),
])
def test_fig_4_9_classes(x, y, ot, expected):
    assert classify(x, y, ot) == expected


def test_polyakov_rule():
    rule = PolyakovRule(0.45)
    assert rule.utilisation(0.36) == pytest.approx(0.8)       # thesis A3: 0.36 m / 0.45 m = 0.80
    assert rule.predicted_scale(0.36) == pytest.approx(1.25)


@pytest.mark.parametrize("k,n", [(0, 44), (3, 44), (44, 44), (7, 21)])
def test_overturning_probability_against_scipy(k, n):
    p, lo, hi = overturning_probability(k, n, 0.90)
    ci = binomtest(k, n).proportion_ci(confidence_level=0.90, method="exact")
    assert p == pytest.approx(k / n)
    assert lo == pytest.approx(ci.low, abs=1e-12) and hi == pytest.approx(ci.high, abs=1e-12)


def test_empirical_cdf():
    x, f = empirical_cdf([0.3, 0.1, 0.2])
    assert list(x) == [0.1, 0.2, 0.3] and list(f) == pytest.approx([1 / 3, 2 / 3, 1.0])


def test_margins_find_the_zhang_makris_bands():
    # Sec 2.2: linearized block (α = 0.25, c_r = 0.81, p = 2.14), one-sine pulse ω_p/p = 5, dynamic
    # overturning. Overturning for a_p/(αg) in [3.0186, 6.3181) and above 7.1681. With a design-level
    # pulse of 2αg the margin is 3.0186/2 = 1.5093, safe again from 3.159, overturning again from 3.584.
    s = block_from_p(2.14, math.tan(0.25)).with_restitution(0.81)
    motion = pulse_motion("sine", 2.0 * 0.25 * G, 2 * math.pi / (5 * 2.14))
    [m] = overturning_margins(s, ModelChoice("block", "linear"), [motion], uplift_factors=[0.5], max_scale=8.0,
                              precision=0.01, rtol=1e-10, atol=1e-12, free_vibration=10.0, criterion="dynamic",
                              rest_velocity=5e-4)
    assert m.overturn_scale == pytest.approx(3.0186 / 2, rel=0.01)
    assert m.overturn_scale >= 3.0186 / 2 - 1e-9      # the reported factor does overturn
    assert len(m.intervals) == 2
    first, second = m.intervals
    assert first[1] == pytest.approx(6.3181 / 2, rel=0.2)     # band edges beyond the first: scan resolution
    assert second[0] == pytest.approx(7.1681 / 2, rel=0.2) and second[1] is None


# ----------------------------------------------------------------------------------------- CLI


def _write(tmp_path, text, name="p.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def test_check_pass_exit_code_and_outputs(tmp_path):
    path = _write(tmp_path, stocky_podium_toml(pga="0.1 g"))
    out = tmp_path / "out"
    result = runner.invoke(app, ["check", str(path), "-o", str(out), "--no-pdf", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["verdict"] == "PASS"
    assert (out / "results.json").exists() and (out / "results.csv").exists()
    assert json.loads((out / "results.json").read_text()) == data
    rec = data["records"][0]
    for key in ("id", "scale", "pga", "sd_max", "polyakov_ratio", "theta_max_over_alpha", "u_B_max_over_2B",
                "impacts", "overturned", "class", "overturn_scale", "polyakov_scale"):
        assert key in rec
    assert rec["pga"] == pytest.approx(0.1 * G, rel=1e-12)
    for key in ("n_records", "n_overturned", "n_false_negative", "classes", "median_margin"):
        assert key in data["summary"]
    assert data["model"]["chosen"] == "rigid-superstructure/linear" or data["model"]["chosen"].startswith("rigid")
    # superstructure demand (CONTRACT §6.2): a rigid superstructure has none; the cap beam is reported
    sup = data["summary"]["superstructure"]
    assert set(sup) >= {"n_records", "shear_coefficient", "drift", "force_ratio", "uplift_base_shear_coefficient",
                        "note", "cap_beam"}
    assert "declared rigid" in sup["note"] and sup["shear_coefficient"]["median"] is None
    assert rec["superstructure"] is None and set(rec["cap_beam"]) == {"acceleration_max", "velocity_jump_max"}
    assert sup["n_records"] == sum(not r["overturned"] for r in data["records"])
    # rerun: identical JSON
    again = runner.invoke(app, ["check", str(path), "-o", str(tmp_path / "out2"), "--no-pdf", "--json"])
    assert json.loads(again.stdout) == data


def test_check_fail_exit_code(tmp_path):
    path = _write(tmp_path, stocky_podium_toml(pga="1.2 g"))
    result = runner.invoke(app, ["check", str(path), "-o", str(tmp_path / "o"), "--no-pdf", "--no-margins"])
    assert result.exit_code == 1, result.output
    assert "FAIL" in result.output


@pytest.mark.parametrize("excitation,key", [
    ('[excitation]\nsuites = ["p695-farfeld"]\ndesign_pga = "0.3 g"\n', "p695-farfeld"),
    ('[excitation]\ndesign_pga = "0.3 kg"\n', "excitation.design_pga"),
    ('[excitation]\ndesing_pga = "0.3 g"\n', "design_pga"),
    ('[excitation]\nrecords = ["p695-ff/11a"]\nscale = { method = "pgv", target = "0.3 g" }\n', "excitation.scale"),
])
def test_bad_excitation_entries(tmp_path, excitation, key):
    text = stocky_podium_toml(pga="0.1 g")
    text = text[:text.index("[excitation]")] + excitation + "\n[analysis]\noverturn = \"static\"\n"
    result = runner.invoke(app, ["check", str(_write(tmp_path, text)), "-o", str(tmp_path / "o"), "--no-pdf"])
    assert result.exit_code == 2, result.output
    assert key in " ".join(result.output.split())
    assert "Traceback" not in result.output


def test_check_without_excitation_needs_design_pga(tmp_path):
    text = stocky_podium_toml(pga="0.1 g")
    text = text[:text.index("[excitation]")] + "[analysis]\noverturn = \"static\"\n"
    result = runner.invoke(app, ["check", str(_write(tmp_path, text)), "--no-pdf"])
    assert result.exit_code == 2
    assert "design_pga" in result.output


@pytest.mark.slow
def test_check_on_dask_equals_local(tmp_path, dask_cluster):
    # the same executor as rocking spectra (dask.distributed LocalCluster): identical results.json
    path = _write(tmp_path, stocky_podium_toml(pga="0.35 g"))
    local = runner.invoke(app, ["check", str(path), "-o", str(tmp_path / "a"), "--no-pdf", "--json"])
    dask = runner.invoke(app, ["check", str(path), "-o", str(tmp_path / "b"), "--no-pdf", "--json", "--dask", dask_cluster.scheduler_address])
    assert local.exit_code in (0, 1) and dask.exit_code == local.exit_code, dask.output
    assert json.loads(dask.stdout) == json.loads(local.stdout)


def test_superstructure_demand_from_2dof_when_overturning_uses_the_rigid_model():
    """CONTRACT §6.2: with the rigid-superstructure model chosen, the demand comes from a 2DOF run of the same
    records; the per-record keys are exact and the statistics run over the records that did not overturn."""
    import math
    from rockdesign.planar.checks.demand import superstructure_demand
    from rockdesign.planar.checks.runner import run_jobs
    from rockdesign.planar.dynamics.model import ModelChoice
    from rockdesign.library import parse_project
    from rockdesign.planar.checks.check import check_records
    from pathlib import Path
    p = parse_project((Path(__file__).resolve().parents[2] / "examples" / "podium_flat.toml").read_text())
    motions = [r.motion for r in check_records(p).records[:6]]
    kw = dict(rtol=1e-8, atol=1e-10, free_vibration=10.0, criterion="static", rest_velocity=5e-4)
    rigid = ModelChoice("rigid-superstructure", "exact")
    runs = run_jobs(p.system, rigid, motions, [1.0] * 6, **kw)
    per, caps, summary, demand_runs = superstructure_demand(p.system, rigid, motions, runs, kw,
                                                            G * math.tan(math.atan(0.15)))
    assert caps == [None] * 6 and all(d is not None for d in per)
    direct = run_jobs(p.system, ModelChoice("podium-2dof", "exact"), motions, [1.0] * 6, **kw)
    for d, r in zip(per, direct):
        assert set(d) == {"acceleration_max", "shear_coefficient_max", "drift_max", "fixed_base_acceleration_max",
                          "force_ratio", "model"}
        assert d["acceleration_max"] == r.superstructure_acceleration_max
        assert d["force_ratio"] == pytest.approx(d["acceleration_max"] / d["fixed_base_acceleration_max"], rel=1e-12)
    assert "rigid superstructure" in summary["note"]
    assert summary["n_overturned_2dof"] == sum(r.overturned for r in direct)
    ok = [i for i in range(6) if not direct[i].overturned and not runs[i].overturned]
    assert summary["n_records"] == len(ok)
    assert summary["shear_coefficient"]["max"] == pytest.approx(max(per[i]["shear_coefficient_max"] for i in ok))
