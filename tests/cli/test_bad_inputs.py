"""Bad input never gives a traceback or exit 1: every command answers with one line naming the key or
file and exit code 2, before any analysis runs (issue: "what a new user broke in an afternoon").

Also: failed analyses are not results (exit 2), Ctrl-C is exit 130 with one line, a UTF-8 BOM is
accepted, implausible records warn."""
from __future__ import annotations

import json
import re
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.paths import REPO_ROOT

runner = CliRunner()
PIER = str(REPO_ROOT / "examples" / "bridge_pier.toml")
PULSE = "ricker-anti:ap=0.38g,Tp=0.95s"

COLUMN = """\
[project]
name = "test column"

[column]
height = "3 m"
slenderness = 0.1
mass = "1 t"
mass_distribution = 0.3333
"""


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def assert_one_line_error(result, *fragments):
    """Exit 2, one 'error:' line on stderr naming what is wrong, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
    text = result.stderr.strip()
    assert text.startswith("error:") and "Traceback" not in result.output, result.output
    flat = " ".join(text.split())
    assert len([ln for ln in text.splitlines() if ln.startswith("error:")]) == 1
    for f in fragments:
        assert f in flat, (f, flat)
    return flat


def write(tmp_path, text, name="p.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


# ------------------------------------------------------------------------------ simulate options
@pytest.mark.parametrize("extra,key,found", [
    (["--t-end", "-5"], "--t-end", "-5"),
    (["--t-end", "nan"], "--t-end", "nan"),
    (["--t-end", "inf"], "--t-end", "inf"),
    (["--t-end", "0"], "--t-end", "0"),
    (["--rtol", "-1"], "--rtol", "-1"),
    (["--rtol", "0.5"], "--rtol", "0.5"),
    (["--rtol", "0"], "--rtol", "0"),
    (["--rtol", "nan"], "--rtol", "nan"),
    (["--plot", "out.xyz"], "--plot", "out.xyz"),
    (["--plot", "noext"], "--plot", "noext"),
    (["--plot", "/nonexistent/dir/x.png"], "--plot", "/nonexistent/dir"),
    (["--csv", "/nonexistent/dir/x.csv"], "--csv", "/nonexistent/dir"),
])
def test_simulate_bad_options(extra, key, found):
    r = invoke("simulate", PIER, "--motion", PULSE, *extra)
    assert_one_line_error(r, f"key '{key}'", found)


@pytest.mark.parametrize("motion", ["sine:ap=0.3g,Tp=1s,t0=-5s", "ricker-sym:ap=0.3g,Tp=1s,tm=-1s",
                                    "free:theta0=5rad", "free:theta0=nan", "record:p695-ff/11a,scale=nan",
                                    "record:p695-ff/11a,scale=inf", "ricker-anti:ap=nan,Tp=1s",
                                    "ricker-anti:ap=0.3g,Tp=-1s", "ricker-anti:ap=0.3g,Tp=inf"])
def test_simulate_bad_motions(motion):
    assert_one_line_error(invoke("simulate", PIER, "--motion", motion), "key '--motion'")


@pytest.mark.parametrize("args,fragments", [
    (["--motion", "free:theta0=nan"], ["key '--motion'"]),
    (["--motion", "record:p695-ff/11a,scale=inf"], ["key '--motion'"]),
    (["--motion", PULSE, "--model", "bogus"], ["key '--model'", "'bogus'"]),
    (["--motion", "record:p695-ff/11a", "--t-end", "1e9"], ["too much memory"]),
    (["--motion", PULSE, "--model", "linear-exact"], ["key '--model'", "SDOF systems only"]),
])
def test_simulate_refuses_bad_input_before_compiling(args, fragments, monkeypatch):
    # a first run compiles the engine (≈ 30 s): a typo must not wait for it
    import rockdesign.execution.compilation as compilation

    def compile_first(*a, **k):  # pragma: no cover - must not run
        raise AssertionError("the kernels were prepared before the input was checked")

    monkeypatch.setattr(compilation, "prepare", compile_first)
    project = PIER if "linear-exact" not in args else str(REPO_ROOT / "examples" / "podium_flat.toml")
    assert_one_line_error(invoke("simulate", project, *args), *fragments)


def test_simulate_csv_into_a_directory(tmp_path):
    assert_one_line_error(invoke("simulate", PIER, "--motion", PULSE, "--csv", tmp_path), "key '--csv'",
                          "a directory")


def test_bad_output_files_are_refused_before_the_analysis(tmp_path, monkeypatch):
    # nothing is analysed (the engine is not even called) when the output cannot be written
    import rockdesign.library as library

    def boom(*a, **k):  # pragma: no cover - must not run
        raise AssertionError("the analysis ran before the output was checked")

    monkeypatch.setattr(library, "run_simulation", boom)
    assert_one_line_error(invoke("simulate", PIER, "--motion", PULSE, "--plot", tmp_path / "x.jpg"), "--plot")


@pytest.mark.parametrize("motion,extra,found", [
    ("ricker-anti:ap=0.38g,Tp=1e-6s", [], "output times"),
    ("sine:ap=0.3g,Tp=1e-7s", [], "output times"),
    (PULSE, ["--t-end", "1e7"], "t_end = 1e+07 s"),
    ("record:p695-ff/11a", ["--t-end", "1e9"], "t_end = 1e+09 s"),
])
def test_memory_is_estimated_up_front(motion, extra, found):
    t0 = time.perf_counter()
    r = invoke("simulate", PIER, "--motion", motion, *extra)
    flat = assert_one_line_error(r, "too much memory", found, "GB")
    assert time.perf_counter() - t0 < 30      # refused at once, not after allocating


def test_simulate_shows_the_resolved_pulse():
    r = invoke("simulate", "examples/podium_flat.toml", "--motion", "ricker-anti:ap=2.5up,wp=3p", "--json")
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    from rockdesign.planar.design.quantities import design_quantities
    from rockdesign.library import load_project
    q = design_quantities(load_project("examples/podium_flat.toml").system)
    assert data["motion_parameters"]["a_p"] == pytest.approx(2.5 * q["uplift_acceleration"].value, rel=1e-12)
    assert data["motion_parameters"]["T_p"] == pytest.approx(2 * math.pi / (3 * q["p"].value), rel=1e-12)
    table = invoke("simulate", "examples/podium_flat.toml", "--motion", "ricker-anti:ap=2.5up,wp=3p", "--t-end", "6")
    assert "pulse amplitude a_p" in table.stdout and "pulse period T_p" in table.stdout


# ------------------------------------------------------------------------------ records / quantities options
@pytest.mark.parametrize("args,key,found", [
    (["records", "show", "p695-ff/11a", "--gravity", "0"], "--gravity", "0.0"),
    (["records", "show", "p695-ff/11a", "--gravity", "-9.81"], "--gravity", "-9.81"),
    (["records", "show", "p695-ff/11a", "--gravity", "nan"], "--gravity", "nan"),
    (["records", "spectrum", "p695-ff/11a", "--gravity", "-1"], "--gravity", "-1"),
    (["records", "list", "--gravity", "0"], "--gravity", "0"),
    (["records", "show", "p695-ff/11a", "--plot", "x.bmp"], "--plot", "x.bmp"),
    (["records", "spectrum", "p695-ff/11a", "--plot", "/nonexistent/dir/s.png"], "--plot", "/nonexistent"),
    (["quantities", PIER, "--pushover", "curve.txt"], "--pushover", "curve.txt"),
])
def test_records_and_quantities_bad_options(args, key, found):
    assert_one_line_error(invoke(*args), f"key '{key}'", found)


@pytest.mark.parametrize("args", [["bench", "--quick", "-o", "{file}"], ["spectrum", PIER, "--pulse", "ricker-anti",
                                                                        "-o", "{file}"],
                                  ["bench", "--quick", "-o", "{file}/sub"]])
def test_output_folder_that_is_a_file(tmp_path, args):
    target = write(tmp_path, "x", "taken.txt")
    r = invoke(*[a.format(file=target) for a in args])
    assert_one_line_error(r, str(target))
    assert target.read_text() == "x"


def test_synth_into_an_existing_file(tmp_path):
    target = write(tmp_path, "x", "taken.txt")
    assert_one_line_error(invoke("records", "synth", "--seed", "p695-ff/11a", "-n", "2", "-o", target),
                          "key '--out'", "an existing file")
    assert target.read_text() == "x"


def test_records_list_help_units():
    r = invoke("records", "list", "--help")
    assert "PGA in g" in " ".join(r.output.split())


def test_version_flag_has_no_bool_metavar():
    r = invoke("--help")
    line = next(ln for ln in r.output.splitlines() if "--version" in ln)
    assert "<bool>" not in line
    assert invoke("--version").exit_code == 0


@pytest.mark.parametrize("command", [["init"], ["quantities"], ["simulate"], ["check"], ["spectrum"], ["bench"],
                                     ["calibrate"], ["validate"], ["ensemble"], ["records", "list"],
                                     ["records", "scale-model"], ["records", "synth"]])
def test_no_option_shows_a_bool_metavar(command):
    r = invoke(*command, "--help")
    assert r.exit_code == 0, r.output
    lines = [ln for ln in r.output.splitlines() if "<bool>" in ln and "--help" not in ln]
    assert not lines, lines


# ------------------------------------------------------------------------------ project keys, every command
BAD_PROJECTS = [
    ('[analysis]\nfree_vibration = "-10 s"\n', "analysis.free_vibration", "-10 s"),
    ('[analysis]\nfree_vibration = "10 m"\n', "analysis.free_vibration", None),
    ('[excitation]\ndesign_pga = "0.35 kg"\n', "excitation.design_pga", "0.35 kg"),
    ('[excitation]\ndesign_pga = "-0.35 g"\n', "excitation.design_pga", None),
    ('[excitation]\nrecords = ["p695-ff/11a"]\nscale = { method = "magic", target = "0.3 g" }\n',
     "excitation.scale.method", "magic"),
    ('[excitation]\nrecords = ["p695-ff/11a"]\nscale = { method = "factor", value = -2.0 }\n',
     "excitation.scale.value", "-2.0"),
    ('[excitation]\nrecords = ["p695-ff/11a"]\nscale = { method = "pga", target = "-0.2 g" }\n',
     "excitation.scale.target", "-0.2 g"),
    ('[excitation]\nrecords = ["p695-ff/11a"]\nscale = { method = "uplift", multiple = -1 }\n',
     "excitation.scale.multiple", "-1"),
    ('[excitation]\nrecords = ["p695-ff/11a"]\nscale = { method = "sdmax", target = "0 m" }\n',
     "excitation.scale.target", None),
    ('[excitation]\ndesign_pga = "0.35 g"\nscale = { method = "pga", target = "0.20 g" }\n',
     "excitation.scale.target", "conflicting design intensities"),
    ('[excitation]\ndesign_pga = "0.35 g"\nscale = { method = "factor", value = 1.0 }\n',
     "excitation.design_pga", "not used by scale method 'factor'"),
    ('[excitation]\ndesign_pga = "0.3 g"\nsuites = []\n', "excitation.suites", "empty suites list"),
    ('[excitation]\ndesign_pga = "0.3 g"\nrecords = []\n', "excitation.records", "empty records list"),
    ('[excitation]\ndesign_pga = "0.3 g"\nsuites = ["p695-farfeild"]\n', "excitation.suites[0]", None),
]


@pytest.mark.parametrize("command", ["quantities", "simulate", "check"])
@pytest.mark.parametrize("extra,key,found", BAD_PROJECTS)
def test_every_command_validates_every_key(tmp_path, command, extra, key, found):
    path = write(tmp_path, COLUMN + extra)
    args = {"quantities": [], "simulate": ["--motion", PULSE], "check": ["-o", tmp_path / "out"]}[command]
    r = invoke(command, path, *args)
    assert_one_line_error(r, str(path), f"key '{key}'", *([found] if found else []))
    assert not (tmp_path / "out").exists()


def test_the_same_intensity_twice_is_fine(tmp_path):
    path = write(tmp_path, COLUMN + '[excitation]\ndesign_pga = "0.35 g"\nscale = { method = "pga", '
                 'target = "3.4335 m/s^2" }\n')
    assert invoke("quantities", path).exit_code == 0


def test_utf8_bom_is_accepted(tmp_path):
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + Path(PIER).read_bytes())
    r = invoke("quantities", path, "--json")
    assert r.exit_code == 0, r.output
    plain = invoke("quantities", PIER, "--json")
    assert json.loads(r.stdout)["quantities"] == json.loads(plain.stdout)["quantities"]


def test_utf8_bom_in_a_suite_manifest(tmp_path):
    manifest = tmp_path / "s.toml"
    manifest.write_bytes(b"\xef\xbb\xbf" + b'name = "s"\n[[records]]\nid = "p695-ff/3a"\n')
    r = invoke("records", "list", "--suite", manifest, "--json")
    assert r.exit_code == 0, r.output
    assert [row["id"] for row in json.loads(r.stdout)] == ["p695-ff/3a"]


# ------------------------------------------------------------------------------ records that cannot be right
def _at2(path, values, dt=0.01):
    head = ("PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Nowhere, 0\n"
            f"ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=  {len(values)}, DT=   {dt:.4f} SEC\n")
    path.write_text(head + "\n".join(f"{v:.6e}" for v in values) + "\n")
    return path


def test_implausible_records_warn(tmp_path):
    huge = _at2(tmp_path / "huge.AT2", [0.0] + [1e30 * math.sin(0.3 * i) for i in range(1, 50)])
    slow = _at2(tmp_path / "slow.AT2", [0.0, 0.1, -0.1, 0.05, 0.0], dt=100.0)
    r = invoke("records", "show", f"file:{huge}")
    assert r.exit_code == 0 and re.search(r"PGA = 9\.99e\+29 g is implausible", r.stderr)
    r = invoke("records", "show", f"file:{slow}")
    assert r.exit_code == 0 and "dt = 100 s is implausible" in " ".join(r.stderr.split())


def test_all_zero_record_has_no_predominant_frequency(tmp_path):
    zero = _at2(tmp_path / "zero.AT2", [0.0] * 100)
    r = invoke("records", "show", f"file:{zero}")
    assert r.exit_code == 0, r.output
    line = next(ln for ln in r.stdout.splitlines() if "predominant frequency" in ln)
    assert "n/a" in line and "Hz" not in line
    assert "all zeros" in r.stderr
    r = invoke("records", "spectrum", f"file:{zero}", "--json")
    assert json.loads(r.stdout)["predominant_frequency"] is None


# ------------------------------------------------------------------------------ failed analyses
PODIUM_2DOF = """\
[project]
name = "podium"

[podium]
columns = 36
cap_beam_mass = "290 t"
height = "3.0 m"
width = "0.45 m"
density = "2.5 t/m^3"
depth = "0.45 m"
mass_distribution = 0.3333

[superstructure]
mass = "2160 t"
period = "{period}"
damping = "2 %"

[analysis]
model = "podium-2dof"
"""


def test_simulate_failed_analysis_is_exit_2(tmp_path):
    huge = _at2(tmp_path / "huge.AT2", [0.0] + [1e30 * math.sin(0.3 * i) for i in range(1, 200)])
    path = write(tmp_path, PODIUM_2DOF.format(period="0.38 s"))
    r = invoke("simulate", path, "--motion", f"file:{huge}", "--model", "linear")
    assert r.exit_code == 2
    assert "the analysis failed: step size collapsed" in " ".join(r.stderr.split())


def test_check_never_counts_a_failed_analysis_as_safe(tmp_path):
    huge = _at2(tmp_path / "huge.AT2", [0.0] + [1e30 * math.sin(0.3 * i) for i in range(1, 200)])
    # one record: the binomial rule with a limit one ground motion can show (ASCE 7's needs 11)
    text = PODIUM_2DOF.format(period="0.38 s").replace("[analysis]\n", '[analysis]\nacceptance = "binomial"\n'
                                                       "overturn_probability_limit = 0.95\n")
    path = write(tmp_path, text + f'[excitation]\nrecords = ["file:{huge}"]\n'
                 'scale = { method = "factor", value = 1.0 }\n')
    out = tmp_path / "out"
    r = invoke("check", path, "-o", out, "--no-pdf", "--no-margins")
    assert r.exit_code == 2, r.output
    data = json.loads((out / "results.json").read_text(encoding="utf-8"))
    assert data["verdict"] == "FAIL"
    assert data["failed_records"] == [{"id": f"file:{huge}", "status": "step size collapsed"}]
    assert data["records"][0]["analysis_failed"] is True
    assert data["summary"]["n_records"] == 0 and data["summary"]["n_failed"] == 1
    assert "analysis(es) failed" in data["verdict_reason"]
    assert "analysis failed:" in r.output and "not counted as safe" in " ".join(r.output.split())
    assert "PGA = 1e+30 g is implausible" in " ".join(r.output.split())


@pytest.mark.slow
def test_stiff_superstructure_event_limit_is_a_failure(tmp_path):
    # period = 1e-5 s: the 2DOF podium chatters until the event limit (it used to print θ_max = 0, safe)
    path = write(tmp_path, PODIUM_2DOF.format(period="1e-5 s"))
    r = invoke("simulate", path, "--motion", "record:p695-ff/11a", "--json")
    assert r.exit_code == 2
    data = json.loads(r.stdout)
    assert data["solver"]["status"] in ("event limit reached", "step limit reached", "step size collapsed")
    assert "the analysis failed" in r.stderr


# ------------------------------------------------------------------------------ Ctrl-C
@pytest.mark.slow
@pytest.mark.parametrize("delay", [4.0, 6.5])   # in the margins stage (the --no-pdf check takes ≈ 10 s)
def test_ctrl_c_is_exit_130_with_one_line(tmp_path, delay):
    env = dict(os.environ, PYTHONPATH=str(REPO_ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    proc = subprocess.Popen([sys.executable, "-m", "rockdesign.cli", "check", "examples/podium_flat.toml", "-o",
                             str(tmp_path / "out"), "--no-pdf"], cwd=REPO_ROOT, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    time.sleep(delay)
    if proc.poll() is not None:   # pragma: no cover - machine much faster than expected
        pytest.skip("the check finished before the interrupt")
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=300)
    if "output:" in out:          # pragma: no cover - the check had written its results: its verdict stands
        assert proc.returncode in (0, 1), err[-2000:]
        pytest.skip("the check had finished its work before the interrupt")
    assert proc.returncode == 130, err[-2000:]
    assert "Traceback" not in err and "SystemError" not in err and "CPUDispatcher" not in err
    assert err.strip().splitlines()[-1].startswith("interrupted (Ctrl-C)")


def test_a_bug_is_exit_3_not_fail(monkeypatch):
    """An exception that is not an input error (a bug) ends with its traceback, one line saying it is an
    internal error, and exit code 3 — never 1, which scripts read as 'the design failed'."""
    import rockdesign.library

    def broken(project):
        raise ZeroDivisionError("simulated bug")

    monkeypatch.setattr(rockdesign.library, "design_quantities", broken)
    result = runner.invoke(app, ["quantities", PIER, "--json"])
    assert result.exit_code == 3
    text = result.output + (result.stderr if hasattr(result, "stderr") else "")
    assert "internal error" in text and "ZeroDivisionError: simulated bug" in text and "Traceback" in text


def test_usage_errors_stay_exit_2():
    result = runner.invoke(app, ["quantities", PIER, "--no-such-option"])
    assert result.exit_code == 2


def test_first_run_stops_on_a_missing_record_before_compiling(tmp_path, monkeypatch):
    """On a first run (kernels not compiled yet) `check` reads its records before it compiles for
    ≈ 40 s: a record file that does not exist is exit 2 at once, and nothing is compiled."""
    from rockdesign.execution import compilation
    text = (REPO_ROOT / "examples" / "podium_flat.toml").read_text(encoding="utf-8")
    assert 'suites = ["p695-farfield"]' in text
    project = write(tmp_path, text.replace('suites = ["p695-farfield"]', 'records = ["file:missing.AT2"]'))
    monkeypatch.setattr(compilation, "missing", lambda kernels: list(kernels))
    monkeypatch.setattr(compilation, "prepare", lambda *a, **k: pytest.fail("compiled before reading the records"))
    result = invoke("check", project, "-o", tmp_path / "out")
    assert_one_line_error(result, "missing.AT2", "record file not found")
    assert not (tmp_path / "out").exists()
