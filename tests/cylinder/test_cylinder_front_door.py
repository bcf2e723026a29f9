"""The cylinder goes through the front door every kind of structure uses: the same library calls,
the same sections and keys in results.json, the one verdict of criteria.decide."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

import rockdesign as rd
from rockdesign.kinds import kind_of, registered

REPO = Path(__file__).resolve().parents[2]
GOLDEN = REPO / "tests" / "golden" / "data" / "check"

SAFE = """[project]
name = "a column nothing rocks"
[cylinder]
height = "3 m"
slenderness = 0.2
mass = "2 t"
[excitation]
scale = { method = "factor", value = 0.001 }
[analysis]
ensemble_size = 1
"""


@pytest.fixture(scope="module")
def safe_check():
    return rd.check(rd.parse_project(SAFE, name="safe.toml"))


def test_a_design_so_safe_nothing_rocks_is_checked(safe_check):
    """No pair uplifts: no median of an empty list (a crash with exit 3 before), a PASS whose reason
    is the suite bound: 22 pairs with none overturning bound P(overturn) by 1 − 0.05^(1/22) = 0.127."""
    data = safe_check.as_json()
    assert all(r["uplift_time"] is None and r["theta_max_over_alpha"] == 0.0 for r in data["records"])
    assert data["summary"]["median_theta_ratio_3d_over_planar"] is None
    # a stocky cylinder that nothing overturns PASSes on the 22-pair suite: ASCE 7-22 §16.4.1.1 counts
    # ground motions (0 of 22, 1 allowed); the binomial bound 1 − 0.05^(1/22) = 0.127 > 10 % is information
    assert data["verdict"] == "PASS" and data["verdict_robust"] is True
    assert data["verdict_reason"].startswith("PASS (ASCE 7-22 §16.4, risk category II; records multiplied by a "
                                             "factor, not per ASCE 7-22 §16.2): 0 of 22 ground motions "
                                             "unacceptable (1 allowed)")
    bound = 1.0 - 0.05 ** (1.0 / 22)
    info = next(c for c in data["checks"] if c["criterion"] == "binomial_bound")
    assert not info["governs_verdict"] and info["utilisation"] == pytest.approx(bound / 0.1, rel=1e-9)
    assert data["acceptance"]["n_ground_motions"] == 22 and data["acceptance"]["passed"] is True


def test_a_stocky_cylinder_passes_from_the_command_line(tmp_path):
    """Exit 0 on the default 22-pair suite (CONTRACT §6.1)."""
    from typer.testing import CliRunner
    from rockdesign.cli import app
    (tmp_path / "safe.toml").write_text(SAFE)
    r = CliRunner().invoke(app, ["check", str(tmp_path / "safe.toml"), "-o", str(tmp_path / "out"), "--no-pdf",
                                 "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["verdict"] == "PASS"


def test_a_cylinder_suite_below_eleven_ground_motions_is_refused_up_front(monkeypatch):
    """ASCE 7-22 needs 11 ground motions: a 3-pair suite is refused before any analysis (exit 2)."""
    from rockdesign.errors import ProjectError
    from rockdesign.cylinder import pairs
    monkeypatch.setitem(pairs.PAIR_SUITES, "test-three-pairs-refused", ("p695-ff", range(1, 4)))
    project = rd.parse_project(SAFE.replace("[excitation]\n", '[excitation]\nsuites = ["test-three-pairs-refused"]\n'),
                               name="three.toml")
    with pytest.raises(ProjectError) as err:
        rd.check(project)
    assert "11" in str(err.value) and "3" in str(err.value)


def test_the_cylinder_results_have_the_sections_and_keys_of_a_planar_check(safe_check):
    planar = json.loads((GOLDEN / "podium_flat.json").read_text(encoding="utf-8"))
    data = safe_check.as_json()
    assert set(planar) <= set(data), set(planar) - set(data)
    planar_check_keys = set(planar["checks"][0])
    assert all(set(c) == planar_check_keys for c in data["checks"])
    assert {"verdict_reason", "verdict_robust", "failed_records", "sensitivity", "excitation"} <= set(data)
    # each record pair is one ground motion (the acceptance criteria group outcomes by it)
    assert all(r["ground_motion"] == r["id"] for r in data["records"])
    assert {"ensemble_robustness", "unacceptable_responses", "binomial_bound", "analyses_completed"} <= {
        c["criterion"] for c in data["checks"]}


def test_one_registry_entry_per_kind():
    cylinder = rd.load_project(REPO / "examples" / "cylinder.toml")
    pier = rd.load_project(REPO / "examples" / "bridge_pier.toml")
    assert kind_of(cylinder).name == "cylinder" and kind_of(pier).name == "planar"
    assert [k.name for k in registered()] == ["cylinder", "planar"]
    assert rd.design_quantities(cylinder).as_json()["quantities"]["alpha"]["unit"] == "rad"


def test_simulate_a_cylinder_through_the_library():
    """rd.simulate of a cylinder returns its typed result (it raised a TypeError before)."""
    cylinder = rd.load_project(REPO / "examples" / "cylinder.toml")
    r = rd.simulate(cylinder, "free:theta0=0.5alpha", t_end=1.0)
    assert r.as_json()["model"].startswith("cylinder-") and r.t[-1] == pytest.approx(1.0)
    assert r.theta_max == pytest.approx(0.5 * cylinder.system.alpha, rel=1e-6)
