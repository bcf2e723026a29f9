"""The output folder of a cylinder check (the planar check's rules: refused before the analyses, all or
nothing, stale files removed, one run at a time), --no-pdf/--html/--json, and ``init cylinder``."""
from __future__ import annotations

import json
import tomllib

import pytest
from typer.testing import CliRunner

from rockdesign.cylinder import check as cylinder_check
from rockdesign.cli import app
from rockdesign.cylinder import pairs
from rockdesign.library import load_project
from rockdesign.library import check_output_folder

runner = CliRunner()
SUITE = "test-two-pairs"
TOML = ('[project]\nname = "folder cylinder"\n[cylinder]\nheight = "3 m"\nslenderness = 0.2\nmass = "2 t"\n'
        f'[excitation]\nsuites = ["{SUITE}"]\nscale = {{ method = "resultant_pga", target = "0.3 g" }}\n'
        '[analysis]\nacceptance = "binomial"\noverturn_probability_limit = 0.8   # a small test suite: the binomial rule needs 2 pairs at 80 %\n')


@pytest.fixture
def project(tmp_path, monkeypatch):
    monkeypatch.setitem(pairs.PAIR_SUITES, SUITE, ("p695-ff", range(1, 3)))
    path = tmp_path / "cyl.toml"
    path.write_text(TOML)
    return path


@pytest.fixture
def no_analysis(monkeypatch):
    """Make any analysis fail loudly: the tests below must stop before it."""
    def refuse(*args, **kwargs):
        raise AssertionError("the analyses ran")
    monkeypatch.setattr(cylinder_check, "run_cylinder_check", refuse)


def test_output_is_a_file_exit_2_before_the_analyses(project, tmp_path, no_analysis):
    target = tmp_path / "taken"
    target.write_text("mine")
    r = runner.invoke(app, ["check", str(project), "-o", str(target)])
    assert r.exit_code == 2 and "output folder is a file" in r.output and "-o/--out" in r.output
    assert "Traceback" not in r.output and target.read_text() == "mine"


def test_foreign_folder_and_busy_folder_are_refused(project, tmp_path, no_analysis):
    foreign = tmp_path / "foreign"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("keep")
    r = runner.invoke(app, ["check", str(project), "-o", str(foreign)])
    assert r.exit_code == 2 and "notes.txt" in r.output and (foreign / "notes.txt").read_text() == "keep"
    busy = check_output_folder(load_project(project), tmp_path / "busy")
    with busy.locked():
        r = runner.invoke(app, ["check", str(project), "-o", str(tmp_path / "busy")])
    assert r.exit_code == 2 and "in use by another rockdesign run" in r.output


def test_no_pdf_html_json_and_stale_files(project, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    for name in ("report.pdf", "report.html", "wobbling_period.png"):   # an earlier run's files
        (out / name).write_text("stale")
    r = runner.invoke(app, ["check", str(project), "-o", str(out), "--no-pdf", "--json"])
    data = json.loads(r.stdout)
    assert r.exit_code == (0 if data["verdict"] == "PASS" else 1)
    assert sorted(p.name for p in out.iterdir()) == ["cylinder_vs_planar.png", "results.csv", "results.json",
                                                     "wobbling_period.png"]
    assert (out / "wobbling_period.png").read_bytes()[:4] == b"\x89PNG"
    assert json.loads((out / "results.json").read_text(encoding="utf-8")) == data
    assert data["summary"]["n_records"] == 2
    r = runner.invoke(app, ["check", str(project), "-o", str(out), "--no-pdf", "--html"])
    assert r.exit_code in (0, 1) and "verdict:" in r.output
    assert (out / "report.html").exists() and not (out / "report.pdf").exists()
    assert not list(tmp_path.glob(".out.*"))   # no temporary folder or lock left beside it


def test_failed_run_leaves_the_previous_folder(project, tmp_path, monkeypatch):
    out = tmp_path / "out"
    assert runner.invoke(app, ["check", str(project), "-o", str(out), "--no-pdf"]).exit_code in (0, 1)
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    from rockdesign.cylinder import report as cylinder_report

    def broken(*args, **kwargs):
        raise RuntimeError("renderer broke")
    monkeypatch.setattr(cylinder_report, "render_cylinder_html", broken)
    r = runner.invoke(app, ["check", str(project), "-o", str(out), "--no-pdf", "--html"])
    assert r.exit_code != 0
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


def test_init_cylinder_writes_a_template_that_parses_and_checks(tmp_path, monkeypatch):
    path = tmp_path / "col.toml"
    r = runner.invoke(app, ["init", "cylinder", str(path)])
    assert r.exit_code == 0 and path.exists()
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    assert set(raw) == {"project", "cylinder", "excitation", "analysis"}
    project = load_project(path)
    cyl = project.system
    assert cyl.kind == "cylinder" and cyl.contact == "rigid"
    assert 2 * cyl.half_height == pytest.approx(3.0) and 2 * cyl.base_radius == pytest.approx(0.6)
    assert cyl.mass == pytest.approx(2600.0 * 3.141592653589793 * 0.3 ** 2 * 3.0)
    assert cyl.overturn_tilt == 1.5 and project.analysis.overturn_probability_limit == 0.1
    assert runner.invoke(app, ["init", "cylinder", str(path)]).exit_code == 2   # never overwrites
    # the template's suite, shortened to two pairs: ASCE 7-22 needs 11 ground motions, refused up front
    monkeypatch.setitem(pairs.PAIR_SUITES, "p695-farfield-pairs", ("p695-ff", range(1, 3)))
    r = runner.invoke(app, ["check", str(path), "-o", str(tmp_path / "out2"), "--no-pdf"])
    assert r.exit_code == 2 and "11" in r.output and "Traceback" not in r.output
    assert not (tmp_path / "out2").exists()
    # with the binomial rule at 80 % two pairs are enough, and the template runs through check
    path.write_text(path.read_text().replace('acceptance = "asce7"', 'acceptance = "binomial"', 1)
                    .replace("overturn_probability_limit = 0.1", "overturn_probability_limit = 0.8"))
    r = runner.invoke(app, ["check", str(path), "-o", str(tmp_path / "out"), "--no-pdf", "--json"])
    data = json.loads(r.stdout)
    assert r.exit_code == (0 if data["verdict"] == "PASS" else 1)
    assert data["summary"]["n_records"] == 2
    assert all(rec["resultant_pga"] == pytest.approx(0.3 * 9.81, rel=1e-12) for rec in data["records"])


def test_options_a_cylinder_check_does_not_use_are_refused(project, tmp_path, no_analysis):
    import rockdesign as rd
    from rockdesign.errors import RockdesignError
    for option in (["--records-dir", str(tmp_path)],):       # (--dask runs its 3D analyses: test_cylinder_executor)
        r = runner.invoke(app, ["check", str(project), "-o", str(tmp_path / "out"), *option])
        assert r.exit_code == 2 and option[0] in r.output and "Traceback" not in r.output
    assert not (tmp_path / "out").exists()
    with pytest.raises(RockdesignError) as err:
        rd.check(load_project(project), records_dir=tmp_path)
    assert err.value.key == "records_dir"
