"""Third round of adversarial input: motion pairs, experiment commands, spectrum grids, output paths.

Every case ends with exit 2 and one ``error:`` line naming the option, key or file — never a
traceback, never exit 0 having ignored or dropped something the user gave."""
from __future__ import annotations

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.paths import REPO_ROOT

runner = CliRunner()
PIER = str(REPO_ROOT / "examples" / "bridge_pier.toml")
CYLINDER = str(REPO_ROOT / "examples" / "cylinder.toml")
AT2_HEAD = ("PEER NGA STRONG MOTION DATABASE RECORD\n"
            "Landers, 6/28/1992, Yermo Fire Station, 270\n"
            "ACCELERATION TIME SERIES IN UNITS OF G\n")


def assert_one_line_error(result, *fragments):
    """Exit 2, one 'error:' line on stderr containing every fragment, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
    text = result.stderr.strip()
    assert "Traceback" not in result.output, result.output
    assert len([ln for ln in text.splitlines() if ln.startswith("error:")]) == 1, text
    flat = " ".join(text.split())
    for f in fragments:
        assert f in flat, (f, flat)
    return flat


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def refuse_compiling(monkeypatch):
    """Bad input is refused before any kernel is compiled or any analysis runs."""
    import rockdesign.dynamics.compilation as compilation

    def boom(*args, **kwargs):
        raise AssertionError("compiled kernels for a bad input")
    monkeypatch.setattr(compilation, "prepare", boom)


# ------------------------------------------------------------------ non-finite and ignored motion parameters
NON_FINITE_PAIR = [
    ("record:p695-ff/11,azimuth=nan deg", "'azimuth'", "nan deg"),
    ("record:p695-ff/11,azimuth=inf deg", "'azimuth'", "inf deg"),
    ("record:p695-ff/11,azimuth=-inf°", "'azimuth'", "-inf°"),
    ("ricker-anti:ap=0.38g,Tp=0.95s,azimuth=nan deg", "'azimuth'", "nan deg"),
    ("ricker-anti:ap=0.38g,Tp=0.95s,azimuth=inf deg", "'azimuth'", "inf deg"),
    ("ricker-anti:ap=1e999g,Tp=0.95s", "'ap'", "1e999g"),
    ("ricker-anti:ap=0.38g,Tp=1e999s", "'Tp'", "1e999s"),
    ("sine:ap=0.3g,wp=1e999p", "'wp'", "1e999p"),
    ("record:p695-ff/11,resultant_pga=1e999g", "'resultant_pga'", "1e999g"),
    ("record:p695-ff/11,scale=nan", "scale", "scale=nan"),
    ("free:theta0=0.1rad,phidot0=1e999rad/s", "'phidot0'", "1e999rad/s"),
    ("free:theta0=0.1rad,phi0=nan deg", "'phi0'", "nan deg"),
]
IGNORED_OR_EMPTY = [
    ("record:p695-ff/11,units=g", "'units='", "units=g"),
    ("record:p695-ff/11,dt=0.01s", "'dt='", "dt=0.01s"),
    ("record:p695-ff/11a,dt=0.01s", "'dt='", "dt=0.01s"),
    ("record:p695-ff/11,,scale=1.5", "empty motion parameter", "record:p695-ff/11,,scale=1.5"),
    ("record:p695-ff/11,", "empty motion parameter", "record:p695-ff/11,"),
    ("ricker-anti:ap=0.38g,,Tp=0.95s", "empty motion parameter", "ap=0.38g,,Tp"),
    ("files:a.AT2,,b.AT2", "empty motion parameter", "files:a.AT2,,b.AT2"),
]


@pytest.mark.parametrize("motion,name,found", NON_FINITE_PAIR + IGNORED_OR_EMPTY)
def test_cylinder_motion_parameters(motion, name, found, monkeypatch):
    refuse_compiling(monkeypatch)
    r = invoke("simulate", CYLINDER, "--motion", motion)
    assert_one_line_error(r, "key '--motion'", name, found)


@pytest.mark.parametrize("motion,name,found", [
    ("ricker-anti:ap=1e999g,Tp=0.95s", "'ap'", "1e999g"),
    ("ricker-sym:ap=0.3g,Tp=1s,tm=1e999s", "'tm'", "1e999s"),
    ("free:theta0=0.1rad,thetadot0=1e999rad/s", "'thetadot0'", "1e999rad/s"),
    ("record:p695-ff/11a,units=g", "'units='", "units=g"),
    ("record:p695-ff/11a,dt=0.01s", "'dt='", "dt=0.01s"),
    ("record:p695-ff/11a,", "empty motion parameter", "record:p695-ff/11a,"),
    ("record:p695-ff/11a,,scale=2", "empty motion parameter", "record:p695-ff/11a,,scale=2"),
])
def test_planar_motion_parameters(motion, name, found, monkeypatch):
    refuse_compiling(monkeypatch)
    r = invoke("simulate", PIER, "--motion", motion)
    assert_one_line_error(r, "key '--motion'", name, found)


def test_a_pair_of_files_with_different_time_steps_names_both(tmp_path, monkeypatch):
    refuse_compiling(monkeypatch)
    x, y = tmp_path / "X.AT2", tmp_path / "Y.AT2"
    x.write_text(AT2_HEAD + "NPTS=    4, DT=   .0100 SEC\n  0.1 0.2 0.1 0.0\n")
    y.write_text(AT2_HEAD + "NPTS=    4, DT=   .0200 SEC\n  0.1 0.2 0.1 0.0\n")
    r = invoke("simulate", CYLINDER, "--motion", f"files:{x},{y}")
    assert_one_line_error(r, "key '--motion'", "different time steps", "0.01 s in 'X.AT2'", "0.02 s in 'Y.AT2'")
