"""Output folders (``check -o DIR``, ``rd.write_report``): all or nothing, only this run's files, one run
at a time, refused before the analyses when they cannot be written."""
from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

import rockdesign as rd
from rockdesign.cli import app
from rockdesign.outdir import OutputFolder

runner = CliRunner()
REPO = Path(__file__).resolve().parents[2]


def _leftovers(parent: Path, name: str) -> list[str]:
    return sorted(p.name for p in parent.iterdir() if p.name.startswith(f".{name}."))


@pytest.fixture
def no_analysis(monkeypatch):
    """Fail the test if a design check starts (errors must come before the analyses)."""
    def forbidden(*args, **kwargs):
        raise AssertionError("the analyses ran before the output folder was checked")
    monkeypatch.setattr("rockdesign.planar.checks.check.run_check", forbidden)


def _one_line_exit_2(result, *words):
    assert result.exit_code == 2, result.output
    text = result.output.strip()
    assert "Traceback" not in text and len(text.splitlines()) <= 2   # one message (rich may wrap it)
    for w in words:
        assert w in " ".join(text.split())


def test_output_is_a_file(small_project_file, tmp_path, no_analysis):
    target = tmp_path / "results.txt"
    target.write_text("mine")
    result = runner.invoke(app, ["check", str(small_project_file), "-o", str(target), "--no-pdf"])
    _one_line_exit_2(result, "-o/--out", "is a file")
    assert target.read_text() == "mine"


@pytest.fixture
def read_only_dir(tmp_path):
    folder = tmp_path / "ro"
    folder.mkdir()
    if os.geteuid() == 0:   # root ignores permission bits: use the immutable flag instead
        if shutil.which("chattr") is None or subprocess.run(["chattr", "+i", str(folder)]).returncode != 0:
            pytest.skip("running as root without chattr: cannot make a read-only folder")
        yield folder
        subprocess.run(["chattr", "-i", str(folder)])
    else:
        folder.chmod(0o555)
        yield folder
        folder.chmod(0o755)


def test_output_in_a_read_only_folder(small_project_file, read_only_dir, no_analysis):
    result = runner.invoke(app, ["check", str(small_project_file), "-o", str(read_only_dir), "--no-pdf"])
    _one_line_exit_2(result, "-o/--out", "read-only")
    result = runner.invoke(app, ["check", str(small_project_file), "-o", str(read_only_dir / "sub"), "--no-pdf"])
    _one_line_exit_2(result, "-o/--out", "read-only")


def test_folder_with_foreign_files_is_not_taken_over(small_project_file, tmp_path, no_analysis):
    (tmp_path / "notes.md").write_text("my notes")
    result = runner.invoke(app, ["check", str(small_project_file), "-o", str(tmp_path), "--no-pdf"])
    _one_line_exit_2(result, "did not write", "notes.md")
    assert (tmp_path / "notes.md").read_text() == "my notes"


def test_working_directory_is_not_replaced(small_project_file, tmp_path, monkeypatch, no_analysis):
    empty = tmp_path / "here"
    empty.mkdir()
    monkeypatch.chdir(empty)
    result = runner.invoke(app, ["check", str(small_project_file), "-o", ".", "--no-pdf"])
    _one_line_exit_2(result, "working directory")
    assert empty.is_dir() and Path.cwd() == empty


def test_busy_folder_is_refused(small_project_file, tmp_path, no_analysis):
    target = tmp_path / "out"
    with OutputFolder(target).locked():   # another run holds the folder
        result = runner.invoke(app, ["check", str(small_project_file), "-o", str(target), "--no-pdf"])
    _one_line_exit_2(result, "in use by another rockdesign run")
    assert not target.exists() and _leftovers(tmp_path, "out") == []


def test_concurrent_library_writes_are_refused(small_check, tmp_path):
    target = tmp_path / "out"
    with OutputFolder(target).locked():
        with pytest.raises(rd.OutputError, match="in use") as exc:
            rd.write_report(small_check, target, pdf=False, html=False)
    assert exc.value.key == "out_dir"
    rd.write_report(small_check, target, pdf=False, html=False)   # lock released: works
    assert _leftovers(tmp_path, "out") == []


def test_stale_files_of_an_earlier_run_are_removed(small_project_file, small_check, tmp_path):
    target = tmp_path / "out"
    rd.write_report(small_check, target, pdf=False, html=True)
    (target / "report.pdf").write_bytes(b"%PDF- an earlier project's report")
    result = runner.invoke(app, ["check", str(small_project_file), "-o", str(target), "--no-pdf", "--no-margins"])
    assert result.exit_code == 4, result.output    # --no-margins: not decided
    assert sorted(p.name for p in target.iterdir()) == ["results.csv", "results.json"]   # no stale report
    assert _leftovers(tmp_path, "out") == []


def test_interrupt_while_writing_leaves_the_old_folder(small_check, tmp_path, monkeypatch):
    target = tmp_path / "out"
    rd.write_report(small_check, target, pdf=False, html=False)
    before = {p.name: p.read_bytes() for p in target.iterdir()}

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt
    monkeypatch.setattr("rockdesign.library.write_document", interrupted)
    with pytest.raises(KeyboardInterrupt):
        rd.write_report(small_check, target, pdf=True, html=True)   # results.json already staged, then Ctrl-C
    assert {p.name: p.read_bytes() for p in target.iterdir()} == before
    assert _leftovers(tmp_path, "out") == []
    with pytest.raises(KeyboardInterrupt):
        rd.write_report(small_check, tmp_path / "new", pdf=True, html=True)
    assert not (tmp_path / "new").exists() and _leftovers(tmp_path, "new") == []


@pytest.mark.slow
def test_second_process_and_ctrl_c_during_the_analyses(tmp_path, small_project_file):
    # run A (a real process) analyses the example; run B into the same folder stops at once (exit 2);
    # a real SIGINT to A while the suite is analysed leaves no output folder and no temporary files
    target = tmp_path / "out"
    env = dict(os.environ, PYTHONPATH=str(REPO))
    proc = subprocess.Popen([sys.executable, "-m", "rockdesign.cli", "check", str(REPO / "examples" / "podium_flat.toml"),
                             "-o", str(target)], cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    lock = tmp_path / ".out.lock"
    deadline = time.monotonic() + 300
    while not lock.exists() and proc.poll() is None and time.monotonic() < deadline:   # the run has started
        time.sleep(0.1)
    assert lock.exists(), proc.stderr.read().decode()
    t0 = time.monotonic()
    second = runner.invoke(app, ["check", str(small_project_file), "-o", str(target), "--no-pdf"])
    _one_line_exit_2(second, "in use by another rockdesign run")
    assert time.monotonic() - t0 < 30
    time.sleep(2.0)
    assert proc.poll() is None, proc.stderr.read().decode()
    proc.send_signal(signal.SIGINT)
    proc.communicate(timeout=120)
    assert proc.returncode != 0
    assert not target.exists()
    assert [p.name for p in tmp_path.iterdir()] == []
