"""Every command that runs numerical kernels compiles them on its first run *after* checking its input,
and says so ("first run: compiling the numerical kernels of `check` (about N s, once per version)"), naming
the groups of kernels it runs: none compiles 30–70 s behind a bar that does not move, or in silence."""
from __future__ import annotations

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.execution import compilation
from rockdesign.paths import REPO_ROOT

PIER = str(REPO_ROOT / "examples" / "bridge_pier.toml")
CYLINDER = str(REPO_ROOT / "examples" / "cylinder.toml")


@pytest.fixture
def prepared(monkeypatch):
    """The commands ``prepare`` was asked for, and a first-run announcement as it would be printed."""
    asked = []

    def prepare(command, kernels, say=None):
        asked.append((command, tuple(k.name for k in kernels)))
        if say is not None:
            say(compilation.announcement(command, kernels))
        return 0.0

    monkeypatch.setattr(compilation, "prepare", prepare)
    return asked


@pytest.mark.parametrize("command,kernels,args", [
    ("records", ("elastic-spectrum",), ["records", "spectrum", "p695-ff/11a", "--n-periods", "20"]),
    ("records", ("elastic-spectrum",), ["records", "synth", "--seed", "p695-ff/11a", "-n", "2", "-o", "{tmp}/synth"]),
    ("ensemble", ("planar-engine",), ["ensemble", PIER, "--suite", "{tmp}/suite.toml", "-o", "{tmp}/analyses.csv"]),
    ("spectrum", ("planar-pulse-spectrum",), ["spectrum", PIER, "--pulse", "ricker-anti", "--x", "omega_p/p:1:4:2",
                                              "--y", "ap/up:0:4:2", "-o", "{tmp}/spectrum"]),
    ("simulate", ("cylinder-integrator",), ["simulate", CYLINDER, "--motion", "record:p695-ff/11", "--t-end", "2"]),
    ("bench", ("planar-engine", "planar-linear-exact"),
     ["bench", "--quick", "--no-stability", "--only", "free-vibration/housner-block", "-o", "{tmp}/bench"]),
    pytest.param("spectrum", ("cylinder-spectrum",), ["spectrum", CYLINDER, "--record", "p695-ff/11", "--x", "R:0.8:1:2",
                                                      "--y", "pga/up:1:2:2", "-o", "{tmp}/cylinder-spectrum"],
                 marks=pytest.mark.slow),   # compiles the 3D spectrum kernels (≈ 30 s)
])
def test_each_command_announces_its_own_kernels(command, kernels, args, prepared, tmp_path):
    # (an ensemble with a record that is not available is refused before compiling: two built-in records)
    (tmp_path / "suite.toml").write_text('name = "two"\n[[records]]\nid = "p695-ff/3a"\n[[records]]\n'
                                         'id = "p695-ff/4a"\n')
    result = CliRunner().invoke(app, [a.format(tmp=tmp_path) for a in args])
    assert result.exit_code == 0, result.output
    assert prepared == [(command, kernels)]
    assert f"first run: compiling the numerical kernels of `{command}`" in " ".join(result.stderr.split())
    if command == "bench":   # runs for minutes: stderr is not a terminal here, so plain lines as a stage starts and ends
        assert "work-precision problems" in result.stderr and "done in" in result.stderr


@pytest.mark.parametrize("args", [
    ["ensemble", PIER, "--suite", "nosuch", "-o", "{tmp}/analyses.csv"],
    ["ensemble", PIER, "--suite", "thesis-table-4.1", "--scale", "-1", "-o", "{tmp}/analyses.csv"],
    ["simulate", CYLINDER, "--motion", "record:nosuch/11"],
    ["simulate", CYLINDER, "--motion", "record:p695-ff/11", "--model", "bogus"],
    ["spectrum", CYLINDER, "--record", "p695-ff/11", "--x", "R:0.8:1", "--y", "bogus:1:2:2"],
    ["records", "spectrum", "nosuch/11a"],
    ["spectrum", CYLINDER, "--record", "p695-ff/11", "--x", "R:0.8:1:2", "--y", "pga/up:1:2:2",
     "--relative", PIER, "-o", "{tmp}/cylinder-spectrum"],
])
def test_bad_input_is_refused_before_compiling(args, prepared, tmp_path):
    result = CliRunner().invoke(app, [a.format(tmp=tmp_path) for a in args])
    assert result.exit_code == 2, result.output
    assert prepared == [] and result.stderr.strip().startswith("error:"), result.output


@pytest.mark.parametrize("args", [["ensemble", PIER, "--suite", "nosuch", "-o", "analyses.csv"],
                                  ["records", "list", "--suite", "nosuch"]])
def test_an_unknown_suite_names_the_option_the_user_typed(args):
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 2 and "key '--suite'" in result.stderr, result.output
