"""Shake-table record preparation (thesis Sec 6.1.3, 6.2.2): Eq 6.5 time scaling, correction, table limits."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy import signal
from scipy.integrate import cumulative_trapezoid
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.errors import MotionError
from rockdesign.experiments.scale_model import band_pass, parse_limits, scale_record, write_at2
from rockdesign.motions.library import load_record
from rockdesign.motions.measures import velocity_displacement
from rockdesign.motions.records import read_record_file

RATIO = 1.0 / 40.0             # time scaled by 1/√40 (thesis: 2H = 20 m prototype, 0.5 m specimen)


@pytest.fixture(scope="module")
def record():
    return load_record("p695-ff/11a")


@pytest.fixture(scope="module")
def scaled(record):
    return scale_record(record, RATIO)


def test_time_scaling_eq_6_5(record, scaled):
    assert scaled.dt == pytest.approx(record.dt / math.sqrt(40.0), rel=1e-12)
    assert scaled.duration == pytest.approx((record.samples.size - 1) * record.dt / math.sqrt(40.0), rel=1e-12)
    assert scaled.raw_pga == pytest.approx(record.pga, rel=1e-12)      # amplitudes unchanged
    # the correction (taper + band-pass) keeps the peak acceleration within a few per cent
    assert scaled.peaks["a"] == pytest.approx(record.pga, rel=0.05)


def test_velocity_and_displacement_peaks_match_independent_integration(scaled):
    a = scaled.acceleration
    v_ref = cumulative_trapezoid(a, dx=scaled.dt, initial=0.0)
    d_ref = cumulative_trapezoid(v_ref, dx=scaled.dt, initial=0.0)
    assert scaled.peaks["v"] == pytest.approx(np.max(np.abs(v_ref)), rel=1e-6)
    assert scaled.peaks["d"] == pytest.approx(np.max(np.abs(d_ref)), rel=1e-6)
    # and against the exact integration of a piecewise-linear acceleration (rockdesign.motions.measures)
    v_lin, d_lin = velocity_displacement(np.ascontiguousarray(a), scaled.dt)
    assert scaled.peaks["v"] == pytest.approx(np.max(np.abs(v_lin)), rel=1e-3)
    assert scaled.peaks["d"] == pytest.approx(np.max(np.abs(d_lin)), rel=5e-3)
    # baseline correction: the table returns near its start (residual drift ≪ peak displacement)
    assert abs(scaled.displacement[-1]) < 1e-6 * scaled.peaks["d"] and abs(scaled.velocity[-1]) < 1e-6 * scaled.peaks["v"]


def test_band_pass_is_zero_phase():
    dt = 0.002
    t = np.arange(0, 20, dt)
    x = np.sin(2 * np.pi * 5.0 * t)
    y = band_pass(x, dt, (0.5, 50.0))
    mid = slice(2000, 8000)
    assert np.max(np.abs(y[mid] - x[mid])) < 0.01          # unit gain, no phase shift in the pass band
    low = band_pass(np.sin(2 * np.pi * 0.05 * t), dt, (0.5, 50.0))
    assert np.max(np.abs(low[mid])) < 0.01                  # stop band
    assert signal.butter(4, [0.5, 50.0], btype="bandpass", fs=1 / dt, output="sos").shape == (4, 6)


def test_at2_reads_back(scaled, tmp_path, record):
    path = write_at2(scaled, tmp_path / "model.AT2", 9.81, record.meta)
    back = read_record_file(path, gravity=9.81)
    assert back.dt == pytest.approx(scaled.dt, rel=1e-8)
    assert back.samples.size == scaled.acceleration.size
    np.testing.assert_allclose(back.samples, scaled.acceleration, rtol=1e-6, atol=1e-9)
    assert back.meta["station"] == record.meta["station"]


def test_limits_parsing():
    limits = parse_limits("d=0.125m,v=220mm/s,a=1.5g", 9.81)
    assert limits == pytest.approx({"d": 0.125, "v": 0.22, "a": 1.5 * 9.81})
    for bad in ("x=1m", "v=0.2m", "d=-1m"):
        with pytest.raises(MotionError):
            parse_limits(bad, 9.81)


def test_cli_exit_codes(tmp_path):
    runner = CliRunner()
    ok = runner.invoke(app, ["records", "scale-model", "p695-ff/11a", "--length-ratio", "0.025", "--table",
                             "d=0.125m,v=0.22m/s,a=1.5g", "-o", str(tmp_path / "m.AT2"), "--plot",
                             str(tmp_path / "m.png"), "--json"])
    assert ok.exit_code == 0, ok.output
    data = json.loads(ok.stdout)
    assert data["exceeded"] == [] and data["time_factor"] == pytest.approx(math.sqrt(0.025))
    assert (tmp_path / "m.AT2").exists() and (tmp_path / "m.png").exists()
    over = runner.invoke(app, ["records", "scale-model", "p695-ff/11a", "--length-ratio", "0.025",
                               "--table", "v=0.01m/s"])
    assert over.exit_code == 1 and "EXCEEDED" in over.output and "Hz" in over.output
    bad = runner.invoke(app, ["records", "scale-model", "p695-ff/11a", "--length-ratio", "0.025", "--table", "q=1"])
    assert bad.exit_code == 2 and "Traceback" not in bad.output
