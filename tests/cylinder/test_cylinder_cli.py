"""``rockdesign quantities|simulate`` for a ``[cylinder]`` project: JSON keys, CSV columns, figure, errors."""
from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from casedata import expected
from rockdesign.cli import app

runner = CliRunner()
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "cylinder.toml"
SIMULATE_KEYS = {"theta_max", "theta_max_over_alpha", "theta_max_over_theta_c", "u_B_max", "uplift_time",
                 "impacts", "overturned", "overturn_mode", "t_end", "model", "solver", "quasi_impacts",
                 "quasi_impact_times", "phi_end", "min_contact_force_over_weight"}


def rigid_project(tmp_path):
    p = tmp_path / "rigid.toml"
    p.write_text('[project]\nname = "rigid cylinder"\n[cylinder]\nheight = "3 m"\nslenderness = 0.2\n'
                 'mass = "2 t"\n')
    return p


def test_quantities_json_keys():
    r = runner.invoke(app, ["quantities", str(EXAMPLE), "--json"])
    assert r.exit_code == 0, r.output
    q = json.loads(r.stdout)["quantities"]
    assert {"alpha", "R", "p", "c_r", "uplift_acceleration", "angle_of_turn"} <= set(q)
    assert q["p"]["value"] == pytest.approx(expected("eq5.27_p"), abs=1e-5) and q["p"]["equation"] == "Eq 5.27"
    table = runner.invoke(app, ["quantities", str(EXAMPLE)])
    assert table.exit_code == 0 and "Eq 5.38" in table.stdout


def test_wobbling_curve_file(tmp_path):
    out = tmp_path / "tw.csv"
    r = runner.invoke(app, ["quantities", str(EXAMPLE), "--pushover", str(out)])
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(out.open()))
    assert list(rows[0]) == ["theta_over_alpha", "Tw_p", "T_housner_p"] and len(rows) > 50


def test_simulate_free_vibration_json_csv_plot(tmp_path):
    csv_path, png = tmp_path / "h.csv", tmp_path / "h.png"
    r = runner.invoke(app, ["simulate", str(EXAMPLE), "--motion", "free:theta0=0.1rad,phidot0=1e-3rad/s",
                            "--t-end", "5", "--json", "--csv", str(csv_path), "--plot", str(png)])
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert SIMULATE_KEYS <= set(data)
    assert data["model"] == "cylinder-damped"
    assert [round(t, 4) for t in data["quasi_impact_times"][:5]] == expected("sec5.4.4_damped_quasi_impacts")[0]
    assert 0 < data["min_contact_force_over_weight"] < 1
    header = next(csv.reader(csv_path.open()))
    assert header[:7] == ["t_s", "ground_x_m_s2", "ground_y_m_s2", "theta_rad", "thetadot_rad_s", "phi_rad",
                          "phidot_rad_s"] and "w_T_m" in header
    assert png.stat().st_size > 10_000


def test_simulate_record_pair_undamped_override(tmp_path):
    r = runner.invoke(app, ["simulate", str(rigid_project(tmp_path)), "--motion",
                            "record:p695-ff/12,resultant_pga=0.3g,azimuth=30deg", "--json"])
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert data["model"] == "cylinder-undamped" and "min_contact_force_over_weight" not in data
    assert data["uplift_time"] > 0 and data["solver"]["status"] in ("completed", "overturned (θ reached θ_ot)")


@pytest.mark.parametrize("args, words", [
    (["--motion", "record:p695-ff/12,resultant_pga=0.3g", "--model", "linear"], "does not apply to a cylinder"),
    (["--motion", "record:p695-ff/12,scale=2,resultant_pga=0.3g"], "conflicting"),
])
def test_simulate_errors_exit_2(tmp_path, args, words):
    r = runner.invoke(app, ["simulate", str(rigid_project(tmp_path)), *args])
    assert r.exit_code == 2
    assert words in r.output and "Traceback" not in r.output


def test_project_error_exit_2(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text('[project]\nname = "x"\n[cylinder]\nheight = "3 m"\ndiameter = "0.6 m"\nmass = "1 t"\n'
                 'contact_damping = 0.5\n')
    r = runner.invoke(app, ["quantities", str(p)])
    assert r.exit_code == 2 and "cylinder.contact_damping" in r.output
