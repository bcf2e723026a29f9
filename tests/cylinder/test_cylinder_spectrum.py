"""Cylinder rocking spectra (Figs 5.16–5.17): grid points equal single analyses; relative spectra; CLI."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.cylinder.engine import simulate_cylinder
from rockdesign.cylinder.spectrum import CylinderSpectrumError, cylinder_spectrum, parse_cylinder_axis
from rockdesign.cylinder.system import Cylinder, cylinder
from rockdesign.cylinder.pairs import parse_pair

runner = CliRunner()


@pytest.mark.slow   # compiles the 3D spectrum kernels on a first run (≈ 30 s)
def test_grid_points_are_single_analyses():
    cyl = cylinder(3.0, 0.6, contact="spring-dashpot")
    pair = parse_pair("record:p695-ff/12").pair
    R = np.array([1.0, 4.0])
    levels = np.array([1.5, 3.0])
    spec = cylinder_spectrum(cyl, pair, R, levels)
    for j, level in enumerate(levels):
        for i, r_size in enumerate(R):
            c = Cylinder("c", r_size * math.cos(cyl.alpha), r_size * math.sin(cyl.alpha), 1000.0, cyl.contact)
            scaled = pair.scaled(level * c.g * c.tan_alpha / pair.resultant_pga)
            r = simulate_cylinder(c, scaled)
            expected = c.overturn_tilt if r.overturned else r.theta_max / c.alpha
            assert spec.theta_max_over_alpha[j, i] == pytest.approx(expected, rel=1e-12, abs=1e-15)
            assert spec.overturned[j, i] == r.overturned
            assert spec.quasi_impacts[j, i] == r.quasi_impacts


def test_progress_runs_the_same_points_in_blocks(monkeypatch):
    """With a progress callback the grid runs in blocks of amplitude rows; every point is the same."""
    import rockdesign.cylinder.spectrum as cs
    monkeypatch.setattr(cs, "PROGRESS_STEPS", 3)
    cyl = cylinder(3.0, 0.6)
    pair = parse_pair("record:p695-ff/12").pair
    R, levels = np.array([1.0, 4.0]), np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    whole = cylinder_spectrum(cyl, pair, R, levels, free_vibration=2.0)
    calls = []
    blocks = cylinder_spectrum(cyl, pair, R, levels, free_vibration=2.0, progress=lambda d, n: calls.append((d, n)))
    assert calls == [(4, 10), (8, 10), (10, 10)]
    for name in ("theta_max_over_alpha", "overturned", "quasi_impacts"):
        assert np.array_equal(getattr(whole, name), getattr(blocks, name)), name


def test_an_executor_runs_the_same_points_in_blocks_of_rows():
    """On an executor (two spawned worker processes, each with its own numba threads) the grid's blocks of
    amplitude rows run there; every point is the same analysis as in this process, and the progress counts
    every point once."""
    from rockdesign.execution.executor import LocalExecutor
    cyl = cylinder(3.0, 0.6)
    pair = parse_pair("record:p695-ff/12").pair
    R, levels = np.array([1.0, 4.0]), np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    here = cylinder_spectrum(cyl, pair, R, levels, free_vibration=2.0)
    calls = []
    with LocalExecutor(processes=2) as pool:
        there = cylinder_spectrum(cyl, pair, R, levels, free_vibration=2.0, executor=pool,
                                  progress=lambda d, n: calls.append((d, n)))
    assert calls[-1] == (10, 10) and len(calls) == 5           # ⌈5 / (4 × 2)⌉ = 1 row per block
    for name in ("theta_max_over_alpha", "overturned", "quasi_impacts"):
        assert np.array_equal(getattr(here, name), getattr(there, name)), name


def test_axes_and_errors():
    assert parse_cylinder_axis("R:0.5:30:60", "x")[1].size == 60
    assert parse_cylinder_axis("pga/up:1:6:51", "y")[1][-1] == 6.0
    for text, which in (("omega_p/p:1:2:3", "x"), ("R:0:3:4", "x"), ("pga/up:1:6:51", "x")):
        with pytest.raises(CylinderSpectrumError):
            parse_cylinder_axis(text, which)
    with pytest.raises(CylinderSpectrumError):
        cylinder_spectrum(cylinder(3.0, 0.6), parse_pair("record:p695-ff/12a").pair, [1.0], [2.0])


def test_relative_spectrum_from_the_cli(tmp_path):
    undamped = tmp_path / "u.toml"
    damped = tmp_path / "d.toml"
    base = '[project]\nname = "{}"\n[cylinder]\nheight = "3 m"\nslenderness = 0.2\nmass = "2 t"\n'
    undamped.write_text(base.format("undamped"))
    damped.write_text(base.format("damped") + 'contact = "spring-dashpot"\n')
    out = tmp_path / "spec"
    r = runner.invoke(app, ["spectrum", str(damped), "--record", "p695-ff/12", "--x", "R:1:5:3", "--y",
                            "pga/up:1.5:3:2", "--relative", str(undamped), "-o", str(out), "--json"])
    assert r.exit_code == 0, r.output
    summary = json.loads(r.stdout[r.stdout.index("{"):])
    assert summary["n_points"] == 6 and summary["reference"]["model"] == "undamped"
    data = np.load(out / "spectrum.npz")
    np.testing.assert_allclose(data["relative"], data["theta_max_over_alpha"] - data["reference_theta_max_over_alpha"])
    assert (out / "spectrum.png").exists() and (out / "relative.png").exists()
    bad = runner.invoke(app, ["spectrum", str(damped), "--x", "R:1:5:3"])
    assert bad.exit_code == 2 and "--record" in bad.output
