"""``rockdesign simulate`` (CONTRACT §2–§3): motion strings, JSON keys, plot and CSV files, errors."""
from __future__ import annotations

import csv
import json
import math

import pytest

from casedata import expected
from typer.testing import CliRunner

from rockdesign.cli import app

runner = CliRunner()
KEYS = {"theta_max", "theta_max_over_alpha", "theta_max_over_theta_c", "u_B_max", "uplift_time", "impacts",
        "overturned", "overturn_mode", "t_end", "model", "solver"}


def run(*args):
    return runner.invoke(app, ["simulate", *args])


def test_json_keys_and_table_3_4_b1_through_the_cli(tmp_path):
    # Table 3.4 B1 as a project file: 2H = 3 m, tan α = 0.1, antisymmetric Ricker 0.38 g, T_p = 0.95 s
    p = tmp_path / "b1.toml"
    p.write_text('[project]\nname = "B1"\n[column]\nheight = "3 m"\nslenderness = 0.1\nmass = "1 t"\n'
                 'mass_distribution = 0.3333333333333333\n[analysis]\noverturn = "dynamic"\n')
    r = run(str(p), "--motion", "ricker-anti:ap=0.38g,Tp=0.95s", "--t-end", "10", "--json")
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert KEYS <= set(data)
    assert data["theta_max_over_alpha"] == pytest.approx(expected("tab3.4_B1_thmax"), abs=1e-4)
    assert data["uplift_time"] == pytest.approx(expected("tab3.4_B1_tup"), abs=5e-5)
    assert data["impacts"] == 15
    assert data["overturn_mode"] == "exceeded" and data["overturned"] is False   # came back: not dynamic
    assert {"steps", "rejected_steps", "function_evaluations", "events", "rest_entries"} <= set(data["solver"])


def test_uplift_multiples_and_frequency_ratio():
    r = run("examples/podium_flat.toml", "--motion", "ricker-anti:ap=2.5up,wp=3p", "--json")
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert data["model"].startswith("podium-2dof")
    assert data["uplift_time"] is not None


def test_free_vibration_and_files(tmp_path):
    png, table = tmp_path / "h.png", tmp_path / "h.csv"
    r = run("examples/shake_table_F02.toml", "--motion", "free:theta0=0.5alpha", "--plot", str(png), "--csv",
            str(table), "--t-end", "3")
    assert r.exit_code == 0, r.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = list(csv.reader(open(table)))
    assert rows[0][0] == "t_s" and len(rows) > 100
    assert float(rows[1][2]) == pytest.approx(0.5 * math.atan(0.1), rel=1e-9)


def test_builtin_record_with_scale():
    r = run("examples/bridge_pier.toml", "--motion", "record:p695-ff/11a,scale=0.5", "--json")
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["t_end"] > 40


def test_record_file(shared):
    path = shared / "ground_motions" / "records" / "FEMAP695_FF11a_RSN900_YER270.AT2"
    a = json.loads(run("examples/bridge_pier.toml", "--motion", f"file:{path}", "--json").stdout)
    b = json.loads(run("examples/bridge_pier.toml", "--motion", "record:p695-ff/11a", "--json").stdout)
    # the same accelerogram (float32 package data vs the AT2 text): the same response to 1e-5
    assert a["theta_max"] == pytest.approx(b["theta_max"], rel=1e-5)


def test_linear_exact_for_a_column_and_not_for_a_2dof_podium():
    r = run("examples/bridge_pier.toml", "--motion", "sine:ap=0.4g,Tp=1s", "--model", "linear-exact", "--json")
    assert r.exit_code == 0, r.output
    r = run("examples/podium_flat.toml", "--motion", "sine:ap=0.4g,Tp=1s", "--model", "linear-exact")
    assert r.exit_code == 2 and "SDOF" in r.output


@pytest.mark.parametrize("motion,fragment", [
    ("quake:ap=1g", "unknown motion kind"),
    ("ricker-anti:Tp=1s", "amplitude"),
    ("ricker-anti:ap=0.3kg,Tp=1s", "acceleration"),
    ("ricker-anti:ap=0.3g,Tp=1s,foo=2", "unknown motion parameter"),
    ("ricker-anti:ap=0.3g", "period"),
    ("record:p695-ff/77a", "unknown record id"),
    ("free:", "initial condition"),
])
def test_bad_motion_strings(motion, fragment):
    r = run("examples/bridge_pier.toml", "--motion", motion)
    assert r.exit_code == 2, r.output
    assert fragment in " ".join(r.output.split())
    assert "Traceback" not in r.output
