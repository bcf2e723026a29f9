"""Each command has a typed library function that a notebook calls and the command line calls too
(docs/api.md, "Every command's function"): ``rd.spectrum``, ``rd.records_*``, ``rd.calibration``,
``rd.validation``, ``rd.ensemble``, ``rd.benchmark``.  The function gives what the command writes and prints, and
its errors name its parameters, before any kernel compiles."""
from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import rockdesign as rd
from rockdesign.cli import app
from rockdesign.paths import REPO_ROOT

runner = CliRunner()
CYLINDER = REPO_ROOT / "examples" / "cylinder.toml"
BLOCK = """
[project]
name = "Housner block B1"
[column]
height = "3.0 m"
width = "0.3 m"
mass = "1 t"
mass_distribution = 0.3333333333333333
"""
SPECIMEN = """
[project]
name = "specimen"
[column]
height = "0.6 m"
width = "0.12 m"
mass = "20 kg"
mass_distribution = 0.3333
"""
TINY = dict(x="omega_p/p:1:8:5", y="ap/up:0:6:4")


@pytest.fixture
def no_compiling(monkeypatch):
    """Bad input is refused before any kernel compiles."""
    import rockdesign.execution.compilation as compilation

    def refuse(*args, **kwargs):
        raise AssertionError("compiled kernels for a bad input")
    monkeypatch.setattr(compilation, "prepare", refuse)


@pytest.fixture
def block(tmp_path):
    path = tmp_path / "b1.toml"
    path.write_text(BLOCK, encoding="utf-8")
    return path


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


# ------------------------------------------------------------------------------------------ spectrum
@pytest.mark.slow       # (≈ 13 s on a loaded machine, most of it loading the spectrum kernel in a fresh process)
def test_the_spectrum_function_is_the_command(block, tmp_path):
    """rd.spectrum writes the folder `rockdesign spectrum` writes, and returns its summary and arrays."""
    s = rd.spectrum(rd.load_project(block), pulse="ricker-anti", out_dir=tmp_path / "lib", figures=False,
                    polyakov=False, **TINY)
    r = invoke("spectrum", block, "--pulse", "ricker-anti", "--x", TINY["x"], "--y", TINY["y"], "-o",
               tmp_path / "cli", "--no-figures", "--no-polyakov", "--json", "-q")
    assert r.exit_code == 0, r.output
    cli = json.loads(r.stdout)
    lib = s.as_json()
    for key in ("system", "pulse", "axes", "analysis", "results", "limit_states", "minimum_overturning_acceleration",
                "polyakov", "relative", "files"):
        assert lib[key] == cli[key], key
    assert s.out_dir == tmp_path / "lib" and sorted(p.name for p in s.out_dir.iterdir()) == ["spectrum.npz",
                                                                                             "summary.json"]
    with np.load(tmp_path / "lib" / "spectrum.npz") as a, np.load(tmp_path / "cli" / "spectrum.npz") as b:
        assert sorted(a.files) == sorted(b.files)
        for key in a.files:
            np.testing.assert_array_equal(a[key], b[key], err_msg=key)
        np.testing.assert_array_equal(s.spectrum.theta_max_over_alpha, a["theta_max_over_alpha"])
    assert s.spectrum.theta_max_over_alpha.shape == (4, 5) and s.reference is None
    assert dict(s.summary_rows())["analyses"] == "20"


@pytest.mark.parametrize("project,options,key,fragment", [
    ("block", dict(), "pulse", "missing pulse"),
    ("block", dict(pulse="sine", record="p695-ff/11"), "record", "not used by the spectrum of a planar system"),
    ("block", dict(pulse="sine", relative=CYLINDER), "relative", "two planar systems"),
    ("block", dict(pulse="sine", x="omega_p/q:1:2:3"), "x", "unknown axis"),
    ("block", dict(pulse="sine", y="ap/up:2:1:3"), "y", "reversed"),
    ("block", dict(pulse="sine", model="exactish"), "model", "unknown model"),
    ("block", dict(pulse="sine", t_free=-1.0), "t_free", "free-vibration time"),
    ("block", dict(pulse="sine", chunk_rows=0), "chunk_rows", "chunk size"),
    ("block", dict(pulse="sine", equivalent_at=[1.0]), "equivalent_at", "relative spectrum only"),
    ("block", dict(pulse="sine", executor="local:0"), "executor", "local cluster"),
    ("block", dict(pulse="sine", x="omega_p/p:0.5:12:100000", y="ap/up:0:12:100000"), "x/y", "memory"),
    ("cylinder", dict(record="p695-ff/11", pulse="sine"), "pulse", "not used by the spectrum of a cylinder"),
    ("cylinder", dict(record="p695-ff/11", executor="local:0"), "executor", "local cluster"),
    ("cylinder", dict(record="p695-ff/11", polyakov=False), "polyakov", "not used by the spectrum of a cylinder"),
    ("cylinder", dict(), "record", "needs a record pair"),
    ("cylinder", dict(record="p695-ff/11,scale=nan"), "record", "scale"),
    ("cylinder", dict(record="p695-ff/11", y="ap/up:1:2:2"), "y", "invalid axis"),
])
def test_spectrum_errors_name_the_parameter(block, tmp_path, no_compiling, project, options, key, fragment):
    path = block if project == "block" else CYLINDER
    with pytest.raises(rd.RockdesignError) as err:
        rd.spectrum(rd.load_project(path), out_dir=tmp_path / "s", **options)
    assert err.value.key == key and fragment in str(err.value), str(err.value)
    assert not (tmp_path / "s").exists()


def test_an_interrupted_spectrum_says_which_chunks_it_kept(block, tmp_path, monkeypatch):
    """Ctrl-C in a notebook: a KeyboardInterrupt saying how many chunks are kept; the same call resumes."""
    from rockdesign.planar.spectra import spectrum as engine
    real, calls = engine.spectrum_rows, {"n": 0}

    def interrupted(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 2:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr(engine, "spectrum_rows", interrupted)
    project = rd.load_project(block)
    options = dict(pulse="sine", chunk_rows=1, out_dir=tmp_path / "s", figures=False, polyakov=False, **TINY)
    with pytest.raises(KeyboardInterrupt, match="1 completed chunks kept in .*chunks; rerun"):
        rd.spectrum(project, **options)
    monkeypatch.setattr(engine, "spectrum_rows", real)
    resumed = rd.spectrum(project, **options)
    assert resumed.summary["execution"]["chunks_resumed"] == 1 and not (tmp_path / "s" / "chunks").exists()


# ------------------------------------------------------------------------------------------ records
def test_the_records_functions_are_the_commands(tmp_path):
    spectrum = rd.records_spectrum("record:p695-ff/11a", damping="5 %", band="0.1:4", n_periods=20)
    r = invoke("records", "spectrum", "p695-ff/11a", "--damping", "5 %", "--band", "0.1:4", "--n-periods", "20",
               "--json")
    assert r.exit_code == 0, r.output
    assert spectrum.as_json() == json.loads(r.stdout)
    assert spectrum.id == "p695-ff/11a" and spectrum.damping == 0.05 and spectrum.periods.size == 20
    shown = rd.records_show("p695-ff/11a")
    assert shown.measures["pga"] == pytest.approx(spectrum.measures["pga"]) and shown.sd_max > 0
    listing = rd.records_list("p695-farfield")
    r = invoke("records", "list", "--suite", "p695-farfield", "--json")
    assert listing.as_json() == json.loads(r.stdout) and len(listing.rows) == 44 and not listing.missing
    model = rd.records_scale_model("p695-ff/11a", 0.025, table="v=0.01m/s")
    assert model.exceeded == ["v"] and model.scaled.dt == pytest.approx(model.motion.dt * 0.025 ** 0.5)
    assert model.write_at2(tmp_path / "m.AT2").read_text().startswith("PEER NGA")


@pytest.mark.parametrize("call,key", [
    (lambda: rd.records_spectrum("p695-ff/11a", damping="abc"), "damping"),
    (lambda: rd.records_spectrum("p695-ff/11a", band="10:1"), "band"),
    (lambda: rd.records_spectrum("p695-ff/11a", n_periods=1), "n_periods"),
    (lambda: rd.records_show("p695-ff/11a", gravity=-1.0), "gravity"),
    (lambda: rd.records_list("thesis-table-9"), "suite"),
    (lambda: rd.records_synth("p695-ff/11a", 2, "ens", scale_to="pga"), "scale_to"),
    (lambda: rd.records_synth("p695-ff/11a", 2, "ens", seed_value=-1), "seed_value"),
    (lambda: rd.records_synth("p695-ff/11a", 0, "ens"), "n"),
    (lambda: rd.records_scale_model("p695-ff/11a", 0.1, table="d=0.1m,d=0.2m"), "table.d"),
    (lambda: rd.records_scale_model("p695-ff/11a", 0.1, table="q=1"), "table"),
    (lambda: rd.records_scale_model("p695-ff/11a", -1.0), "length_ratio"),
    (lambda: rd.records_scale_model("p695-ff/11a", 0.1, band="x:y"), "band"),
])
def test_records_errors_name_the_parameter(call, key, no_compiling, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(rd.RockdesignError) as err:
        call()
    assert err.value.key == key, str(err.value)
    assert not (tmp_path / "ens").exists()


# ------------------------------------------------------------------------------------------ experiments
def test_the_experiment_functions_are_the_commands(tmp_path):
    (tmp_path / "specimen.toml").write_text(SPECIMEN, encoding="utf-8")
    specimen = rd.load_project(tmp_path / "specimen.toml")
    free = rd.simulate(specimen, "free:theta0=0.8alpha", t_end=4.0)
    csv = tmp_path / "free.csv"
    csv.write_text("t,theta\n" + "".join(f"{t:.17g},{th:.17g}\n" for t, th in zip(free.t, free.theta)))
    cal = rd.calibration(specimen, csv)
    assert cal.c_r == pytest.approx(cal.c_r_theory, abs=2e-3) and cal.lam == pytest.approx(1 / 3, abs=0.02)
    r = invoke("calibrate", tmp_path / "specimen.toml", "--free-vibration", csv, "--json")
    assert r.exit_code == 0, r.output
    assert cal.as_json() == json.loads(r.stdout)
    (tmp_path / "two.toml").write_text('name = "two"\n[[records]]\nid = "p695-ff/3a"\n[[records]]\nid = "p695-ff/4a"\n')
    run = rd.ensemble(specimen, tmp_path / "two.toml", scale=0.5, restitution=cal.c_r)
    assert [row["id"] for row in run.rows()] == ["p695-ff/3a", "p695-ff/4a"] and run.c_r == cal.c_r
    run.write_csv(tmp_path / "analyses.csv")
    (tmp_path / "tests.csv").write_text("id,theta_max_over_alpha,overturned\np695-ff/3a,0.5,false\n"
                                        "p695-ff/4a,inf,true\n")
    v = rd.validation(tmp_path / "tests.csv", tmp_path / "analyses.csv", seed=3, out_dir=tmp_path / "v", pdf=False)
    r = invoke("validate", "--tests", tmp_path / "tests.csv", "--analyses", tmp_path / "analyses.csv", "--seed", "3",
               "--json")
    assert r.exit_code == 0, r.output
    assert v.as_json() == json.loads(r.stdout) and v.title == "tests.csv vs analyses.csv"
    assert sorted(p.name for p in (tmp_path / "v").iterdir()) == ["report.html", "validation.json", "validation.png",
                                                                 "validation.svg"]


@pytest.mark.parametrize("call,key", [
    (lambda p, c, t: rd.calibration(c, t), "project"),
    (lambda p, c, t: rd.calibration(p, t, min_amplitude=2.0), "min_amplitude"),
    (lambda p, c, t: rd.calibration(p, t, half_cycles=1), "half_cycles"),
    (lambda p, c, t: rd.ensemble(p, "thesis-table-4.1", scale=0.0), "scale"),
    (lambda p, c, t: rd.ensemble(p, "thesis-table-4.1", restitution=2.0), "restitution"),
    (lambda p, c, t: rd.ensemble(p, "nosuch"), "suite"),
    (lambda p, c, t: rd.ensemble(c, "thesis-table-4.1"), "project"),
])
def test_experiment_errors_name_the_parameter(call, key, tmp_path, no_compiling):
    specimen, cylinder = rd.parse_project(SPECIMEN), rd.load_project(CYLINDER)
    tilt = tmp_path / "free.csv"
    tilt.write_text("t,theta\n" + "".join(f"{0.01 * k},{0.01 * np.cos(k / 10)}\n" for k in range(200)))
    with pytest.raises(rd.RockdesignError) as err:
        call(specimen, cylinder, tilt)
    assert err.value.key == key, str(err.value)


def test_validation_seed_names_the_parameter(tmp_path):
    (tmp_path / "t.csv").write_text("id,theta_max_over_alpha,overturned\na,0.5,false\nb,inf,true\n")
    with pytest.raises(rd.RockdesignError) as err:
        rd.validation(tmp_path / "t.csv", tmp_path / "t.csv", seed=-1)
    assert err.value.key == "seed"


def test_bench_refuses_an_unknown_problem_before_compiling(tmp_path, no_compiling):
    with pytest.raises(rd.RockdesignError) as err:
        rd.benchmark(tmp_path / "b", quick=True, only="no-such-problem")
    assert err.value.key == "only" and not (tmp_path / "b").exists()
