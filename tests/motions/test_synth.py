"""Synthetic ensembles with sgsim (optional): reproducibility, ensemble scaling, suite round trip, CLI."""
from __future__ import annotations

import json
import sys

import numpy as np
import pytest
from typer.testing import CliRunner

from rockdesign.errors import MotionError
from rockdesign.motions.library import load_record
from rockdesign.motions.spectra import sd_max
from rockdesign.motions.suites import load_suite

pytest.importorskip("sgsim")

from rockdesign.motions.synth import fit_model, scale_ensemble, simulate_ensemble, synthesize  # noqa: E402


@pytest.fixture(scope="module")
def seed():
    return load_record("p695-ff/11a")


@pytest.fixture(scope="module")
def model(seed):
    return fit_model(seed)


@pytest.mark.slow   # synthetic ensembles: ~25 s
def test_reproducible_ensembles(seed, model):
    first = simulate_ensemble(seed, 3, seed_value=5, model=model)
    again = simulate_ensemble(seed, 3, seed_value=5, model=model)
    other = simulate_ensemble(seed, 3, seed_value=6, model=model)
    for a, b, c in zip(first, again, other):
        np.testing.assert_array_equal(a.samples, b.samples)
        assert not np.allclose(a.samples, c.samples)
        assert a.dt == seed.dt and a.samples.size == seed.samples.size
    assert [m.name for m in first] == ["synth/001", "synth/002", "synth/003"]


def test_ensemble_scaling_to_seed(seed, model):
    motions = simulate_ensemble(seed, 4, seed_value=2, model=model)
    scaled, match = scale_ensemble(motions, seed, scale_to="sdmax")
    seed_sd = sd_max(seed)[0]
    assert match.seed_sd_max == pytest.approx(seed_sd)
    assert np.median([sd_max(m)[0] for m in scaled]) == pytest.approx(seed_sd, rel=1e-9)
    assert match.factor == pytest.approx(seed_sd / match.median_sd_max_before)
    _, spectral = scale_ensemble(motions, seed, scale_to="spectrum")
    assert spectral.spectrum_ratio_after == pytest.approx(1.0, rel=1e-9)
    _, none = scale_ensemble(motions, seed, scale_to="none")
    assert none.factor == 1.0 and none.spectrum_ratio_after == pytest.approx(none.spectrum_ratio_before)
    assert "of the seed's" in match.describe()


def test_synthesize_writes_a_loadable_suite(tmp_path, seed):
    path, match = synthesize(seed, 2, tmp_path / "ens", seed_value=3, scale_to="sdmax")
    suite = load_suite(path)
    assert len(suite.records) == 2 and not suite.missing
    assert suite.meta["seed_record"] == "p695-ff/11a" and suite.meta["seed_value"] == 3
    median = np.median([sd_max(m)[0] for _, m, _ in suite.records])
    assert median == pytest.approx(match.seed_sd_max, rel=1e-9)
    assert json.loads((tmp_path / "ens" / "match.json").read_text())["factor"] == pytest.approx(match.factor)
    assert "modulating" in json.loads((tmp_path / "ens" / "model.json").read_text())


def test_cli_synth(tmp_path):
    from rockdesign.cli.records import app
    result = CliRunner().invoke(app, ["synth", "--seed", "p695-ff/11a", "-n", "2", "-o", str(tmp_path / "cli"),
                                      "--seed-value", "4", "--scale-to", "spectrum"])
    assert result.exit_code == 0, result.output
    assert "wrote 2 records" in result.stdout and (tmp_path / "cli" / "ensemble.npz").is_file()


def test_missing_sgsim_gives_clear_error(monkeypatch, seed):
    monkeypatch.setitem(sys.modules, "sgsim", None)
    with pytest.raises(MotionError, match="optional package 'sgsim'"):
        fit_model(seed)
