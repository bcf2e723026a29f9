"""``rockdesign spectrum`` through typer's CliRunner on ``rockdesign.cli.app`` (CONTRACT §2, §4)."""
from __future__ import annotations

import json

import numpy as np
import pytest

from casedata import expected
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.planar.spectra import spectrum as spectrum_module

runner = CliRunner()

B1 = """
[project]
name = "Housner block B1 (thesis Table 3.4)"
[column]
height = "3.0 m"
width = "0.3 m"
mass = "1 t"
mass_distribution = 0.3333333333333333
"""
B2 = """
[project]
name = "B2ec: curved extensions, rho = 0.25"
[column]
height = "3000 mm"
width = "0.3 m"
extended_width = "0.6 m"
curvature = 0.25
mass = "1 t"
mass_distribution = 0.3333333333333333
"""
SMALL = ["--x", "omega_p/p:0.5:12:25", "--y", "ap/up:0:12:13"]


@pytest.fixture()
def projects(tmp_path):
    (tmp_path / "b1.toml").write_text(B1)
    (tmp_path / "b2.toml").write_text(B2)
    return tmp_path


def run(*args):
    return runner.invoke(app, ["spectrum", *map(str, args)])


def test_files_of_contract_section_4(projects):
    out = projects / "out"
    r = run(projects / "b1.toml", "--pulse", "ricker-anti", *SMALL, "-o", out, "-q")
    assert r.exit_code == 0, r.output
    for name in ("spectrum.npz", "summary.json", "theta_max.png", "theta_max.svg", "overturning.png",
                 "overturning.svg", "limit_states.png", "limit_states.svg"):
        assert (out / name).stat().st_size > 0, name
    assert not (out / "chunks").exists()
    with np.load(out / "spectrum.npz") as d:
        assert d["x"].shape == (25,) and d["y"].shape == (13,)
        assert d["x"][0] == 0.5 and d["y"][-1] == 12.0
        psi, ot, n = d["theta_max_over_alpha"], d["overturned"], d["impacts_before_overturn"]
        assert psi.shape == ot.shape == n.shape == (13, 25)
        assert psi.dtype == np.float64 and ot.dtype == bool and np.issubdtype(n.dtype, np.integer)
        assert np.all(n[~ot] == -1) and np.all(n[ot] >= 0)
        assert ot.any() and (~ot).any()
        assert np.all(psi[0] == 0.0)                              # a_p = 0: no rocking
        assert np.all(psi[ot] >= 1.0)                             # static criterion, θc = α for a block
        assert d["limit_state_IV"].shape == (25,) and d["contour_I"].shape[1] == 2
        assert d["polyakov_y"].shape == (25,)
    s = json.loads((out / "summary.json").read_text())
    for key in ("project", "system", "pulse", "axes", "analysis", "results", "limit_states",
                "minimum_overturning_acceleration", "polyakov", "execution", "timings", "files"):
        assert key in s
    assert s["axes"]["x"]["name"] == "omega_p/p" and s["axes"]["x"]["n"] == 25
    assert s["axes"]["y"]["name"] == "ap/up" and s["axes"]["y"]["values"][1] == 1.0
    assert s["pulse"]["kind"] == "ricker-anti" and s["pulse"]["tm_over_Tp"] == 1.5
    assert s["system"]["model"] == "block/exact" and s["analysis"]["overturn"] == "static"
    assert s["results"]["n_analyses"] == 325
    assert sum(s["results"]["overturned_by_impacts"].values()) == s["results"]["n_overturned"] == int(ot.sum())
    assert set(s["limit_states"]) == {"I", "II", "III", "IV"}
    assert s["limit_states"]["II"]["theta_max_over_alpha"] == 0.5
    assert s["timings"]["per_analysis_ms"] > 0 and s["timings"]["wall_s"] > 0
    assert s["polyakov"]["damping"] == 0.02 and s["polyakov"]["u_capacity"] == pytest.approx(0.3)


def test_json_to_stdout_and_example_3_5(projects):
    # thesis Example 3.5 / Table 3.4: B1, antisymmetric Ricker a_p = 0.38 g, T_p = 0.95 s → θ_max/α of case tab3.4_B1_thmax
    r = run(projects / "b1.toml", "--pulse", "ricker-anti", "--x", "Tp:0.95", "--y", "ap/g:0.38", "-o",
            projects / "o", "--json", "-q", "--no-figures", "--no-polyakov")
    assert r.exit_code == 0, r.output
    s = json.loads(r.stdout)
    assert s["results"]["n_analyses"] == 1 and s["polyakov"] is None
    with np.load(projects / "o" / "spectrum.npz") as d:
        assert d["theta_max_over_alpha"][0, 0] == pytest.approx(expected("tab3.4_B1_thmax"), abs=2e-5)
        assert d["Tp"][0] == 0.95 and d["ap"][0] == pytest.approx(0.38 * 9.81)


def test_relative_spectrum_and_equivalent_size(projects):
    out = projects / "rel"
    r = run(projects / "b2.toml", "--pulse", "ricker-anti", "--relative", projects / "b1.toml", "--x",
            "omega_p/p:2:6:41", "--y", "ap/up:3:6:7", "--equivalent-at", "5", "-o", out, "-q")
    assert r.exit_code == 0, r.output
    assert (out / "relative.png").exists() and (out / "relative.svg").exists()
    s = json.loads((out / "summary.json").read_text())
    assert s["relative"]["reference"]["project"]["name"].startswith("Housner block B1")
    eq = s["equivalent_size"]
    assert eq["ordinates"] == [5.0]
    assert eq["R_hat_over_R"][0] == pytest.approx(1.99, abs=0.1)     # Eq 3.65, thesis 1.99
    cap = s["display_cap"]
    assert cap == pytest.approx(max(1.5, s["system"]["theta_c_over_alpha"]))   # B2ec: θc ≈ 2α
    with np.load(out / "spectrum.npz") as d:
        delta = d["delta_theta_max_over_alpha"]
        assert delta.shape == (7, 41)
        np.testing.assert_allclose(
            delta, np.where(d["overturned"], cap, np.minimum(d["theta_max_over_alpha"], cap))
            - np.where(d["reference_overturned"], cap, np.minimum(d["reference_theta_max_over_alpha"], cap)))


@pytest.mark.slow
def test_dask_cluster_is_identical_to_local(projects, dask_cluster):
    args = [projects / "b1.toml", "--pulse", "sine", "--x", "omega_p/p:1:9:9", "--y", "ap/up:0:9:7", "-q",
            "--no-figures", "--no-polyakov"]
    r1 = run(*args, "-o", projects / "local")
    r2 = run(*args, "-o", projects / "dask", "--dask", dask_cluster.scheduler_address)
    assert r1.exit_code == 0 and r2.exit_code == 0, r1.output + r2.output
    s2 = json.loads((projects / "dask" / "summary.json").read_text())
    assert s2["execution"]["executor"] == "dask" and s2["execution"]["workers"] == 2
    with np.load(projects / "local" / "spectrum.npz") as a, np.load(projects / "dask" / "spectrum.npz") as b:
        for key in ("theta_max_over_alpha", "overturned", "impacts_before_overturn", "t_stop", "steps"):
            np.testing.assert_array_equal(a[key], b[key])


def test_interrupted_command_resumes(projects, monkeypatch):
    args = [projects / "b1.toml", "--pulse", "ricker-sym", *SMALL, "--chunk-rows", "2", "-q", "--no-figures",
            "--no-polyakov"]
    real = spectrum_module.spectrum_rows
    calls = {"n": 0}

    def interrupted(*a, **k):
        calls["n"] += 1
        if calls["n"] == 3:
            raise KeyboardInterrupt
        return real(*a, **k)

    monkeypatch.setattr(spectrum_module, "spectrum_rows", interrupted)
    r = run(*args, "-o", projects / "out")
    assert r.exit_code == 130
    assert "resume" in r.output
    assert len(list((projects / "out" / "chunks" / "project").glob("chunk-*.npz"))) == 2
    monkeypatch.setattr(spectrum_module, "spectrum_rows", real)
    r = run(*args, "-o", projects / "out")
    assert r.exit_code == 0, r.output
    ex = json.loads((projects / "out" / "summary.json").read_text())["execution"]
    assert ex["chunks_resumed"] == 2 and ex["chunks_computed"] == 5
    r = run(*args, "-o", projects / "fresh", "--no-resume")
    assert r.exit_code == 0
    with np.load(projects / "out" / "spectrum.npz") as a, np.load(projects / "fresh" / "spectrum.npz") as b:
        for key in ("theta_max_over_alpha", "overturned", "impacts_before_overturn"):
            np.testing.assert_array_equal(a[key], b[key])


@pytest.mark.parametrize("extra,needle", [
    (["--pulse", "ricker-anti", "--x", "omega_p/p:0.5:12"], "--x"),
    (["--pulse", "ricker-anti", "--y", "ap/upp:0:12:5"], "--y"),
    (["--pulse", "ricker-anti", "--x", "ap/up:0:1:5"], "--x"),
    (["--pulse", "triangle"], "--pulse"),
    (["--pulse", "sine", "--dask", "local:zero"], "--dask"),
    (["--pulse", "sine", "--model", "exactish"], "--model"),
    (["--pulse", "sine", "--structure", "podium-2dof"], "model"),
    (["--pulse", "sine", "--overturn", "sometimes"], "--overturn"),
    (["--pulse", "sine", "--t-free", "-1"], "--t-free"),
    (["--pulse", "sine", "--chunk-rows", "0"], "--chunk-rows"),
    (["--pulse", "sine", "--relative", "missing.toml"], "missing.toml"),
])
def test_bad_input_exits_2_with_a_message(projects, extra, needle):
    r = run(projects / "b1.toml", *extra, "-o", projects / "o", "-q")
    assert r.exit_code == 2, r.output
    assert needle in r.output and "Traceback" not in r.output


def test_missing_project_and_file_as_output(projects):
    r = run(projects / "nope.toml", "--pulse", "sine")
    assert r.exit_code == 2 and "nope.toml" in r.output
    (projects / "afile").write_text("x")
    r = run(projects / "b1.toml", "--pulse", "sine", "--x", "omega_p/p:2", "--y", "ap/up:2", "-o", projects / "afile")
    assert r.exit_code == 2 and "folder" in r.output
