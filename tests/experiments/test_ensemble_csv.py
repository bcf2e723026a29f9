"""A project run over an ensemble writes the analyses.csv that validate reads; numbers equal single runs."""
from __future__ import annotations

import csv

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.planar.experiments.ensemble import run_ensemble, write_analyses_csv
from rockdesign.experiments.validate import read_results_csv
from rockdesign.motions.library import load_record
from rockdesign.motions.suites import save_suite
from rockdesign.library import load_project

COLUMN = """
[project]
name = "ensemble column 2H = 5 m"

[column]
height = "5 m"
width = "0.5 m"
mass = "3 t"
mass_distribution = 0.333

[analysis]
overturn = "static"
free_vibration = "5 s"
"""
RECORDS = ("p695-ff/11a", "p695-ff/12a", "p695-ff/3b")


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ensemble")
    (folder / "column.toml").write_text(COLUMN)
    motions = [load_record(r) for r in RECORDS]
    suite = save_suite(folder / "ensemble.toml", motions, name="three", scale={"method": "factor", "value": 2.0})
    return folder, suite, motions


def test_ensemble_equals_single_analyses(setup):
    folder, suite, motions = setup
    project = load_project(folder / "column.toml")
    run = run_ensemble(project, str(suite), scale=1.5, restitution=0.95)
    assert run.ids == ["three/001", "three/002", "three/003"]
    assert run.scales == [3.0] * 3 and run.c_r == 0.95            # --scale × the manifest's factor
    system = project.system.with_restitution(0.95)
    a = project.analysis
    for motion, result in zip(motions, run.runs):
        single = simulate(system, motion.scaled(3.0), model="exact", rtol=a.rtol, atol=a.atol,
                          t_end=motion.duration + a.free_vibration, record_history=False)
        assert result.overturned == single.overturned
        assert result.theta_max_over_alpha == pytest.approx(single.theta_max / single.alpha, rel=1e-6)
    path = write_analyses_csv(run, folder / "analyses.csv")
    back = read_results_csv(path, "analyses")
    assert back.n == 3 and back.n_overturned == sum(r.overturned for r in run.runs)
    with open(path) as fh:
        assert next(csv.reader(fh))[:5] == ["id", "scale", "pga", "theta_max_over_alpha", "overturned"]


def test_cli(setup):
    folder, suite, _ = setup
    out = folder / "cli.csv"
    res = CliRunner().invoke(app, ["ensemble", str(folder / "column.toml"), "--suite", str(suite), "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert read_results_csv(out, "analyses").n == 3
    bad = CliRunner().invoke(app, ["ensemble", str(folder / "column.toml"), "--suite", str(suite), "-o", str(out),
                                   "--restitution", "1.5"])
    assert bad.exit_code == 2 and "Traceback" not in bad.output
