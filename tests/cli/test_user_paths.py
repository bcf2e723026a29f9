"""Paths a user gives that the file system refuses: input errors (exit 2) naming the key or option (issue 49).

``~nosuchuser/…`` made Python raise "Could not determine home directory", a name over 255 bytes OSError 36
and a folder that cannot be read PermissionError — each an internal error (exit 3) with a traceback.  Now each
is refused before any work, naming the project key or the option, and nothing is written.
"""
from __future__ import annotations

import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

import rockdesign as rd
from rockdesign.cli import app
from rockdesign.paths import REPO_ROOT

runner = CliRunner()
PIER = REPO_ROOT / "examples" / "bridge_pier.toml"
ASCE = REPO_ROOT / "examples" / "podium_asce7_22.toml"
LONG = "x" * 300
NO_HOME = "names no home folder on this machine"
TOO_LONG = "a file name too long for the file system"


def assert_one_line_error(result, *fragments):
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert "Traceback" not in result.output and "internal error" not in result.output, result.output
    text = " ".join(result.stderr.split())
    assert text.count("error:") == 1, text
    for fragment in fragments:
        assert fragment in text, (fragment, text)
    return text


@pytest.fixture(autouse=True)
def no_compiling(monkeypatch):
    def boom(*args, **kwargs):
        raise AssertionError("compiled kernels for a bad path")
    monkeypatch.setattr("rockdesign.execution.compilation.prepare", boom)


def project_with(tmp_path: Path, source: Path, old: str, new: str) -> Path:
    text = source.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "p.toml"
    path.write_text(text.replace(old, new), encoding="utf-8")
    return path


ASCE_SCALE = 'scale = { method = "asce7-22", SMS = "0.30 g", SM1 = "0.12 g", TL = "8 s" }'
PIER_EXCITATION = "[excitation]\n"


@pytest.mark.parametrize("source,old,new,key,problem", [
    (ASCE, ASCE_SCALE, 'scale = { method = "asce7-22", target = "~nosuchuser/t.csv" }',
     "excitation.scale.target", NO_HOME),
    (ASCE, ASCE_SCALE, f'scale = {{ method = "asce7-22", target = "{LONG}.csv" }}', "excitation.scale.target",
     TOO_LONG),
    (ASCE, 'suites = ["p695-farfield"]', 'suites = ["~nosuchuser/s.toml"]', "excitation.suites[0]", NO_HOME),
    (ASCE, 'suites = ["p695-farfield"]', 'suites = ["p695-farfield"]\nrecords = ["~nosuchuser/r.AT2"]',
     "excitation.records[0]", NO_HOME),
    (ASCE, 'suites = ["p695-farfield"]', f'suites = ["p695-farfield"]\nrecords = ["file:{LONG}.AT2"]',
     "excitation.records[0]", TOO_LONG),
    (ASCE, 'suites = ["p695-farfield"]', 'suites = ["p695-farfield"]\nrecords_dir = "~nosuchuser/peer"',
     "excitation.records_dir", NO_HOME),
])
def test_project_keys(tmp_path, source, old, new, key, problem):
    project = project_with(tmp_path, source, old, new)
    r = runner.invoke(app, ["check", str(project), "--no-pdf", "-o", str(tmp_path / "out")])
    assert_one_line_error(r, str(project), f"key '{key}'", problem)
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("args,key,problem", [
    (["check", PIER, "--no-pdf", "-o", "~nosuchuser/out"], "-o/--out", NO_HOME),
    (["design", PIER, "--vary", "column.width=0.7m:0.8m:2", "-o", "~nosuchuser/out"], "-o/--out", NO_HOME),
    (["spectrum", PIER, "--pulse", "sine", "-o", "~nosuchuser/out"], "-o/--out", NO_HOME),
    (["simulate", PIER, "--motion", "sine:ap=0.3g,Tp=1s", "--csv", "~nosuchuser/x.csv"], "--csv", NO_HOME),
    (["records", "synth", "--seed", "p695-ff/11a", "-n", "2", "-o", "~nosuchuser/s"], "--out", NO_HOME),
    (["simulate", PIER, "--motion", "file:~nosuchuser/x.AT2"], "--motion", NO_HOME),
    (["check", PIER, "--no-pdf", "-o", "{tmp}/" + LONG], "-o/--out", TOO_LONG),
    (["design", PIER, "--vary", "column.width=0.7m:0.8m:2", "-o", "{tmp}/" + LONG + "/d"], "-o/--out", TOO_LONG),
    (["simulate", PIER, "--motion", "sine:ap=0.3g,Tp=1s", "--plot", "{tmp}/" + LONG + ".png"], "--plot", TOO_LONG),
    (["simulate", PIER, "--motion", "file:{tmp}/" + LONG + ".AT2"], "--motion", TOO_LONG),
])
def test_options(tmp_path, args, key, problem):
    r = runner.invoke(app, [str(a).format(tmp=tmp_path) for a in args])
    assert_one_line_error(r, f"key '{key}'", problem)
    assert list(tmp_path.iterdir()) == []


@pytest.fixture
def unreadable(tmp_path, monkeypatch):
    """A folder that cannot be read: as another user, Python raises PermissionError (Errno 13) when looking
    inside it; as root, who may look anywhere, Path.exists and Path.is_dir raise it for that folder."""
    folder = tmp_path / "private"
    folder.mkdir()
    if os.geteuid() != 0:
        folder.chmod(0o000)
    else:
        for name in ("exists", "is_dir", "is_file"):
            real = getattr(Path, name)

            def refusing(path, *a, _real=real, **k):
                if str(path).startswith(str(folder) + os.sep):
                    raise PermissionError(13, "Permission denied", str(path))
                return _real(path, *a, **k)
            monkeypatch.setattr(Path, name, refusing)
    yield folder
    folder.chmod(0o700)


def test_an_unreadable_folder_on_the_way(unreadable, tmp_path):
    r = runner.invoke(app, ["check", str(PIER), "--no-pdf", "-o", str(unreadable / "out")])
    assert_one_line_error(r, "key '-o/--out'", "Errno 13")
    r = runner.invoke(app, ["simulate", str(PIER), "--motion", "sine:ap=0.3g,Tp=1s", "--csv",
                            str(unreadable / "x.csv")])
    assert_one_line_error(r, "key '--csv'", "Errno 13")


# ------------------------------------------------------------------ the same from the library
def test_library_output_folders(tmp_path):
    project = rd.load_project(PIER)
    with pytest.raises(rd.OutputError) as err:
        rd.design(project, ["column.width=0.7m:0.8m:2"], out_dir="~nosuchuser/out")
    assert err.value.key == "out_dir" and NO_HOME in str(err.value)
    with pytest.raises(rd.OutputError) as err:
        rd.design_folder(tmp_path / LONG)
    assert err.value.key == "out_dir" and TOO_LONG in str(err.value)
    with pytest.raises(rd.RockdesignError) as err:
        rd.records_synth("p695-ff/11a", 2, "~nosuchuser/s")
    assert err.value.key == "out_dir" and NO_HOME in str(err.value)


def test_library_motion_and_records_dir():
    project = rd.load_project(PIER)
    with pytest.raises(rd.RockdesignError) as err:
        rd.simulate(project, "file:~nosuchuser/x.AT2")
    assert err.value.key == "motion" and NO_HOME in str(err.value)
    with pytest.raises(rd.RockdesignError) as err:
        rd.records_show("rsn:900:270", records_dir="~nosuchuser/peer")
    assert err.value.key == "records_dir" and NO_HOME in str(err.value)
