"""The library names a parameter, the command line names its flag (docs/architecture.md): the same bad input
raises an error keyed ``motion`` from ``rd.simulate`` and prints ``key '--motion'`` from ``simulate`` — the
mapping lives in ``cli/app.py`` (a parameter named like the command's option, or an alias) and nowhere below."""
from __future__ import annotations

import pytest
from typer.testing import CliRunner

import rockdesign as rd
from rockdesign.cli import app
from rockdesign.paths import REPO_ROOT

PIER = str(REPO_ROOT / "examples" / "bridge_pier.toml")
CYLINDER = str(REPO_ROOT / "examples" / "cylinder.toml")
SMALL = ["--x", "omega_p/p:1:2:2", "--y", "ap/up:1:2:2"]

CASES = [
    # (command line, its flag, the library call, its parameter)
    (["simulate", PIER, "--motion", "sine:ap=0.3g,Tp=-1s"], "--motion",
     lambda: rd.simulate(rd.load_project(PIER), "sine:ap=0.3g,Tp=-1s"), "motion"),
    (["simulate", PIER, "--motion", "sine:ap=0.3g,Tp=1s", "--model", "bogus"], "--model",
     lambda: rd.simulate(rd.load_project(PIER), "sine:ap=0.3g,Tp=1s", model="bogus"), "model"),
    (["simulate", CYLINDER, "--motion", "record:p695-ff/11", "--model", "exact"], "--model",
     lambda: rd.simulate(rd.load_project(CYLINDER), "record:p695-ff/11", model="exact"), "model"),
    (["spectrum", PIER, "--pulse", "sine", *SMALL, "--dask", "local:0"], "--dask",
     lambda: rd.spectrum(rd.load_project(PIER), pulse="sine", executor="local:0"), "executor"),
    (["spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:2:1:3"], "--x",
     lambda: rd.spectrum(rd.load_project(PIER), pulse="sine", x="omega_p/p:2:1:3"), "x"),
    (["spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:0.5:12:100000", "--y", "ap/up:0:12:100000"], "--x/--y",
     lambda: rd.spectrum(rd.load_project(PIER), pulse="sine", x="omega_p/p:0.5:12:100000",
                         y="ap/up:0:12:100000"), "x/y"),
    (["spectrum", PIER, "--pulse", "sine", "--overturn", "dynamic", "--stop-at-capacity"], "--stop-at-capacity",
     lambda: rd.spectrum(rd.load_project(PIER), pulse="sine", overturn="dynamic", stop_at_capacity=True),
     "stop_at_capacity"),
    (["spectrum", CYLINDER, "--record", "p695-ff/11", "--pulse", "sine"], "--pulse",
     lambda: rd.spectrum(rd.load_project(CYLINDER), record="p695-ff/11", pulse="sine"), "pulse"),
    (["spectrum", CYLINDER, "--record", "p695-ff/11", "--no-resume"], "--resume/--no-resume",
     lambda: rd.spectrum(rd.load_project(CYLINDER), record="p695-ff/11", resume=False), "resume"),
    (["records", "spectrum", "p695-ff/11a", "--damping", "abc"], "--damping",
     lambda: rd.records_spectrum("p695-ff/11a", damping="abc"), "damping"),
    (["records", "list", "--gravity", "1"], "--gravity", lambda: rd.records_list(gravity=1.0), "gravity"),
    (["records", "scale-model", "p695-ff/11a", "--length-ratio", "0.1", "--table", "a=1g,a=2g"], "--table a",
     lambda: rd.records_scale_model("p695-ff/11a", 0.1, table="a=1g,a=2g"), "table.a"),
    (["calibrate", PIER, "--free-vibration", str(REPO_ROOT / "examples" / "free_vibration.csv"), "--min-amplitude",
      "2"], "--min-amplitude",
     lambda: rd.calibration(rd.load_project(PIER), REPO_ROOT / "examples" / "free_vibration.csv", min_amplitude=2.0),
     "min_amplitude"),
    (["ensemble", PIER, "--suite", "thesis-table-4.1", "-o", "{tmp}/a.csv", "--restitution", "0"], "--restitution",
     lambda: rd.ensemble(rd.load_project(PIER), "thesis-table-4.1", restitution=0.0), "restitution"),
    (["bench", "--only", "no-such-problem", "-o", "{tmp}/b"], "--only",
     lambda: rd.benchmark("b", only="no-such-problem"), "only"),
]


@pytest.fixture
def no_compiling(monkeypatch):
    import rockdesign.execution.compilation as compilation

    def refuse(*args, **kwargs):
        raise AssertionError("compiled kernels for a bad input")
    monkeypatch.setattr(compilation, "prepare", refuse)


@pytest.mark.parametrize("args,flag,call,parameter", CASES, ids=[f"{c[1]}" for c in CASES])
def test_the_command_line_names_the_flag_the_library_the_parameter(args, flag, call, parameter, tmp_path,
                                                                   monkeypatch, no_compiling):
    monkeypatch.chdir(tmp_path)
    r = CliRunner().invoke(app, [a.replace("{tmp}", str(tmp_path)) for a in args])
    assert r.exit_code == 2, r.output
    errors = [line for line in r.stderr.splitlines() if line.startswith("error:")]
    assert len(errors) == 1 and f"key '{flag}'" in errors[0], r.stderr
    with pytest.raises(rd.RockdesignError) as err:
        call()
    assert err.value.key == parameter, str(err.value)
    assert "--" not in f"key '{err.value.key}'"
