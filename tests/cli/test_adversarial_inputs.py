"""Third round of adversarial input: motion pairs, experiment commands, spectrum grids, output paths.

Every case ends with exit 2 and one ``error:`` line naming the option, key or file — never a
traceback, never exit 0 having ignored or dropped something the user gave."""
from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

import rockdesign
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
    import rockdesign.execution.compilation as compilation

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


# ------------------------------------------------------------------ output paths that exist as the wrong type
@pytest.mark.parametrize("args,key", [
    (["check", PIER, "--no-pdf", "-o", "{link}"], "-o/--out"),
    (["simulate", PIER, "--motion", "sine:ap=0.3g,Tp=1s", "--plot", "{link}.png"], "--plot"),
    (["simulate", PIER, "--motion", "sine:ap=0.3g,Tp=1s", "--csv", "{link}.csv"], "--csv"),
    (["records", "synth", "--seed", "p695-ff/11a", "-n", "2", "-o", "{link}"], "--out"),
    (["spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:1:2:2", "--y", "ap/up:1:2:2", "-o", "{link}"],
     "-o/--out"),
    (["spectrum", CYLINDER, "--record", "p695-ff/11", "--x", "R:0.8:1:2", "--y", "pga/up:1:2:2", "-o", "{link}"],
     "-o/--out"),
    (["records", "scale-model", "p695-ff/11a", "--length-ratio", "0.1", "-o", "{link}.AT2"], "-o/--out"),
    (["init", "column", "{link}.toml"], "path"),
    (["init", "column", "{link}/x.toml"], "path"),
])
def test_dangling_symlink_outputs_are_refused_before_the_work(tmp_path, args, key, monkeypatch):
    """check -o <dangling symlink> used to fail with a traceback after the whole check ran."""
    refuse_compiling(monkeypatch)
    link = str(tmp_path / "link")
    args = [a.format(link=link) for a in args]
    target = next(a for a in args if a.startswith(link))
    name = Path(target).name if not target.endswith("/x.toml") else "link"
    (tmp_path / name).symlink_to(tmp_path / "nowhere" / name)
    r = invoke(*args)
    assert_one_line_error(r, f"key '{key}'", "dangling symbolic link", name)
    assert not (tmp_path / "nowhere").exists()


# ------------------------------------------------------------------ options given twice or not used
@pytest.mark.parametrize("args,key,found", [
    (["simulate", PIER, "--motion", "sine:ap=0.3g,Tp=1s", "--t-end", "3", "--t-end=4"], "--t-end",
     "'--t-end 3' and '--t-end=4'"),
    (["simulate", PIER, "--motion", "sine:ap=0.3g,Tp=1s", "--motion", "sine:ap=0.5g,Tp=1s"], "--motion",
     "'--motion sine:ap=0.3g,Tp=1s' and '--motion sine:ap=0.5g,Tp=1s'"),
    (["spectrum", PIER, "--pulse", "sine", "--resume", "--no-resume"], "--no-resume", "'--resume' and '--no-resume'"),
    (["check", PIER, "-o", "a", "--out", "b"], "--out", "'-o a' and '--out b'"),
])
def test_an_option_given_twice_is_refused(args, key, found, monkeypatch):
    refuse_compiling(monkeypatch)
    assert_one_line_error(invoke(*args), f"key '{key}'", "given twice", found)


def test_repeatable_options_may_repeat(tmp_path, monkeypatch):
    """--equivalent-at is declared repeatable: giving it twice is not an error (the run stops later, at the
    bad --x on purpose, before any analysis)."""
    refuse_compiling(monkeypatch)
    r = invoke("spectrum", PIER, "--pulse", "sine", "--equivalent-at", "1", "--equivalent-at", "2",
               "--x", "omega_p/p:2:1:3", "-o", tmp_path / "s")
    assert_one_line_error(r, "key '--x'")


@pytest.mark.parametrize("extra,key", [
    (["--pulse", "ricker-anti"], "--pulse"), (["--rtol", "1e-8"], "--rtol"),
    (["--no-polyakov"], "--polyakov/--no-polyakov"), (["--equivalent-at", "2"], "--equivalent-at"),
    (["--t-free", "5"], "--t-free"), (["--model", "linear"], "--model"),
])
def test_a_cylinder_spectrum_refuses_the_planar_options(tmp_path, extra, key, monkeypatch):
    """--pulse (and every planar-only option) on a cylinder spectrum used to be accepted and ignored."""
    refuse_compiling(monkeypatch)
    r = invoke("spectrum", CYLINDER, "--record", "p695-ff/11", *extra, "-o", tmp_path / "s")
    assert_one_line_error(r, f"key '{key}'", "not used by the spectrum of a cylinder")
    assert not (tmp_path / "s").exists()


def test_a_planar_spectrum_refuses_record(tmp_path, monkeypatch):
    refuse_compiling(monkeypatch)
    r = invoke("spectrum", PIER, "--pulse", "sine", "--record", "p695-ff/11", "-o", tmp_path / "s")
    assert_one_line_error(r, "key '--record'", "planar")


# ------------------------------------------------------------------ spectrum grids and output folders
def test_a_grid_too_large_for_memory_is_refused_with_the_estimate(tmp_path, monkeypatch):
    """1e5 × 1e5 used to end in MemoryError (exit 3) or days of work."""
    refuse_compiling(monkeypatch)
    r = invoke("spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:0.5:12:100000", "--y", "ap/up:0:12:100000",
               "-o", tmp_path / "s")
    flat = assert_one_line_error(r, "key '--x/--y'", "does not fit in memory", "10,000,000,000 analyses", "TB")
    assert "days" in flat
    assert not (tmp_path / "s").exists()


def test_grid_estimates():
    """Memory = points × BYTES_PER_POINT; time = points × CPU_PER_ANALYSIS / cores; both limits refuse."""
    import os
    from rockdesign.planar.spectra.axes import parse_axis
    from rockdesign.planar.spectra.spectrum import (BYTES_PER_POINT, CPU_PER_ANALYSIS, MAX_HOURS, SpectrumError,
                                             check_grid)
    x, y = parse_axis("omega_p/p:0.5:12:801", "x"), parse_axis("ap/up:0:12:401", "y")
    memory, seconds = check_grid(x, y, available=1e12)
    assert memory == 801 * 401 * BYTES_PER_POINT
    assert seconds == pytest.approx(801 * 401 * CPU_PER_ANALYSIS / (os.cpu_count() or 1))
    with pytest.raises(SpectrumError, match="memory"):
        check_grid(x, y, 2, available=memory)
    big = parse_axis("omega_p/p:0.5:12:100000", "x")
    n_y = int(MAX_HOURS * 3600 * (os.cpu_count() or 1) / CPU_PER_ANALYSIS / 100000) + 1
    tall = parse_axis(f"ap/up:0:12:{n_y}", "y")
    with pytest.raises(SpectrumError, match="too long"):
        check_grid(big, tall, available=1e18)
    check_grid(big, tall, distributed=True, available=1e18)      # a cluster: only memory is checked here


def test_unreachable_dask_scheduler_is_refused_at_once_without_a_folder(tmp_path, monkeypatch):
    import socket
    refuse_compiling(monkeypatch)
    with socket.socket() as s:       # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    r = invoke("spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:1:2:2", "--y", "ap/up:1:2:2",
               "--dask", f"tcp://127.0.0.1:{port}", "-o", tmp_path / "s")
    assert_one_line_error(r, "key '--dask'", "cannot reach", str(port))
    assert not (tmp_path / "s").exists()


def test_a_failed_spectrum_leaves_no_empty_folder(tmp_path, monkeypatch):
    import rockdesign.planar.spectra.spectrum as spectrum
    from rockdesign.errors import RockdesignError

    def fail(*args, **kwargs):
        raise RockdesignError("the cluster went away", key="--dask")
    monkeypatch.setattr(spectrum, "compute_spectrum", fail)
    monkeypatch.setattr(rockdesign, "compute_spectrum", fail)      # (the command reaches it through rockdesign)
    monkeypatch.setattr("rockdesign.execution.compilation.prepare", lambda *a, **k: 0.0)
    out = tmp_path / "deep" / "s"
    r = invoke("spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:1:2:2", "--y", "ap/up:1:2:2", "-o", out)
    assert_one_line_error(r, "the cluster went away")
    assert not (tmp_path / "deep").exists()


# ------------------------------------------------------------------ user text printed verbatim
NAME = "pier :-1: :smile: [red]x[/red]"


@pytest.mark.parametrize("command", [["quantities"], ["simulate", "--motion", "sine:ap=0.3g,Tp=1s", "--t-end", "2"]])
def test_user_text_is_printed_verbatim(tmp_path, command):
    """rich turned ':-1:' into an emoji (and would read '[red]' as markup) in tables and messages."""
    text = Path(PIER).read_text(encoding="utf-8")
    project = tmp_path / "p.toml"
    project.write_text(text.replace('name = "', f'name = "{NAME} ', 1), encoding="utf-8")
    r = invoke(command[0], project, *command[1:])
    assert r.exit_code == 0, r.output
    assert NAME in " ".join(r.stdout.split()) or NAME in r.stdout, r.stdout


def test_messages_quote_user_text_verbatim(monkeypatch):
    refuse_compiling(monkeypatch)
    r = invoke("spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:-1:8:5")
    assert_one_line_error(r, "'omega_p/p:-1:8:5'")
    r = invoke("simulate", PIER, "--motion", "sine:ap=0.3g,Tp=:smile:")
    assert_one_line_error(r, "':smile:'")


def test_every_console_comes_from_one_place():
    """No module creates a rich Console but rockdesign.console (emoji replacement off everywhere)."""
    import re
    root = Path(__file__).resolve().parents[2] / "rockdesign"
    makers = [str(p.relative_to(root)) for p in root.rglob("*.py")
              if re.search(r"(?<![\w.])Console\(", p.read_text(encoding="utf-8"))]
    assert makers == ["console.py"], makers


@pytest.mark.parametrize("extra,fragments", [
    (["--equivalent-at", "1"], ["key '--equivalent-at'", "relative spectrum only"]),
    (["--equivalent-at", "nan", "--relative", PIER], ["key '--equivalent-at'", "outside the y axis", "nan"]),
    (["--equivalent-at", "5", "--relative", PIER], ["key '--equivalent-at'", "within 1…2", "found 5"]),
])
def test_equivalent_size_ordinates_are_used_or_refused(tmp_path, extra, fragments, monkeypatch):
    """--equivalent-at without --relative was accepted and ignored (exit 0), a NaN ordinate too."""
    refuse_compiling(monkeypatch)
    r = invoke("spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:1:2:2", "--y", "ap/up:1:2:2", *extra,
               "-o", tmp_path / "s")
    assert_one_line_error(r, *fragments)
    assert not (tmp_path / "s").exists()


@pytest.mark.parametrize("args", [
    ["spectrum", CYLINDER, "--record", "p695-ff/11", "--x", "R:0.8:1:2", "--y", "pga/up:1:2:2", "-o", "{file}"],
    ["init", "column", "{file}/x.toml"],
])
def test_output_folder_that_is_a_file_before_any_work(tmp_path, args, monkeypatch):
    """The cylinder spectrum compiled and analysed before finding that -o is a file."""
    refuse_compiling(monkeypatch)
    target = tmp_path / "taken"
    target.write_text("x")
    r = invoke(*[a.format(file=target) for a in args])
    assert_one_line_error(r, "is a file", "taken")
    assert target.read_text() == "x"
