"""``rockdesign design`` as safe as ``check`` (issue 42): every input problem is found before any analysis
(exit 2, one line naming the option, key or file), and a typo is never a grid of INVALID cells."""
from __future__ import annotations

import socket
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.paths import REPO_ROOT

runner = CliRunner()
CURVED = REPO_ROOT / "examples" / "podium_curved.toml"
CYLINDER = REPO_ROOT / "examples" / "cylinder.toml"


def refuse_analysing(monkeypatch):
    """Bad input is refused before any kernel compiles or any variant is analysed."""
    import rockdesign.design_space.batches as batches
    import rockdesign.execution.compilation as compilation

    def boom(*args, **kwargs):
        raise AssertionError("compiled or analysed for a bad input")
    monkeypatch.setattr(compilation, "prepare", boom)
    monkeypatch.setattr(batches.VariantChecker, "check", boom)


def one_line_error(result, *fragments):
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert "Traceback" not in result.output, result.output
    text = " ".join(result.stderr.split())
    assert len([ln for ln in result.stderr.splitlines() if ln.startswith("error:")]) == 1, result.stderr
    for f in fragments:
        assert f in text, (f, text)
    return text


def design(*args):
    return runner.invoke(app, ["design", *[str(a) for a in args]])


@pytest.mark.parametrize("vary, fragments", [
    # typos and keys the project file does not take: before any analysis, not a grid of INVALID cells
    ("podium.widht=0.3m:0.5m:2", ["no such key", "podium.widht", "did you mean 'width'"]),
    ("podium.theta_c=0.1:0.2:2", ["a design quantity, not a key", "podium.theta_c"]),
    ("podium.diameter=0.4m:0.5m:2", ["no such key", "podium.diameter"]),          # a cylinder's key
    ("cylinder.diameter=0.4m:0.5m:2", ["no such table", "[cylinder]"]),
    ("analysis.overturn=1:2:2", ["not a numeric key", "analysis.overturn"]),     # a string key
    ("analysis.equations=1:2:2", ["not a numeric key", "analysis.equations"]),
    ("analysis.acceptance=1:2:2", ["do not fit the key", "analysis.acceptance"]),  # a string key the file omits
    ("podium.curvature=0.1m:0.5m:2", ["plain numbers", "podium.curvature"]),        # a unit on a dimensionless key
    ("podium.mass_distribution=1s:2s:2", ["plain numbers", "podium.mass_distribution"]),
    ("podium.width=0.3:0.5:2", ["do not fit the key", "podium.width", "length"]),  # no unit on a length
    ("podium.width=0.3s:0.5s:2", ["do not fit the key", "podium.width"]),
    ("podium.width=0.5m:0.4m:1", ["one value but two ends", "0.5m:0.4m:1"]),      # FROM > TO with N = 1
    ("podium.width=0.5m:0.4m:3", ["FROM is above TO", "0.5m > 0.4m"]),
    ("podium.width=0.3m:0.5m:0", ["out of range", "N = 0"]),
    ("podium.width=0.3m:0.5m:42", ["out of range", "N = 42"]),
    ("podium.columns=6:10:4", ["whole numbers"]),
    ("podium.width=1e999m:2e999m:2", ["finite"]),
    ("podium.width=0.60m:0.70m:2", ["no variant of the grid is a valid project", "extended_width"]),
])
def test_a_bad_variable_is_an_input_error_before_any_analysis(tmp_path, monkeypatch, vary, fragments):
    refuse_analysing(monkeypatch)
    out = tmp_path / "d"
    res = design(CURVED, "--vary", vary, "-o", out, "--no-pdf")
    one_line_error(res, "key '--vary'", *fragments)
    assert not out.exists() and not list(tmp_path.iterdir())        # no folder left behind


@pytest.mark.parametrize("second", ["podium.slenderness=0.1:0.2:2", "podium.width=0.4m:0.5m:2"])
def test_two_keys_that_say_the_same_thing_are_refused(tmp_path, monkeypatch, second):
    """Varying width with slenderness followed slenderness while labelling the cells by width."""
    refuse_analysing(monkeypatch)
    res = design(CURVED, "--vary", "podium.width=0.36m:0.44m:2", "--vary", second, "-o", tmp_path / "d", "--no-pdf")
    one_line_error(res, "key '--vary'", "podium.width")


def test_cylinder_aliases_are_refused_together(tmp_path, monkeypatch):
    refuse_analysing(monkeypatch)
    res = design(CYLINDER, "--vary", "cylinder.mass=1t:2t:2", "--vary", "cylinder.density=2t/m^3:3t/m^3:2",
                 "-o", tmp_path / "d", "--no-pdf")
    one_line_error(res, "key '--vary'", "say the same thing", "cylinder.mass and cylinder.density")


@pytest.mark.parametrize("address, fragments", [
    ("", ["empty dask address"]),
    (" ", ["empty dask address"]),
    ("local:0", ["invalid local cluster"]),
    ("local:x", ["invalid local cluster"]),
    ("inproc://x", ["unknown transport"]),
    ("tcp://host", ["invalid dask scheduler address"]),
    ("nohost", ["invalid dask scheduler address"]),
])
def test_dask_addresses_are_validated_before_any_analysis(tmp_path, monkeypatch, address, fragments):
    """--dask "" or " " silently ran locally; a typo named the wrong problem."""
    refuse_analysing(monkeypatch)
    out = tmp_path / "d"
    res = design(CURVED, "--vary", "podium.width=0.36m:0.44m:2", "--dask", address, "-o", out, "--no-pdf")
    one_line_error(res, "key '--dask'", *fragments)
    assert not out.exists()


@pytest.mark.parametrize("scheme", ["tcp://", "tls://", ""])
def test_an_unreachable_scheduler_is_refused_at_once(tmp_path, monkeypatch, scheme):
    """tls://… ended in a TypeError traceback; localhost:1 was called 'an invalid local cluster'."""
    refuse_analysing(monkeypatch)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    host = "localhost" if not scheme else "127.0.0.1"
    res = design(CURVED, "--vary", "podium.width=0.36m:0.44m:2", "--dask", f"{scheme}{host}:{port}",
                 "-o", tmp_path / "d", "--no-pdf")
    one_line_error(res, "key '--dask'", "cannot reach the dask scheduler", str(port))


def test_a_tls_address_without_certificates_is_an_input_error():
    """dask raises TypeError for tls:// without a TLS configuration: an input error, not a traceback."""
    from rockdesign.execution.executor import DaskExecutor, ExecutorError
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        with pytest.raises(ExecutorError, match="TLS certificates"):   # refused when made (dask's handshake probe)
            DaskExecutor(f"tls://127.0.0.1:{s.getsockname()[1]}").start()


def test_a_cylinder_refuses_records_dir(tmp_path, monkeypatch):
    refuse_analysing(monkeypatch)
    res = design(CYLINDER, "--vary", "cylinder.diameter=0.5m:0.6m:2", "--records-dir", tmp_path, "-o", tmp_path / "d")
    one_line_error(res, "key '--records-dir'", "not used by the check of a cylinder")


# ------------------------------------------------------------------ -o: check's protection
def _user_folder(tmp_path, name="design.csv") -> Path:
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("my own notes")
    (out / name).write_text("my own table")
    return out


@pytest.mark.parametrize("make, fragments", [
    (lambda t: _user_folder(t), ["holds files rockdesign did not write", "notes.txt"]),
    (lambda t: ((t / "taken").write_text("x"), t / "taken")[-1], ["is a file"]),
    (lambda t: ((t / "file").write_text("x"), t / "file" / "sub")[-1], ["is not a folder"]),
    (lambda t: ((t / "link").symlink_to(t / "nowhere"), t / "link")[-1], ["dangling symbolic link"]),
    (lambda t: ((t / "d").mkdir(), (t / "d" / "variants").write_text("x"), t / "d")[-1],
     ["holds files rockdesign did not write", "variants"]),
    (lambda t: ((t / "d").mkdir(), (t / "d" / "variants").mkdir(), (t / "d" / "variants" / "x.txt").write_text("x"),
                t / "d")[-1], ["holds files rockdesign did not write", "variants"]),
])
def test_the_output_folder_is_checked_before_any_analysis(tmp_path, monkeypatch, make, fragments):
    """-o overwrote a user's own design.csv and ended in tracebacks on a dangling link, a path under a file
    or a 'variants' file."""
    refuse_analysing(monkeypatch)
    out = make(tmp_path)
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    res = design(CURVED, "--vary", "podium.width=0.36m:0.44m:2", "-o", out, "--no-pdf")
    one_line_error(res, "key '-o/--out'", *fragments)
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before   # nothing created or changed


def test_an_input_error_leaves_no_folder_and_no_parents(tmp_path, monkeypatch):
    refuse_analysing(monkeypatch)
    res = design(CURVED, "--vary", "podium.widht=0.3m:0.5m:2", "-o", tmp_path / "a" / "b" / "d")
    one_line_error(res, "key '--vary'")
    assert list(tmp_path.iterdir()) == []


def test_a_folder_in_use_is_refused(tmp_path, monkeypatch):
    from rockdesign.outdir import DesignFolder
    refuse_analysing(monkeypatch)
    with DesignFolder(tmp_path / "d").locked():
        res = design(CURVED, "--vary", "podium.width=0.36m:0.44m:2", "-o", tmp_path / "d", "--no-pdf")
    one_line_error(res, "key '-o/--out'", "in use by another rockdesign run")


def test_library_errors_name_the_parameters(tmp_path):
    import rockdesign as rd
    project = rd.load_project(CURVED)
    with pytest.raises(rd.RockdesignError, match="key 'vary'"):
        rd.plan_design(project, ["podium.widht=0.3m:0.5m:2"])
    with pytest.raises(rd.RockdesignError, match="key 'vary'.*one or two"):
        rd.plan_design(project, [])
    with pytest.raises(rd.RockdesignError, match="key 'vary'.*strings"):
        rd.plan_design(project, [1])
    (tmp_path / "f").write_text("x")
    with pytest.raises(rd.RockdesignError, match="key 'out_dir'"):
        rd.design(project, "podium.width=0.36m:0.44m:2", out_dir=tmp_path / "f")
    cylinder = rd.load_project(CYLINDER)
    with pytest.raises(rd.RockdesignError, match="key 'records_dir'"):
        rd.plan_design(cylinder, "cylinder.diameter=0.5m:0.6m:2", records_dir=tmp_path)
