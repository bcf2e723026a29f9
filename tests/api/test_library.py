"""The notebook API of CONTRACT §5.1: ``import rockdesign as rd`` — everything from a TOML string, typed
results whose ``as_json()`` is the CLI's JSON byte for byte, errors naming the parameter."""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import rockdesign as rd
from rockdesign.cli import app
from rockdesign.report.results import json_text

from api_support import SMALL_PODIUM

runner = CliRunner()
REPO = Path(__file__).resolve().parents[2]
PULSE = "ricker-anti:ap=0.38g,Tp=0.95s"


def test_top_level_names():
    for name in ("load_project", "parse_project", "design_quantities", "simulate", "check", "write_report",
                 "RockdesignError", "ProjectError", "MotionError", "CheckResult"):
        assert name in dir(rd) and getattr(rd, name) is not None
    assert issubclass(rd.ProjectError, rd.RockdesignError) and issubclass(rd.OutputError, rd.RockdesignError)


def test_parse_project_equals_load_project(small_project_file):
    from_text = rd.parse_project(SMALL_PODIUM, name="notebook")
    from_file = rd.load_project(small_project_file)
    assert from_text.system == from_file.system
    assert from_text.path == "notebook" and from_text.sha256 == from_file.sha256


def test_parse_project_errors_name_the_source_and_key():
    with pytest.raises(rd.ProjectError) as exc:
        rd.parse_project(SMALL_PODIUM.replace('height = "3.0 m"', 'height = "3.0 kg"'), name="cell 3")
    assert exc.value.file == "cell 3" and exc.value.key == "podium.height"
    with pytest.raises(rd.ProjectError) as exc:
        rd.parse_project("[project\nname = 1", name="cell 4")
    assert "cell 4" in str(exc.value)


def test_quantities_attribute_and_key_access_with_units():
    q = rd.design_quantities(rd.parse_project(SMALL_PODIUM))
    assert q.theta_c is q["theta_c"]
    assert q.theta_c.unit == "rad" and q.R.unit == "m" and q.p.unit == "1/s"
    assert math.isclose(q.alpha.value, math.atan(0.6 / 3.0), rel_tol=1e-12)   # Eq 3.3: tan α = B/H
    assert all(isinstance(x.unit, str) and x.unit for x in q.values())       # units on every value
    with pytest.raises(AttributeError, match="theta_c"):
        q.no_such_quantity  # noqa: B018


def test_quantities_as_json_is_the_cli_json(small_project_file):
    q = rd.design_quantities(rd.load_project(small_project_file))
    cli = runner.invoke(app, ["quantities", str(small_project_file), "--json"])
    assert cli.exit_code == 0, cli.output
    assert json.dumps(q.as_json(), indent=2) + "\n" == cli.stdout


def test_simulate_string_and_object_and_cli_json(small_project_file):
    project = rd.load_project(small_project_file)
    r = rd.simulate(project, PULSE)
    assert r.t.shape == r.theta.shape and r.t[0] == 0.0
    assert r.theta_max == pytest.approx(np.max(np.abs(r.theta)), rel=1e-3)   # sampled peak ≤ event peak
    assert r.theta_max >= np.max(np.abs(r.theta))
    cli = runner.invoke(app, ["simulate", str(small_project_file), "--motion", PULSE, "--json"])
    assert cli.exit_code == 0, cli.output
    assert json.dumps(r.as_json(), indent=2) + "\n" == cli.stdout
    # a motion object gives the same response as its string
    from rockdesign.motions.parse import parse_motion
    from rockdesign.planar.simulation import system_scales
    motion = parse_motion(PULSE, system_scales(project.system)).motion
    r2 = rd.simulate(project, motion)
    assert r2.theta_max == r.theta_max and r2.impacts == r.impacts


def test_errors_name_the_parameter_not_a_flag():
    project = rd.parse_project(SMALL_PODIUM)
    with pytest.raises(rd.MotionError) as exc:
        rd.simulate(project, "ricker-anti:ap=-1g,Tp=1s")
    assert exc.value.key == "motion" and "--" not in str(exc.value)
    with pytest.raises(rd.RockdesignError) as exc:
        rd.simulate(project, PULSE, model="no-such-model")
    assert exc.value.key == "model" and "--model" not in str(exc.value)
    with pytest.raises(rd.RockdesignError) as exc:
        rd.simulate(project, 3.5)
    assert exc.value.key == "motion"
    with pytest.raises(rd.ProjectError) as exc:
        rd.check("podium.toml")
    assert exc.value.key == "project"


def test_check_result_and_cli_json_byte_for_byte(small_check, small_project_file, tmp_path):
    c = small_check
    assert c.verdict == "NOT DECIDED" and len(c.records) == 2      # margins=False: a governing criterion skipped
    assert c.fragility is None or hasattr(c.fragility, "__dict__") or isinstance(c.fragility, dict)
    cli = runner.invoke(app, ["check", str(small_project_file), "-o", str(tmp_path / "o"), "--no-pdf",
                              "--no-margins", "--json"])
    assert cli.exit_code == 4, cli.output
    assert json_text(c.as_json()) == cli.stdout
    assert (tmp_path / "o" / "results.json").read_text(encoding="utf-8") == cli.stdout


def test_write_report_from_a_notebook(small_check, tmp_path):
    out = rd.write_report(small_check, tmp_path / "out", pdf=False, html=True)
    assert sorted(p.name for p in out.iterdir()) == ["report.html", "results.csv", "results.json"]
    assert json.loads((out / "results.json").read_text(encoding="utf-8")) == json.loads(json_text(small_check.as_json()))
    header = (out / "results.csv").read_text(encoding="utf-8").splitlines()[0].split(",")
    assert header[0] == "id" and len((out / "results.csv").read_text().splitlines()) == 3


def test_no_module_switches_the_matplotlib_backend():
    # importing every rockdesign module keeps a notebook's backend; figures are pyplot-free Figures
    code = ("import matplotlib, pkgutil, importlib, rockdesign\n"
            "matplotlib.use('svg')\n"
            "for m in pkgutil.walk_packages(rockdesign.__path__, 'rockdesign.'):\n"
            "    importlib.import_module(m.name)\n"
            "import sys\n"
            "print(matplotlib.get_backend(), 'matplotlib.pyplot' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=REPO, timeout=600)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["svg", "False"]
    offenders = [str(p.relative_to(REPO)) for p in (REPO / "rockdesign").rglob("*.py")
                 if "matplotlib.use(" in p.read_text(encoding="utf-8") or "import matplotlib.pyplot" in p.read_text(encoding="utf-8")]
    assert offenders == []


def test_report_figures_are_figure_objects():
    from matplotlib.figure import Figure

    from rockdesign.planar.checks.figure_data import pushover_data
    from rockdesign.planar.report.figures import pushover_figure
    fig = pushover_figure(pushover_data(rd.parse_project(SMALL_PODIUM).system))
    assert isinstance(fig, Figure)
