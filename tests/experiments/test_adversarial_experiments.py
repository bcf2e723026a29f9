"""Adversarial input to the experiment commands (calibrate, validate, ensemble, records scale-model/synth):
exit 2 with one line naming the option, key or file — never a traceback, never a silent drop."""
from __future__ import annotations

import math

import json

import pytest
from typer.testing import CliRunner

from conftest import ALPHA, SPECIMEN_TOML, write_tilt_csv
from rockdesign.cli import app
from rockdesign.planar.experiments.synthetic import free_rocking_history
from rockdesign.experiments.validate import read_results_csv, validate
from rockdesign.planar.system import block

runner = CliRunner()
TESTS = "id,theta_max_over_alpha,overturned\na,0.5,false\nb,0.7,false\nc,inf,true\nd,0.2,false\n"
MODEL = "id,theta_max_over_alpha,overturned\nd,0.25,false\nc,0.9,false\nb,inf,true\na,0.4,false\n"


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def one_line_error(result, *fragments):
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
    assert "Traceback" not in result.output
    errors = [ln for ln in result.stderr.splitlines() if ln.startswith("error:")]
    assert len(errors) == 1, result.stderr
    flat = " ".join(result.stderr.split())
    for f in fragments:
        assert f in flat, (f, flat)


def write(tmp_path, name, data):
    path = tmp_path / name
    path.write_bytes(data if isinstance(data, bytes) else data.encode("utf-8"))
    return path


def no_compiling(monkeypatch):
    import rockdesign.execution.compilation as compilation

    def boom(*args, **kwargs):
        raise AssertionError("compiled kernels (or ran analyses) for a bad input")
    monkeypatch.setattr(compilation, "prepare", boom)


# ------------------------------------------------------------------------------------------------ validate
def test_a_byte_order_mark_keeps_the_id_column(tmp_path):
    """Excel's UTF-8 BOM used to turn 'id' into '\\ufeffid': the ids were lost and runs paired by row."""
    tests = write(tmp_path, "t.csv", b"\xef\xbb\xbf" + TESTS.encode())
    model = write(tmp_path, "m.csv", b"\xef\xbb\xbf" + MODEL.encode())
    assert read_results_csv(tests, "tests").ids == ["a", "b", "c", "d"]
    r = invoke("validate", "--tests", tests, "--analyses", model, "--json")
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["model_pairing"] == "id"


def test_pairing_by_id_uses_the_run_of_the_same_id(tmp_path):
    """Stage 2 compares tests D1 with the model runs of D2's ids (the model file is in another order)."""
    tests = read_results_csv(write(tmp_path, "t.csv", TESTS), "tests")
    model = read_results_csv(write(tmp_path, "m.csv", MODEL), "analyses")
    result = validate(tests, model, seed=3)
    d2 = result.split[1]
    expected = {"a": 0.4, "b": float("inf"), "c": 0.9, "d": 0.25}
    stage2 = sorted(expected[tests.ids[i]] for i in d2)
    assert result.pairing == "id"
    assert sorted(model.values[[model.ids.index(tests.ids[i]) for i in d2]]) == stage2


@pytest.mark.parametrize("which", ["--tests", "--analyses"])
def test_duplicate_ids_are_refused(tmp_path, which):
    dup = write(tmp_path, "dup.csv", "id,theta_max_over_alpha\na,0.5\nb,0.7\na,0.1\n")
    other = write(tmp_path, "ok.csv", TESTS)
    files = {"--tests": other, "--analyses": other, which: dup}
    one_line_error(invoke("validate", "--tests", files["--tests"], "--analyses", files["--analyses"]),
                   "dup.csv:4", "key 'id'", "duplicate id", "'a' again (first on line 2)")


def test_a_blank_id_is_refused(tmp_path):
    blank = write(tmp_path, "blank.csv", "id,theta_max_over_alpha\na,0.5\n,0.7\nc,0.1\n")
    one_line_error(invoke("validate", "--tests", blank, "--analyses", write(tmp_path, "m.csv", MODEL)),
                   "blank.csv:3", "key 'id'", "missing id")


def test_tests_without_a_model_run_of_their_id_are_refused(tmp_path):
    """No silent fall-back to pairing by row when the ids do not match."""
    model = write(tmp_path, "m.csv", MODEL.replace("\nd,", "\nx,"))
    one_line_error(invoke("validate", "--tests", write(tmp_path, "t.csv", TESTS), "--analyses", model),
                   "key 'id'", "tests without a model run", "'d'", "m.csv", "t.csv")     # names both files


@pytest.mark.parametrize("row, found", [
    ("e,inf,false", "overturned = 'false' and theta_max_over_alpha = 'inf'"),
    ("e,OT,no", "overturned = 'no' and theta_max_over_alpha = 'OT'"),
    ("e,0.4,true", "overturned = 'true' and theta_max_over_alpha = '0.4'"),
])
def test_a_row_that_contradicts_itself_is_refused(tmp_path, row, found):
    """θ_max/α = inf marked not overturned, or 0.4 marked overturned, was accepted (and counted one way)."""
    bad = write(tmp_path, "bad.csv", "id,theta_max_over_alpha,overturned\na,0.5,false\nb,1.2,true\n" + row + "\n")
    one_line_error(invoke("validate", "--tests", bad, "--analyses", write(tmp_path, "m.csv", MODEL)),
                   "bad.csv:4", "key 'overturned'", "contradicts itself", found)


def test_consistent_flags_are_read(tmp_path):
    ok = write(tmp_path, "ok.csv", "id,theta_max_over_alpha,overturned\na,0.5,false\nb,1.2,true\nc,inf,\nd,inf,true\n")
    assert list(read_results_csv(ok, "tests").values) == [0.5, math.inf, math.inf, math.inf]


def test_semicolons_and_decimal_commas_read_as_commas(tmp_path):
    semi = write(tmp_path, "semi.csv", TESTS.replace(",", ";").replace("0.", "0,"))
    a = read_results_csv(semi, "tests")
    b = read_results_csv(write(tmp_path, "comma.csv", TESTS), "tests")
    assert a.ids == b.ids and list(a.values) == list(b.values)
    r = invoke("validate", "--tests", semi, "--analyses", write(tmp_path, "m.csv", MODEL), "--json")
    assert r.exit_code == 0, r.output


@pytest.mark.parametrize("content,fragments", [
    ("id,theta_max_over_alpha\n\xe9a,0.5\nb,0.7\n".encode("latin-1"), ["bad.csv:2", "not UTF-8", "0xe9"]),
    (b"id,theta_max_over_alpha\na,0.5,7\nb,0.7\n", ["bad.csv:2", "does not match the header"]),
    (b"id;theta_max_over_alpha\na;0.5;7\nb;0.7\n", ["bad.csv:2", "does not match the header"]),
    (b"theta_max_over_alpha;overturned\n0,5;false\n0,7;maybe\n", ["bad.csv:3", "key 'overturned'", "'maybe'"]),
])
def test_unreadable_results_files(tmp_path, content, fragments):
    bad = write(tmp_path, "bad.csv", content)
    one_line_error(invoke("validate", "--tests", bad, "--analyses", write(tmp_path, "m.csv", MODEL)), *fragments)


def test_validate_into_an_existing_file(tmp_path):
    taken = write(tmp_path, "taken", "x")
    t, m = write(tmp_path, "t.csv", TESTS), write(tmp_path, "m.csv", MODEL)
    one_line_error(invoke("validate", "--tests", t, "--analyses", m, "-o", taken, "--no-pdf"),
                   "key '-o/--out'", "taken")
    one_line_error(invoke("validate", "--tests", t, "--analyses", m, "--plot", tmp_path), "key '--plot'")
    assert taken.read_text() == "x"


# ------------------------------------------------------------------------------------------------ ensemble
COLUMN = '[project]\nname = "c"\n[column]\nheight = "5 m"\nwidth = "0.5 m"\nmass = "3 t"\nmass_distribution = 0.333\n'


def test_ensemble_refuses_a_suite_with_a_missing_record(tmp_path, monkeypatch):
    """It used to drop the record and report 2 analyses for a 3-record suite (exit 0)."""
    no_compiling(monkeypatch)
    project = write(tmp_path, "c.toml", COLUMN)
    suite = write(tmp_path, "s.toml", 'name = "s"\n[[records]]\nid = "p695-ff/3a"\n[[records]]\n'
                  'file = "gone.AT2"\n[[records]]\nid = "p695-ff/4a"\n')
    out = tmp_path / "analyses.csv"
    one_line_error(invoke("ensemble", project, "--suite", suite, "-o", out), "key '--suite'",
                   "1 of 3 records", "gone.AT2")
    assert not out.exists()


def test_ensemble_into_an_existing_folder_stops_before_the_analyses(tmp_path, monkeypatch):
    no_compiling(monkeypatch)
    project = write(tmp_path, "c.toml", COLUMN)
    suite = write(tmp_path, "s.toml", 'name = "s"\n[[records]]\nid = "p695-ff/3a"\n')
    one_line_error(invoke("ensemble", project, "--suite", suite, "-o", tmp_path), "key '-o/--out'", "directory")


# ------------------------------------------------------------------------------------------------ calibrate
@pytest.fixture(scope="module")
def fv_files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fv")
    (folder / "specimen.toml").write_text(SPECIMEN_TOML)
    system = block(0.25, 0.025, 0.329, 0.543, g=9.807)
    t, theta = free_rocking_history(system, 0.7 * ALPHA, c_r_left=0.93, c_r_right=0.93, duration=20.0, rate=500.0,
                                    noise=0.0, seed=1)
    rad = write_tilt_csv(folder / "fv.csv", t, theta)
    degrees = write_tilt_csv(folder / "deg.csv", t, theta, degrees=True)
    (folder / "mislabelled.csv").write_text(degrees.read_text().replace("theta_deg", "theta"))
    return folder, rad


@pytest.mark.parametrize("value", ["-1", "nan", "inf", "1", "1.5"])
def test_calibrate_min_amplitude_out_of_range(fv_files, value, monkeypatch):
    no_compiling(monkeypatch)
    folder, rad = fv_files
    one_line_error(invoke("calibrate", folder / "specimen.toml", "--free-vibration", rad, "--min-amplitude", value),
                   "key '--min-amplitude'", value)


def test_degrees_under_a_theta_header(fv_files):
    folder, _ = fv_files
    one_line_error(invoke("calibrate", folder / "specimen.toml", "--free-vibration", folder / "mislabelled.csv"),
                   "mislabelled.csv:", "key 'theta'", "beyond π/2", "may be in degrees")


# ------------------------------------------------------------------------------------------------ records
@pytest.mark.parametrize("args,key,found", [
    (["--table", "d=0.1m,d=0.2m"], "--table d", "d=0.1m,d=0.2m"),
    (["--table", "d=0.1m", "--table", "d=0.2m"], "--table", "'--table d=0.1m' and '--table d=0.2m'"),
    (["--table", "v=0.2m/s", "--table=a=1g"], "--table", "'--table v=0.2m/s' and '--table=a=1g'"),
    (["--length-ratio", "0.2"], "--length-ratio", "'--length-ratio 0.1' and '--length-ratio 0.2'"),
])
def test_scale_model_values_given_twice(args, key, found):
    one_line_error(invoke("records", "scale-model", "p695-ff/11a", "--length-ratio", "0.1", *args),
                   f"key '{key}'", "twice", found)


def test_synth_negative_seed_value(tmp_path):
    out = tmp_path / "ens"
    one_line_error(invoke("records", "synth", "--seed", "p695-ff/11a", "-n", "2", "-o", out, "--seed-value", "-1"),
                   "key '--seed-value'", "-1")
    assert not out.exists()


@pytest.mark.parametrize("value", ["inf", "nan", "0", "-1"])
def test_ensemble_scale_must_be_finite_and_positive(tmp_path, value, monkeypatch):
    no_compiling(monkeypatch)
    project = write(tmp_path, "c.toml", COLUMN)
    suite = write(tmp_path, "s.toml", 'name = "s"\n[[records]]\nid = "p695-ff/3a"\n')
    one_line_error(invoke("ensemble", project, "--suite", suite, "-o", tmp_path / "a.csv", "--scale", value),
                   "key '--scale'", value)


def test_validate_negative_seed(tmp_path):
    one_line_error(invoke("validate", "--tests", write(tmp_path, "t.csv", TESTS), "--analyses",
                          write(tmp_path, "m.csv", MODEL), "--seed", "-1"), "key '--seed'", "-1")


def test_a_failed_synth_leaves_no_folder(tmp_path, monkeypatch):
    """records synth created its folder first and left it empty when the fit failed."""
    import rockdesign.motions.synth as synth
    from rockdesign.errors import MotionError

    def fail(*args, **kwargs):
        raise MotionError("the stochastic model does not fit this record", key="--seed")
    monkeypatch.setattr(synth, "fit_model", fail)
    monkeypatch.setattr("rockdesign.execution.compilation.prepare", lambda *a, **k: 0.0)
    out = tmp_path / "deep" / "ens"
    one_line_error(invoke("records", "synth", "--seed", "p695-ff/11a", "-n", "2", "-o", out), "does not fit")
    assert not (tmp_path / "deep").exists()
