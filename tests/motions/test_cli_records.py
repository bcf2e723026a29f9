"""``rockdesign records ...`` through typer's CliRunner (sub-app of rockdesign.cli.records).

User errors surface as RockdesignError subclasses (the main CLI turns them into exit code 2)."""
from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from rockdesign.cli.records import app
from rockdesign.errors import MotionError, RecordError
from rockdesign.motions.library import load_record
from rockdesign.motions.spectra import sd_max

runner = CliRunner()

SPECTRUM_KEYS = ["id", "damping", "band", "periods", "SD", "PSV", "PSA", "sd_max", "t_sd_max", "pga", "pgv", "pgd",
                 "arias", "cav", "bracketed_duration", "significant_duration", "a_rms", "predominant_frequency"]


def invoke(*args):
    return runner.invoke(app, list(args))


def test_list_json():
    result = invoke("list", "--json")
    assert result.exit_code == 0, result.output
    rows = json.loads(result.stdout)
    assert len(rows) == 100
    assert list(rows[0]) == ["id", "event", "year", "station", "rsn", "component", "dt", "npts", "pga"]


def test_list_suite_table_shows_missing():
    result = invoke("list", "--suite", "thesis-table-4.1")
    assert result.exit_code == 0, result.output
    line = next(line for line in result.stdout.splitlines() if "rsn:900:270" in line)
    assert "A9" in line and "Yermo Fire Station" in line and "0.245" in line
    assert "missing rsn:29:065" in result.stdout and "[excitation] records_dir" in result.stdout


def test_list_suite_json_with_records_dir(shared_records):
    result = invoke("list", "--suite", "thesis-table-4.2", "--json", "--records-dir", str(shared_records))
    rows = json.loads(result.stdout)
    assert [r["label"] for r in rows if r["pga"] is not None] == ["B1", "B2", "B3"]


def test_show_and_plot(tmp_path):
    plot = tmp_path / "show.png"
    result = invoke("show", "p695-ff/11a", "--plot", str(plot))
    assert result.exit_code == 0, result.output
    assert "Yermo Fire Station" in result.stdout and "SD_max (2 % damping, 0.05–10 s)" in result.stdout
    assert "1.135 m" in result.stdout
    assert plot.stat().st_size > 10_000


def test_spectrum_json_keys_and_values(tmp_path):
    plot = tmp_path / "spectrum.svg"
    result = invoke("spectrum", "record:p695-ff/11a", "--json", "--damping", "1 %", "--band", "0.1:5",
                    "--n-periods", "50", "--plot", str(plot))
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert list(data) == SPECTRUM_KEYS
    assert data["id"] == "p695-ff/11a" and data["damping"] == pytest.approx(0.01) and data["band"] == [0.1, 5.0]
    assert len(data["periods"]) == len(data["SD"]) == 50
    periods, sd = np.array(data["periods"]), np.array(data["SD"])
    np.testing.assert_allclose(data["PSA"], (2 * np.pi / periods) ** 2 * sd, rtol=1e-12)
    expected, period = sd_max(load_record("p695-ff/11a"), 0.01, (0.1, 5.0), 50)
    assert data["sd_max"] == pytest.approx(expected) and data["t_sd_max"] == pytest.approx(period)
    assert data["sd_max"] >= max(data["SD"])
    assert data["pga"] == pytest.approx(0.244803 * 9.81, rel=1e-5)
    assert plot.read_text().startswith("<?xml")


def test_spectrum_of_a_file(shared_records):
    path = shared_records / "elcentro_chopra_NS.csv"
    result = invoke("spectrum", f"file:{path}", "--json", "--n-periods", "20")
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["pga"] == pytest.approx(0.3188 * 9.81, rel=2e-4)


@pytest.mark.parametrize("args,error,fragment", [
    (("spectrum", "p695-ff/99a"), RecordError, "did you mean"),
    (("spectrum", "p695-ff/11a", "--band", "10:1"), MotionError, "Tmin < Tmax"),
    (("spectrum", "p695-ff/11a", "--damping", "abc"), MotionError, "damping"),
    (("show", "rsn:29:065"), RecordError, "not found"),
    (("show", "no/such/file.AT2"), RecordError, "record file not found"),
    (("list", "--suite", "thesis-table-9"), MotionError, "unknown suite"),
    (("synth", "--seed", "p695-ff/11a", "-n", "2", "-o", "out", "--scale-to", "pga"), MotionError, "--scale-to"),
])
def test_user_errors_are_rockdesign_errors(args, error, fragment):  # noqa: ARG001 (error documents the class)
    # through the main CLI: a clean one-line message naming what was expected, exit code 2
    from rockdesign.cli import app as main_app
    result = runner.invoke(main_app, ["records", *args])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    assert fragment in " ".join(result.output.split())
