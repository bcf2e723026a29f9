"""Construction tolerance of the varied keys (SPEC §15, CONTRACT §8.1, rockdesign.design_space.tolerance): the
defaults, the project table and the option, bad input refused naming its key, and the neighbours of a design."""
from __future__ import annotations

import tomllib

import pytest
from typer.testing import CliRunner

import rockdesign as rd
from support import stocky_podium_toml
from rockdesign.cli.app import app
from rockdesign.design_space.recommend import neighbourhood_of
from rockdesign.design_space.tolerance import default_tolerance, parse_tolerance, tolerances
from rockdesign.design_space.variants import parse_vary
from rockdesign.errors import ProjectError, RockdesignError

runner = CliRunner()
CURVED = "examples/podium_curved.toml"


def _vars(raw, *specs):
    from rockdesign.planar.kind import Planar
    return [parse_vary(s, raw, alternatives=Planar.key_alternatives) for s in specs]


def test_defaults_by_the_keys_dimension():
    raw = tomllib.loads(open(CURVED, encoding="utf-8").read())
    width, curvature, columns, period = _vars(raw, "podium.width=0.3m:0.6m:3", "podium.curvature=0.1:0.5:3",
                                               "podium.columns=30:40:2", "superstructure.period=0.3s:0.5s:2")
    assert default_tolerance(width).relative == 0.01                 # a length: ±1 %
    assert default_tolerance(curvature).relative == 0.02             # a dimensionless shape key: ±2 %
    assert default_tolerance(period).relative == 0.02                # any other quantity: ±2 %
    assert default_tolerance(columns).absolute == 0.0                # a whole number is built exactly
    # ±1 % of 0.4 m is 4 mm; an absolute tolerance in the key's units, any length unit
    assert default_tolerance(width).plus_minus(0.4) == pytest.approx(0.004)
    assert parse_tolerance("4 mm", width, key="tolerance", source="option").plus_minus(0.4) == pytest.approx(0.004)
    assert parse_tolerance("0.5 cm", width, key="tolerance", source="option").absolute == pytest.approx(0.005)
    assert parse_tolerance("0.01", curvature, key="tolerance", source="option").absolute == pytest.approx(0.01)
    assert parse_tolerance("5 %", curvature, key="tolerance", source="option").relative == pytest.approx(0.05)


@pytest.mark.parametrize("value, words", [("4 s", "wrong units"), ("-1%", "out of range"), ("60%", "out of range"),
                                          ("abc", "cannot read"), ("-2 mm", "out of range"), ("4", "wrong units"),
                                          ("inf mm", "cannot read"), (True, "cannot read")])
def test_a_tolerance_that_cannot_be_used_is_refused_naming_its_key(value, words):
    raw = tomllib.loads(open(CURVED, encoding="utf-8").read())
    (width,) = _vars(raw, "podium.width=0.3m:0.6m:3")
    with pytest.raises(RockdesignError) as e:
        parse_tolerance(value, width, key="tolerance", source="option")
    assert words in str(e.value) and e.value.key == "tolerance"


def test_the_option_wins_over_the_project_table_and_unused_entries_are_said():
    raw = tomllib.loads(open(CURVED, encoding="utf-8").read())
    raw["design"] = {"tolerance": {"podium.width": "3 mm", "podium": {"curvature": "5%"},
                                   "podium.height": "1%"}}
    variables = _vars(raw, "podium.width=0.3m:0.6m:3", "podium.curvature=0.1:0.5:3")
    tols, notes = tolerances(variables, None, raw, file="p.toml")
    assert tols["podium.width"].absolute == pytest.approx(0.003) and tols["podium.width"].source == "project"
    assert tols["podium.curvature"].relative == pytest.approx(0.05)
    assert notes == ["[design.tolerance] podium.height = '1%' is not used: the chart does not vary podium.height"]
    tols, _ = tolerances(variables, ["podium.width=1%"], raw, file="p.toml")
    assert tols["podium.width"].relative == 0.01 and tols["podium.width"].source == "option"
    assert tols["podium.width"].as_json() == {"relative": 0.01, "source": "option", "given": "1%"}
    with pytest.raises(RockdesignError) as e:
        tolerances(variables, {"podium.height": "1%"}, raw, file="p.toml")
    assert e.value.key == "tolerance" and "does not vary" in str(e.value)
    raw["design"]["tolerance"]["podium.width"] = "3 s"
    with pytest.raises(ProjectError) as e:
        tolerances(variables, None, raw, file="p.toml")
    assert e.value.key == "design.tolerance.podium.width" and e.value.file == "p.toml"


def test_the_project_table_is_validated_when_the_project_loads(tmp_path):
    base = stocky_podium_toml()
    for extra, key in [('[design]\ntolerence = 1', "design.tolerence"),
                       ('[design.tolerance]\nwidth = "1%"', "design.tolerance.width"),
                       ('[design.tolerance]\n"podium.width" = [1, 2]', "design.tolerance.podium.width"),
                       ('[design]\ntolerance = "1%"', "design.tolerance")]:
        with pytest.raises(ProjectError) as e:
            rd.parse_project(base + extra)
        assert e.value.key == key, extra
    rd.parse_project(base + '[design.tolerance]\n"podium.width" = "2 mm"\npodium.height = "1%"\n')


def test_the_neighbourhood_is_each_key_plus_and_minus_its_tolerance_the_others_nominal():
    raw = tomllib.loads(open(CURVED, encoding="utf-8").read())
    variables = _vars(raw, "podium.width=0.3m:0.6m:3", "podium.curvature=0.1:0.5:3")
    tols, _ = tolerances(variables, None, raw, file=CURVED)
    cell = {"index": [1, 2], "values": {"podium.width": 0.45, "podium.curvature": 0.5}}
    hood = neighbourhood_of(cell, variables, tols, raw, CURVED)
    got = [(key, sign, v.values) for key, sign, v in hood]
    assert [g[:2] for g in got] == [("podium.width", -1.0), ("podium.width", 1.0), ("podium.curvature", -1.0),
                                    ("podium.curvature", 1.0)]
    assert got[0][2] == {"podium.width": pytest.approx(0.4455), "podium.curvature": 0.5}
    assert got[3][2] == {"podium.width": 0.45, "podium.curvature": pytest.approx(0.51)}
    # each neighbour is a validated project with that value written in
    assert hood[1][2].project.system.column.half_width * 2 == pytest.approx(0.4545)
    assert hood[1][2].labels == {"podium.width": "0.4545 m", "podium.curvature": "0.5"}


def test_the_command_line_refuses_a_bad_tolerance_before_any_analysis(tmp_path):
    p = tmp_path / "p.toml"
    p.write_text(stocky_podium_toml(), encoding="utf-8")
    for spec, words in [("podium.height=1%", "does not vary"), ("podium.width", "KEY=VALUE"),
                        ("podium.width=2 s", "wrong units")]:
        res = runner.invoke(app, ["design", str(p), "--vary", "podium.width=0.4m:0.6m:3", "--tolerance", spec,
                                  "-o", str(tmp_path / "out"), "--no-pdf"])
        assert res.exit_code == 2, res.output
        assert "--tolerance" in res.output and words in res.output and "Traceback" not in res.output
        assert not (tmp_path / "out").exists()


def test_the_library_takes_a_mapping_or_options_and_writes_them_into_the_settings(tmp_path):
    project = rd.parse_project(stocky_podium_toml())
    plan = rd.plan_design(project, ["podium.width=0.4m:0.6m:3"], tolerance={"podium.width": "2 mm"})
    assert plan.tolerances["podium.width"].absolute == pytest.approx(0.002)
    plan = rd.plan_design(project, ["podium.width=0.4m:0.6m:3"], tolerance=["podium.width=0.5%"])
    assert plan.tolerances["podium.width"].relative == pytest.approx(0.005)
    with pytest.raises(RockdesignError) as e:
        rd.plan_design(project, ["podium.width=0.4m:0.6m:3"], tolerance=0.01)
    assert e.value.key == "tolerance"


def test_a_dask_value_keeps_the_tolerances(monkeypatch):
    """``rd.design(p, vary, executor="tcp://…", tolerance=…)`` starts the executor and calls itself with it: the
    tolerances went missing on that call (the chart was built to the defaults).  The executor is replaced here by
    one that runs nothing, and the plan is caught before any analysis."""
    import contextlib

    import rockdesign.design_space.run as run
    seen = {}

    @contextlib.contextmanager
    def no_cluster(executor, **_):
        yield object()

    class Planned(Exception):
        pass

    def plan(project, vary, **kwargs):
        seen.update(kwargs)
        raise Planned
    monkeypatch.setattr(run, "check_executor", lambda *a, **k: None)
    monkeypatch.setattr(run, "running_on", no_cluster)
    monkeypatch.setattr(run, "plan_design", plan)
    with pytest.raises(Planned):
        rd.design(CURVED, ["podium.width=0.5m:0.6m:2"], executor="tcp://127.0.0.1:8786",
                  tolerance={"podium.width": "3 mm"})
    assert seen["tolerance"] == {"podium.width": "3 mm"}
