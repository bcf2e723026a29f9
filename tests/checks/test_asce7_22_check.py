"""A check whose suite is scaled per ASCE 7-22 §16.2.3 (examples/podium_asce7_22.toml): results.json's
``excitation.scaling`` (CONTRACT §7.1) and the design spectrum beside the fixed base (SPEC §13), and the
project parser's answers to bad ``scale = { method = "asce7-22", … }`` tables (exit 2, file, key, expected, found)."""
from __future__ import annotations

import math

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.paths import REPO_ROOT

EXAMPLE = REPO_ROOT / "examples" / "podium_asce7_22.toml"
runner = CliRunner()


@pytest.mark.slow
def test_example_check_reports_a_conformant_suite():
    """The example's check carries the §16.2.3 block: conformant, lowest ratio ≥ 0.90 over the range derived
    from the structure (0.2 × T_s/S_r to 2 × T_R(α/2), Eq 4.25 and Eq 2.8), one factor per ground motion; the
    superstructure summary shows the MCE_R target at T_s = 0.38 s (S_MS = 0.30 g on the plateau)."""
    import rockdesign as rd
    from rockdesign.planar.checks.check import run_check
    project = rd.load_project(EXAMPLE)
    result = run_check(project, margins=False, verdict_only=True)
    data = result.as_json()
    block = data["excitation"]["scaling"]
    assert block["standard"] == "ASCE 7-22 §16.2.3" and block["method"] == "asce7-22"
    assert block["conformant"] is True and block["min_ratio"] >= 0.9 * (1 - 1e-9)
    q = data["quantities"]
    t_s = 2 * math.pi / q["omega_s"]["value"]
    lo, hi = block["period_range"]
    assert lo == pytest.approx(0.2 * t_s / q["S_r"]["value"], rel=1e-12)
    assert hi == pytest.approx(2 * 4.0 / q["p_hat"]["value"] * math.acosh(2.0), rel=1e-12)
    assert "Eq 2.8" in block["period_range_basis"]
    assert len(block["factors"]) == 22 == data["summary"]["n_ground_motions"]
    for row in data["records"]:
        assert row["scale"] == pytest.approx(block["factors"][row["ground_motion"]], rel=1e-12)
    avg, target = block["suite_average_max_direction"], block["target"]
    assert avg["periods"] == target["periods"]
    inside = [(a, t) for T, a, t in zip(avg["periods"], avg["psa"], target["psa"]) if lo <= T <= hi]
    assert min(a / t for a, t in inside) == pytest.approx(block["min_ratio"], rel=1e-12)
    sd = data["summary"]["superstructure"]
    if sd is not None and sd.get("n_records"):
        g = data["settings"]["g"]
        assert sd["design_spectrum_acceleration"] == pytest.approx(0.30 * g, rel=1e-12)
        assert sd["design_spectrum_shear_coefficient"] == pytest.approx(0.30, rel=1e-12)
        assert sd["fixed_base_damping"] == pytest.approx(0.02)


def _project(tmp_path, scale: str, extra_file: tuple[str, str] | None = None):
    text = EXAMPLE.read_text(encoding="utf-8").replace(
        'scale = { method = "asce7-22", SMS = "0.30 g", SM1 = "0.12 g", TL = "8 s" }', f"scale = {scale}")
    if extra_file:
        (tmp_path / extra_file[0]).write_text(extra_file[1], encoding="utf-8")
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_target_file_is_accepted(tmp_path):
    import rockdesign as rd
    table = "period [s], Sa [g]\n0.01, 0.30\n0.1, 0.75\n0.5, 0.75\n1.0, 0.40\n4.0, 0.08\n"
    path = _project(tmp_path, '{ method = "asce7-22", target = "mce_r.csv", periods = ["0.05 s", "2.5 s"] }',
                    ("mce_r.csv", table))
    rule = rd.load_project(path).excitation.scale
    assert rule.method == "asce7-22" and rule.periods == (0.05, 2.5)
    assert rule.spectrum.psa([0.3])[0] == pytest.approx(0.75 * 9.81, rel=1e-3)


@pytest.mark.parametrize("scale,fragments", [
    ('{ method = "asce7-22", SMS = "-0.5 g", SM1 = "0.2 g" }', ["excitation.scale.SMS", "SMS > 0"]),
    ('{ method = "asce7-22", SMS = "0.5 m", SM1 = "0.2 g" }', ["excitation.scale.SMS"]),
    ('{ method = "asce7-22", SM1 = "0.2 g" }', ["excitation.scale.SMS", "needs the MCE_R target"]),
    ('{ method = "asce7-22", SMS = "0.5 g", SM1 = "0.2 g", TL = "0.2 s" }', ["excitation.scale.TL", "T_S"]),
    ('{ method = "asce7-22", SMS = "0.5 g", SM1 = "0.2 g", SDS = "0.3 g" }', ["excitation.scale.SDS", "SMS = 1.5 SDS"]),
    ('{ method = "asce7-22", SMS = "0.5 g", SM1 = "0.2 g", periods = ["2 s", "1 s"] }',
     ["excitation.scale.periods", "lower bound < upper bound"]),
    ('{ method = "asce7-22", target = "missing.csv" }', ["excitation.scale.target", "not found"]),
    ('{ method = "asce7-22", target = "t.csv", SMS = "0.5 g" }', ["excitation.scale.SMS", "one way"]),
])
def test_bad_asce7_22_tables_exit_2(tmp_path, scale, fragments):
    result = runner.invoke(app, ["check", str(_project(tmp_path, scale)), "--no-pdf", "-o", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    text = " ".join(result.stderr.split())
    assert text.startswith("error:") and "Traceback" not in result.output and "p.toml" in text
    for fragment in fragments:
        assert fragment in text, (fragment, text)


def test_bad_target_table_names_its_line(tmp_path):
    path = _project(tmp_path, '{ method = "asce7-22", target = "t.csv" }',
                    ("t.csv", "period [s], Sa [g]\n0.1, 0.5\n0.05, 0.6\n"))
    result = runner.invoke(app, ["check", str(path), "--no-pdf", "-o", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    text = " ".join(result.stderr.split())
    assert "t.csv" in text and "periods must increase" in text and "3" in text
