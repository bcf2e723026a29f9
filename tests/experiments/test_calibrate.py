"""Free-vibration calibration (thesis Sec 6.3.5, 6.4.3) on engine-made measurements with known p and c_r."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from conftest import ALPHA, C_R_LEFT, C_R_RIGHT, SPECIMEN_TOML, write_tilt_csv
from rockdesign.cli import app
from rockdesign.planar.design.frequencies import frequency_parameter, rocking_period
from rockdesign.planar.design.quantities import system_frequency_parameter
from rockdesign.planar.experiments.calibrate import (calibrate, frequency_parameter_from_period, mass_distribution_from_p,
                                              peak_potential_energy)
from rockdesign.experiments.free_vibration import ExperimentError, TiltHistory, read_tilt_csv
from rockdesign.planar.experiments.synthetic import free_rocking_history

NOISE = 0.005 * ALPHA           # 0.5 % of α
OFFSET = 0.004                  # rad


def _measurement(system, seed, duration=40.0, noise=NOISE, offset=OFFSET):
    return free_rocking_history(system, 0.7 * ALPHA, c_r_left=C_R_LEFT, c_r_right=C_R_RIGHT, duration=duration,
                                rate=500.0, noise=noise, offset=offset, seed=seed)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_recovers_p_and_left_right_restitution(specimen, tmp_path, seed):
    """Noise 0.5 % α, 500 Hz, offset, missing samples and a NaN row: p within 0.5 %, each c_r within 0.005."""
    t, theta = _measurement(specimen, seed)
    path = write_tilt_csv(tmp_path / "fv.csv", t, theta, degrees=True, skip={700, 701, 2222}, nan_rows={3000})
    history = read_tilt_csv(path)
    assert history.dropped_rows == 1 and history.t.size == t.size - 4
    cal = calibrate(specimen, history)
    p_true = system_frequency_parameter(specimen)[0]
    assert cal.p == pytest.approx(p_true, rel=0.005)
    assert cal.c_r_left == pytest.approx(C_R_LEFT, abs=0.005)
    assert cal.c_r_right == pytest.approx(C_R_RIGHT, abs=0.005)
    assert cal.offset == pytest.approx(OFFSET, abs=1e-4)
    assert cal.lam == pytest.approx(0.543, abs=0.02)
    assert len(cal.half_cycles) == 20


@pytest.mark.parametrize("rate", [100.0, 1000.0])
def test_sampling_rates(specimen, rate):
    t, theta = free_rocking_history(specimen, 0.7 * ALPHA, c_r_left=C_R_LEFT, c_r_right=C_R_RIGHT, duration=40.0,
                                    rate=rate, noise=NOISE, offset=-0.006, seed=1)
    cal = calibrate(specimen, TiltHistory(t, theta, f"{rate:g} Hz"))
    assert cal.p == pytest.approx(system_frequency_parameter(specimen)[0], rel=0.005)
    assert cal.c_r_left == pytest.approx(C_R_LEFT, abs=0.005)
    assert cal.c_r_right == pytest.approx(C_R_RIGHT, abs=0.005)


@pytest.mark.parametrize("seed", [4, 5])
def test_offset_without_rest_tail(specimen, seed):
    """A record that ends while the body still rocks: the offset comes from the arc fit (less precise)."""
    t, theta = _measurement(specimen, seed, duration=12.0)
    cal = calibrate(specimen, TiltHistory(t, theta, "synthetic"))
    assert cal.offset_source == "arcs"
    assert cal.p == pytest.approx(system_frequency_parameter(specimen)[0], rel=0.005)
    assert cal.c_r_left == pytest.approx(C_R_LEFT, abs=0.005)
    assert cal.c_r_right == pytest.approx(C_R_RIGHT, abs=0.005)


def test_clean_measurement_is_exact(specimen):
    """Without noise the only error left is Eq 2.8's linearization (p) and the peak fits (c_r)."""
    t, theta = _measurement(specimen, 0, noise=0.0, offset=0.0)
    cal = calibrate(specimen, TiltHistory(t, theta, "clean"))
    assert cal.p == pytest.approx(system_frequency_parameter(specimen)[0], rel=2e-3)
    assert cal.c_r_left == pytest.approx(C_R_LEFT, abs=5e-4)
    assert cal.c_r_right == pytest.approx(C_R_RIGHT, abs=5e-4)
    assert cal.c_r == pytest.approx(np.mean(cal.c_r_per_impact))


def test_eq_2_8_inversion_and_lambda_closed_form(specimen):
    p, alpha = 5.0, 0.1
    for theta0 in (0.01, 0.05, 0.09):
        assert frequency_parameter_from_period(rocking_period(p, alpha, theta0) / 2, theta0, alpha) == \
            pytest.approx(p, rel=1e-12)
    R = math.hypot(0.25, 0.025)
    lam = mass_distribution_from_p(specimen, 5.018)
    assert lam == pytest.approx(9.807 / (R * 5.018 ** 2) - 1.0, rel=1e-9)     # Eq 3.13 solved for λ
    assert frequency_parameter(R, lam, 9.807) == pytest.approx(5.018, rel=1e-12)
    # Eq 2.10: E_p/(W R) = cos(α − θ0) − cos α, zero at θ0 = 0
    assert peak_potential_energy(0.0, alpha) == 0.0
    assert peak_potential_energy(0.08, 0.0997) == pytest.approx(math.cos(0.0997 - 0.08) - math.cos(0.0997))


def test_theoretical_restitution_ignores_a_measured_value(specimen):
    from rockdesign.planar.design.restitution import restitution_block
    cal = calibrate(specimen.with_restitution(0.9), TiltHistory(*_measurement(specimen, 0, noise=0.0), "x"))
    assert cal.c_r_theory == pytest.approx(restitution_block(ALPHA, 0.543), rel=1e-12)


def test_one_half_cycle_is_an_error(specimen):
    t, theta = _measurement(specimen, 0, noise=0.0, offset=0.0)
    from rockdesign.planar.experiments.synthetic import free_rocking_history as fr
    t1, th1 = fr(specimen, 0.7 * ALPHA, c_r_left=C_R_LEFT, c_r_right=C_R_RIGHT, duration=1.3, rate=500.0)
    with pytest.raises(ExperimentError, match="too few rocking half-cycles"):
        calibrate(specimen, TiltHistory(t1, th1, "short"))


def test_no_rocking_is_an_error(specimen):
    t = np.arange(0, 5, 0.002)
    theta = 0.01 + np.random.default_rng(0).normal(0, 1e-4, t.size)
    with pytest.raises(ExperimentError, match="no rocking"):
        calibrate(specimen, TiltHistory(t, theta, "still"))


def test_csv_errors(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("time,angle\n0,0\n")
    with pytest.raises(ExperimentError, match="missing column"):
        read_tilt_csv(bad)
    rows = "".join(f"{0.002 * k if k != 30 else 0.01},{0.0}\n" for k in range(50))
    bad.write_text("t,theta\n" + rows)
    with pytest.raises(ExperimentError, match="time is not increasing") as err:
        read_tilt_csv(bad)
    assert ":32" in str(err.value)             # the file line of the offending row
    bad.write_text("t [s],theta [grad]\n" + rows)
    with pytest.raises(ExperimentError, match="unknown angle unit"):
        read_tilt_csv(bad)
    ok = tmp_path / "ok.csv"
    ok.write_text("t [ms];theta (deg)\n" + "".join(f"{2 * k};{1.0}\n" for k in range(30)))
    h = read_tilt_csv(ok)
    assert h.dt == pytest.approx(0.002) and h.theta[0] == pytest.approx(math.pi / 180)


def test_cli_json_and_plot(specimen, tmp_path):
    project = tmp_path / "specimen.toml"
    project.write_text(SPECIMEN_TOML)
    t, theta = _measurement(specimen, 1)
    csv_path = write_tilt_csv(tmp_path / "fv.csv", t, theta)
    result = CliRunner().invoke(app, ["calibrate", str(project), "--free-vibration", str(csv_path), "--json",
                                      "--plot", str(tmp_path / "cal.png")])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert {"p", "lambda", "c_r", "c_r_left", "c_r_right", "c_r_theory", "half_cycles", "alpha"} <= set(data)
    assert data["alpha"] == pytest.approx(ALPHA)
    assert (tmp_path / "cal.png").stat().st_size > 10_000
    short = write_tilt_csv(tmp_path / "short.csv", t[:650], theta[:650])
    result = CliRunner().invoke(app, ["calibrate", str(project), "--free-vibration", str(short)])
    assert result.exit_code == 2
    assert "half-cycles" in result.output and "Traceback" not in result.output


def test_measured_restitution_goes_into_the_project(tmp_path):
    """The calibrated values are project keys: restitution = 0.9417 (a measured number in (0, 1])."""
    from rockdesign.planar.design.quantities import coefficient_of_restitution
    from rockdesign.library import load_project
    path = tmp_path / "measured.toml"
    path.write_text(SPECIMEN_TOML.replace("mass_distribution = 0.543", "mass_distribution = 0.54\nrestitution = 0.9417"))
    system = load_project(path).system
    assert coefficient_of_restitution(system) == (0.9417, "measured (project file)")


def test_cli_compiles_the_engine_only_for_the_plot(specimen, tmp_path, monkeypatch):
    """`calibrate` fits without the engine; `--plot` simulates the calibrated free vibration, so on a
    first run it announces and compiles the engine's kernels first (docs/engine.md, "First run")."""
    from rockdesign.execution import compilation
    asked = []
    monkeypatch.setattr(compilation, "prepare", lambda command, kernels, say=None: asked.append(command) or 0.0)
    project = tmp_path / "specimen.toml"
    project.write_text(SPECIMEN_TOML)
    csv_path = write_tilt_csv(tmp_path / "fv.csv", *_measurement(specimen, 1))
    assert CliRunner().invoke(app, ["calibrate", str(project), "--free-vibration", str(csv_path)]).exit_code == 0
    assert asked == []
    result = CliRunner().invoke(app, ["calibrate", str(project), "--free-vibration", str(csv_path),
                                      "--plot", str(tmp_path / "cal.png")])
    assert result.exit_code == 0, result.output
    assert asked == ["calibrate"]
