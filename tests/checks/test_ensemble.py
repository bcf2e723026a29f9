"""Perturbation ensembles ("verdicts that survive chaos", thesis Ch. 7) and the check's new
results.json sections (CONTRACT §5.3) and report section.

The ensemble is tested where the answer is known: the Zhang–Makris block of thesis Sec 2.2 under a
one-sine pulse (ω_p/p = 5) overturns for a_p/(αg) in [3.0186, 6.3181).  Well inside the safe and the
overturning ranges every perturbed run agrees (robust outcome, fraction 0 or 1); at the threshold
itself the ±0.1 % amplitude perturbation straddles it and the outcome is not robust.
"""
from __future__ import annotations

import json
import math
import textwrap

import numpy as np
import pytest
from typer.testing import CliRunner

from rockdesign.planar.checks.ensemble import (AMPLITUDE_VARIATION, RESTITUTION_VARIATION, ensemble_summary,
                                        perturbations, run_ensembles)
from rockdesign.planar.checks.runner import run_jobs
from rockdesign.cli import app
from rockdesign.planar.dynamics.model import ModelChoice
from rockdesign.motions.motion import pulse_motion
from support import G, block_from_p, stocky_podium_toml

ALPHA = 0.25
KW = dict(rtol=1e-10, atol=1e-12, free_vibration=10.0, criterion="dynamic", rest_velocity=5e-4)


def test_perturbations_are_seeded_and_bounded():
    a1, r1 = perturbations(44, 8, seed=3)
    a2, r2 = perturbations(44, 8, seed=3)
    a3, _ = perturbations(44, 8, seed=4)
    assert np.array_equal(a1, a2) and np.array_equal(r1, r2) and not np.array_equal(a1, a3)
    assert a1.shape == (8, 44) and r1.shape == (8,)
    assert np.all(np.abs(a1 - 1) <= AMPLITUDE_VARIATION) and np.all(np.abs(r1 - 1) <= RESTITUTION_VARIATION)


def test_ensemble_on_the_zhang_makris_bands():
    system = block_from_p(2.14, math.tan(ALPHA)).with_restitution(0.81)
    period = 2 * math.pi / (5 * 2.14)
    amplitudes = (2.0, 3.0186, 4.5)      # safe, at the threshold, inside the overturning band
    motions = [pulse_motion("sine", k * ALPHA * G, period) for k in amplitudes]
    choice = ModelChoice("block", "linear")
    nominal = run_jobs(system, choice, motions, [1.0] * 3, **KW)
    assert [r.overturned for r in nominal][::2] == [False, True]
    ens = run_ensembles(system, choice, motions, nominal, size=16, seed=11, **KW)
    assert ens["fractions"][0] == 0.0 and ens["fractions"][2] == 1.0
    assert bool(ens["robust"][0]) and bool(ens["robust"][2])
    assert 0.0 < ens["fractions"][1] < 1.0 and not ens["robust"][1]
    again = run_ensembles(system, choice, motions, nominal, size=16, seed=11, **KW)
    assert np.array_equal(again["overturned"], ens["overturned"])
    summary = ensemble_summary(["safe", "threshold", "band"], ens, size=16, seed=11, rtol=1e-10, atol=1e-12,
                               nominal_overturned=sum(r.overturned for r in nominal))
    assert summary["p_overturn"] == pytest.approx(np.mean(ens["fractions"]))
    assert summary["records_not_robust"] == ["threshold"] and summary["rtol"] == pytest.approx(1e-11)


PROJECT = stocky_podium_toml(("p695-ff/12a", "p695-ff/15b", "p695-ff/11a"), "0.3 g",
                             'acceptance = "binomial"\noverturn_probability_limit = 0.8\nensemble_size = 3\n'
                             'quality = { design_requirements = "B", test_data = "C", modeling = "B" }')


@pytest.mark.slow   # a check with ensembles to a report (≈ 10 s)
def test_results_json_sections_and_report(tmp_path):
    import pypdf
    path = tmp_path / "p.toml"
    path.write_text(textwrap.dedent(PROJECT))
    out = tmp_path / "out"
    result = runner.invoke(app, ["check", str(path), "-o", str(out), "--json"])
    assert result.exit_code in (0, 1), result.output
    data = json.loads((out / "results.json").read_text())
    frag = data["fragility"]
    for key in ("im", "unit", "median", "beta", "method", "n_censored", "median_ci90", "beta_ci90", "stripes",
                "p_overturn_design"):
        assert key in frag
    assert frag["im"] == "pga" and frag["unit"] == "m/s^2" and frag["method"] in ("moments", "censored-mle")
    assert set(frag["stripes"]) >= {"median", "beta"}
    cm = data["collapse_margin"]
    for key in ("CMR", "SSF", "ACMR", "beta_tot", "quality", "ACMR10", "ACMR20", "p_collapse_design", "passed"):
        assert key in cm
    assert set(cm["quality"]) == {"design_requirements", "test_data", "modeling"} and cm["beta_tot"] == 0.6
    assert cm["ACMR10"] == pytest.approx(2.16, abs=0.005)
    ens = data["ensemble"]
    assert ens["size"] == 3 and 0.0 <= ens["p_overturn"] <= 1.0
    for rec in data["records"]:
        assert rec["ensemble_overturn_fraction"] in (0.0, 1 / 3, 2 / 3, 1.0)
        assert isinstance(rec["outcome_robust"], bool)
    names = [c["name"] for c in data["checks"]]
    assert any(n.startswith("Collapse margin (FEMA P695 adaptation)") for n in names)
    rha = next(c for c in data["checks"] if c["criterion"] == "overturning_probability")
    assert rha["governs_verdict"] and "3 ground motions (3 records)" in rha["detail"]
    assert data["acceptance"]["method"] == "binomial" and data["summary"]["n_ground_motions"] == 3
    html = (out / "report.html").read_text()
    assert "Overturning fragility, collapse margin and robustness to chaos" in html
    assert "written for conventional seismic-force-resisting systems" in html
    text = " ".join(p.extract_text() for p in pypdf.PdfReader(str(out / "report.pdf")).pages)
    assert "stripe binomial MLE" in text          # the fragility figure's legend, inside the PDF


runner = CliRunner()
