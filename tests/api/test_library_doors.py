"""The library checks its arguments at its doors (issue 49) and keys errors by the parameter passed (issue 50).

A wrong argument type used to surface as a raw TypeError or AttributeError from deep inside
(``rd.load_project(None)``: "expected str, bytes or os.PathLike object"; ``rd.design(..., executor="tcp://…")``:
"'str' object has no attribute 'start'").  Each now raises a :class:`rockdesign.RockdesignError` whose ``key`` is
the parameter of the function called, before any analysis and before any output folder exists.
"""
from __future__ import annotations

from pathlib import Path

import pytest

import rockdesign as rd
from rockdesign.design_space import grid

from api_support import SMALL_PODIUM

REPO = Path(__file__).resolve().parents[2]
PIER = REPO / "examples" / "bridge_pier.toml"
VARY = ["column.width=0.7m:0.8m:2"]


@pytest.fixture(scope="module")
def pier():
    return rd.load_project(PIER)


@pytest.fixture
def no_analysis(monkeypatch):
    def boom(*args, **kwargs):
        raise AssertionError("analysed or compiled for a bad argument")
    monkeypatch.setattr("rockdesign.execution.compilation.prepare", boom)
    monkeypatch.setattr("rockdesign.design_space.run.run_grid", boom)
    monkeypatch.setattr("rockdesign.planar.checks.check.run_check", boom)


@pytest.mark.parametrize("value", [None, 123, 1.5, True, ["a.toml"], "", "   "])
def test_load_project_refuses_what_is_not_a_path(value):
    with pytest.raises(rd.ProjectError) as err:
        rd.load_project(value)
    assert err.value.key == "path" and "not a path" in str(err.value) and type(value).__name__ in str(err.value)


def test_a_missing_project_file_names_the_parameter(tmp_path):
    with pytest.raises(rd.ProjectError) as err:
        rd.load_project(tmp_path / "nosuch.toml")
    assert err.value.key == "path" and err.value.file == str(tmp_path / "nosuch.toml")
    assert "file not found" in str(err.value)


def test_an_unknown_record_of_a_motion_is_keyed_by_motion(pier):
    with pytest.raises(rd.RecordError) as err:
        rd.simulate(pier, "record:p695-ff/99z,scale=1")
    assert err.value.key == "motion" and "unknown record id" in str(err.value) and "p695-ff/99z" in str(err.value)


@pytest.mark.parametrize("call,key,found", [
    (lambda p, tmp: rd.design(p, VARY, out_dir=123), "out_dir", "123 (int)"),
    (lambda p, tmp: rd.design(p, VARY, records_dir=4.5), "records_dir", "4.5 (float)"),
    (lambda p, tmp: rd.design(p, VARY, executor=42), "executor", "42 (int)"),
    (lambda p, tmp: rd.design(p, VARY, executor="local:0"), "executor", "'local:0'"),
    (lambda p, tmp: rd.design(p, VARY, executor="tcp://127.0.0.1:70267"), "executor", "outside 1–65535"),
    (lambda p, tmp: rd.plan_design(p, VARY, executor="tcp://127.0.0.1:1"), "executor", "rockdesign.make_executor("),
    (lambda p, tmp: rd.design_folder(None), "out_dir", "None (NoneType)"),
    (lambda p, tmp: rd.check(p, executor=42), "executor", "42 (int)"),
    (lambda p, tmp: rd.check(p, executor=object()), "executor", "(object)"),
    (lambda p, tmp: rd.check(p, records_dir=7), "records_dir", "7 (int)"),
    (lambda p, tmp: rd.simulate(p, "sine:ap=0.3g,Tp=1s", records_dir=7), "records_dir", "7 (int)"),
    (lambda p, tmp: rd.spectrum(p, pulse="sine", out_dir=3.0), "out_dir", "3.0 (float)"),
    (lambda p, tmp: rd.spectrum(p, pulse="sine", out_dir=tmp / "s", executor=1), "executor", "1 (int)"),
])
def test_wrong_argument_types_name_the_parameter(pier, tmp_path, call, key, found, no_analysis):
    with pytest.raises(rd.RockdesignError) as err:
        call(pier, tmp_path)
    assert err.value.key == key and found in str(err.value), str(err.value)
    assert list(tmp_path.iterdir()) == []


def test_write_report_refuses_a_folder_that_is_not_a_path(small_check, tmp_path):
    with pytest.raises(rd.ProjectError) as err:
        rd.write_report(small_check, 123)
    assert err.value.key == "out_dir"


def test_design_takes_a_dask_address_and_says_when_it_cannot_reach_it(pier, no_analysis):
    """A string executor is a dask value: rd.design starts and closes it (here: nothing listens on port 1)."""
    with pytest.raises(rd.RockdesignError) as err:
        rd.design(pier, VARY, executor="tcp://127.0.0.1:1")
    assert err.value.key == "executor" and "cannot reach the dask scheduler" in str(err.value)
    assert "'str' object" not in str(err.value)


def test_the_recommendation_explains_itself_in_library_words():
    """rd.design(..., prefer="material") said "(--prefer material)" in its reason."""
    cell = {"index": [0], "verdict": "PASS", "robust": True, "analysed": True, "column_material": 2.0e3,
            "robustness": "robust", "acceptance": "asce7", "values": {"column.width": 0.7},
            "labels": {"column.width": "0.7 m"}}
    best = grid.recommended([cell], ("column material", "volume"), "material")
    assert "--" not in best["reason"] and "preferred: material" in best["reason"], best["reason"]


def test_parse_project_is_unchanged_for_text():
    assert rd.parse_project(SMALL_PODIUM, name="x").path == "x"
