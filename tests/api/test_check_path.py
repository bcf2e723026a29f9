"""A ``check`` followed from ``cli/`` to the written report (issue 48): the registry is asked once, the result is
serialised once (results.json, results.csv, the report and the console summary read one dict), the records are
read and scaled once and the design quantities computed once — on a first run (kernels missing: ``prepare_check``
reads the records before compiling) as on a warm one.  Counted with wrappers (check_path_counts.py)."""
from __future__ import annotations

import pytest
from typer.testing import CliRunner

from api_support import SMALL_PODIUM
from check_path_counts import count_check_path, first_run

SUITE = "test-two-pairs"
CYLINDER = ('[project]\nname = "counted cylinder"\n[cylinder]\nheight = "3 m"\nslenderness = 0.2\nmass = "2 t"\n'
            f'[excitation]\nsuites = ["{SUITE}"]\nscale = {{ method = "resultant_pga", target = "0.3 g" }}\n'
            '[analysis]\nacceptance = "binomial"\noverturn_probability_limit = 0.8\n')


def _check(tmp_path, text: str):
    from rockdesign.cli import app
    project = tmp_path / "p.toml"
    project.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["check", str(project), "-o", str(out), "--no-margins", "--no-pdf", "--html"])
    assert result.exit_code in (0, 1, 4), result.output
    assert {p.name for p in out.iterdir()} >= {"results.json", "results.csv", "report.html"}
    return out


@pytest.mark.parametrize("first", [True, False], ids=["first run", "warm run"])
def test_planar_check_asks_once_serialises_once_reads_once(tmp_path, monkeypatch, first):
    counts = count_check_path(monkeypatch)
    if first:
        first_run(monkeypatch)
    _check(tmp_path, SMALL_PODIUM)
    assert counts["registry"] == 1 and counts["kind_of_document"] == 1, counts
    assert counts["serialise"] == 1, counts          # as_json() may be called: it returns the one dict
    assert counts["records"] == 1 and counts["quantities"] == 1, counts


@pytest.mark.parametrize("first", [True, False], ids=["first run", "warm run"])
def test_cylinder_check_asks_once_serialises_once_reads_once(tmp_path, monkeypatch, first):
    from rockdesign.cylinder import check as cylinder_check
    pairs = __import__(cylinder_check.suite_pairs.__module__, fromlist=["PAIR_SUITES"])   # (wherever pairs live)
    monkeypatch.setitem(pairs.PAIR_SUITES, SUITE, ("p695-ff", range(1, 3)))
    counts = count_check_path(monkeypatch)
    if first:
        first_run(monkeypatch)
    _check(tmp_path, CYLINDER)
    assert counts["registry"] == 1 and counts["kind_of_document"] == 1, counts
    assert counts["serialise"] == 1, counts
    assert counts["record_pairs"] == 1 and counts["cylinder_quantities"] == 1, counts


def test_as_json_is_one_dict(small_check):
    """The result is serialised once: every call returns the same dict (read it, do not change it)."""
    assert small_check.as_json() is small_check.as_json()
    assert {"pushover", "spectra"} <= set(small_check.figure_data)
    assert "figure_data" not in small_check.as_json()           # report data, not results.json


def test_a_parsed_project_carries_its_kind(small_project_file):
    import rockdesign as rd
    from rockdesign.kinds import kind_of
    project = rd.load_project(small_project_file)
    assert project.kind is not None and kind_of(project) is project.kind


FORBIDDEN = ("rockdesign.planar.design.pushover:pushover_curve", "rockdesign.motions.spectra:motion_spectrum",
             "rockdesign.motions.spectra:period_grid", "rockdesign.planar.design.quantities:design_quantities",
             "rockdesign.cylinder.quantities:wobbling_curve", "rockdesign.cylinder.quantities:cylinder_quantities")
"""The computations the report used to make itself (issue 48): the check makes them now."""


def test_the_report_draws_what_the_check_computed(small_check, tmp_path, monkeypatch):
    """Writing the report (results, figures, HTML) of a finished check calls none of the computations."""
    import importlib
    import sys

    import rockdesign as rd
    for spec in FORBIDDEN:
        module, name = spec.split(":")
        original = getattr(importlib.import_module(module), name)

        def refuse(*args, _name=name, **kwargs):
            raise AssertionError(f"the report computed {_name}")
        for mod in [m for n, m in list(sys.modules.items()) if n.startswith("rockdesign") and m is not None]:
            if getattr(mod, name, None) is original:
                monkeypatch.setattr(mod, name, refuse)
    rd.write_report(small_check, tmp_path / "out", pdf=False, html=True)
    assert (tmp_path / "out" / "report.html").is_file()
