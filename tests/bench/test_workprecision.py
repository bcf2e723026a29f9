"""The work-precision machinery: problems, reference solutions, bench.json (CONTRACT §4), the CLI."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from rockdesign.bench.methods import METHODS, method
from rockdesign.bench.problems import make_problem, problem_set
from rockdesign.bench.reference import build_reference, engine_history_at
from rockdesign.bench.runner import run_study
from rockdesign.jsonable import json_ready
from rockdesign.cli import app
from rockdesign.planar.dynamics.simulate import simulate

POINT_KEYS = ("tolerance", "seconds", "error_theta", "error_theta_max", "error_impact_times")


def assert_contract_bench_json(data: dict) -> None:
    """CONTRACT §4: {"problems": [{"name", "system", "methods": [{"name", "points": [{...}]}]}]}."""
    assert isinstance(data["problems"], list) and data["problems"]
    for prob in data["problems"]:
        assert isinstance(prob["name"], str) and isinstance(prob["system"], str)
        assert isinstance(prob["methods"], list) and prob["methods"]
        for m in prob["methods"]:
            assert isinstance(m["name"], str)
            assert isinstance(m["points"], list)
            for p in m["points"]:
                for k in POINT_KEYS:
                    assert isinstance(p[k], (int, float)) and not isinstance(p[k], bool), (prob["name"], m["name"], k)
                    assert math.isfinite(p[k]) and p[k] >= 0.0
                assert p["tolerance"] > 0 and p["seconds"] > 0


def test_problem_set_covers_three_excitations_and_three_systems():
    probs = problem_set(quick=True)
    exact = {(p.name, p.system_name) for p in probs if p.equations == "exact"}
    assert len(exact) == 9
    assert {s for _, s in exact} == {"housner-block", "curved-block", "podium-2dof"}
    linear = [p for p in probs if p.equations == "linear"]
    assert len(linear) == 6 and all(p.closed_form for p in linear)
    rec = make_problem("record-30s", "housner-block")
    assert rec.motion.is_record and 29.9 < rec.motion.duration < 30.1 and rec.t_end == 35.0


@pytest.mark.parametrize("excitation,system,model", [("ricker-anti", "podium-2dof", "exact"),
                                                      ("free-vibration", "podium-2dof", "exact"),
                                                      ("record-30s", "curved-block", "linear")])
def test_history_at_reproduces_simulate_at_its_own_times(excitation, system, model):
    # the reference evaluator sets the kernel up exactly as simulate() does
    p = make_problem(excitation, system, "linear" if model == "linear" else "exact", quick=True)
    r = simulate(p.system, p.motion, model=model, structure=p.structure, t_end=p.t_end, theta0=p.theta0)
    th = engine_history_at(p, r.t, model=model, rtol=1e-10, atol=1e-12)
    assert np.max(np.abs(th - r.theta)) < 1e-12


def test_references_and_their_bounds():
    cf = build_reference(make_problem("free-vibration", "curved-block", "linear"))
    assert cf.kind == "closed-form" and cf.impacts > 3
    assert all(c["theta"] < 1e-10 and c["overturn_agrees"] for c in cf.checks.values())
    conv = build_reference(make_problem("ricker-anti", "housner-block"), independent_check=True)
    assert conv.kind == "converged"
    assert set(conv.checks) == {"rockdesign rtol=1e-12", "scipy DOP853 rtol=1e-13"}
    assert 0.0 < conv.error_bound["theta"] < 1e-9
    assert conv.theta_max == pytest.approx(0.801 * math.atan(0.15), rel=1e-3)


def test_methods_registry():
    names = [m.name for m in METHODS]
    assert names == ["rockdesign", "rockdesign linear-exact", "rockdesign DP5(4)", "rockdesign DOP853",
                     "scipy RK45", "scipy DOP853", "scipy LSODA", "scipy Radau"]
    le = method("rockdesign linear-exact")
    assert not le.has_tolerance
    assert le.applies(make_problem("ricker-anti", "housner-block"))
    assert not le.applies(make_problem("ricker-anti", "podium-2dof"))
    assert not le.applies(make_problem("ricker-anti", "housner-block", "linear"))


def test_quick_study_on_a_reduced_set_gives_contract_json():
    probs = [make_problem("free-vibration", "housner-block"), make_problem("free-vibration", "curved-block", "linear")]
    study = run_study(quick=True, problems=probs, methods=[method("rockdesign"), method("rockdesign linear-exact"),
                                                           method("scipy DOP853")], tolerances=(1e-4, 1e-8))
    data = json.loads(json.dumps(json_ready(study)))
    assert_contract_bench_json(data)
    ours = next(m for m in data["problems"][0]["methods"] if m["name"] == "rockdesign")
    errs = [p["error_theta"] for p in ours["points"]]
    assert errs[1] < errs[0]                      # tighter tolerance, smaller error
    assert all(p["overturn_agrees"] for p in ours["points"])
    lin = data["problems"][1]
    assert lin["reference"]["kind"] == "closed-form"
    assert [m["name"] for m in lin["methods"]] == ["rockdesign", "scipy DOP853"]
    assert data["machine"]["nproc"] >= 1 and data["machine"]["date"]


@pytest.mark.slow
def test_cli_bench_quick_writes_json_and_figures(tmp_path):
    out = tmp_path / "bench"
    only = "free-vibration/curved-block,free-vibration-linearized/curved-block"
    result = CliRunner().invoke(app, ["bench", "--quick", "--only", only, "--no-stability", "-o", str(out)])
    assert result.exit_code == 0, result.output
    data = json.loads((out / "bench.json").read_text())
    assert_contract_bench_json(data)
    assert {p["name"] for p in data["problems"]} == {"free-vibration", "free-vibration-linearized"}
    for stem in ("wp_free-vibration_curved-block", "wp_overview_exact", "wp_overview_linear"):
        assert (out / f"{stem}.png").stat().st_size > 1000
        assert (out / f"{stem}.svg").stat().st_size > 1000
    assert "Work-precision highlights" in result.output


def test_cli_bench_rejects_an_unknown_problem(tmp_path):
    result = CliRunner().invoke(app, ["bench", "--quick", "--only", "no-such-problem", "-o", str(tmp_path)])
    assert result.exit_code == 2
    assert "--only" in result.output
