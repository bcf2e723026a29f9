"""``rockdesign design`` for a 3D cylinder: every cell's verdict is ``rockdesign check`` of the variant's
own project file (exit codes compared), an impossible diameter is a named INVALID cell, the command
writes design.json/csv and the PDF, and the charts show the cylinder's own numbers."""
from __future__ import annotations

import json
import math
import tomllib

import pytest
from scipy.stats import beta, norm
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.design_space.variants import parse_vary, variant_document, variant_toml
from rockdesign.cylinder import pairs

SUITE = "test-design-two-pairs"
TOML = f"""\
[project]
name = "design cylinder"

[cylinder]
height = "2.8 m"
diameter = "0.7 m"
density = "2.6 t/m^3"

[excitation]
suites = ["{SUITE}"]
scale = {{ method = "resultant_pga", target = "0.3 g" }}

[analysis]
acceptance = "binomial"
overturn_probability_limit = 0.8   # a small test suite: two pairs show P ≤ 80 % with none overturning
ensemble_size = 1
"""
VARY = ["cylinder.diameter=0.4m:0.7m:2", "cylinder.height=2.8m:3m:2"]
runner = CliRunner()


@pytest.fixture(scope="module")
def two_pairs():
    with pytest.MonkeyPatch.context() as mp:
        mp.setitem(pairs.PAIR_SUITES, SUITE, ("p695-ff", range(1, 3)))
        yield


@pytest.fixture(scope="module")
def grid(two_pairs, tmp_path_factory):
    folder = tmp_path_factory.mktemp("cyl_design")
    path = folder / "cyl.toml"
    path.write_text(TOML, encoding="utf-8")
    out = folder / "d"
    args = ["design", str(path), "-o", str(out), "--no-pdf", "--json"]
    for v in VARY:
        args += ["--vary", v]
    res = runner.invoke(app, args)
    return folder, out, res


def test_each_cell_verdict_equals_the_check_of_its_project_file(grid):
    folder, out, res = grid
    assert res.exit_code == 0, res.output         # at least one variant passes
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert json.loads(res.stdout)["cells"] == data["cells"]
    raw = tomllib.loads(TOML)
    variables = [parse_vary(v, raw) for v in VARY]
    codes = {"PASS": 0, "FAIL": 1}
    verdicts = []
    for cell in data["cells"]:
        doc, _ = variant_document(raw, variables, tuple(cell["index"]))
        file = folder / f"variant_{'_'.join(map(str, cell['index']))}.toml"
        file.write_text(variant_toml(doc), encoding="utf-8")
        check = runner.invoke(app, ["check", str(file), "-o", str(folder / f"check_{file.stem}"), "--no-pdf",
                                    "--json"])
        assert check.exit_code == codes[cell["verdict"]], (cell["labels"], cell["reason"], check.output[-400:])
        full = json.loads(check.stdout)
        assert full["verdict"] == cell["verdict"]
        assert full["acceptance"]["n_unacceptable"] == cell["n_unacceptable"]
        assert full["acceptance"]["binomial_bound"] == cell["p_overturn_bound"]
        # the distance to the flip: the check's full scans and the cell's (stopped once decided) agree
        if not cell["decided_at_design_level"]:
            assert cell["flip_margin"] == pytest.approx(full["acceptance"]["flip_margin"], rel=1e-12)
        else:
            assert cell["flip_margin"] == pytest.approx(full["acceptance"]["flip"]["count"]["value"], rel=1e-12)
        if cell["verdict"] == "PASS":   # the draws are the check's ensemble runs: the same robustness
            assert cell["robust"] == full["verdict_robust"] and cell["draws"]["n"] >= 1, cell["robustness"]
        else:
            assert cell["robust"] is None
        if not cell["decided_at_design_level"]:     # the same incremental scans: the same collapse margin
            assert cell["acmr"] == pytest.approx(full["acceptance"]["acmr"], rel=1e-12)
            assert cell["p_collapse_design"] == pytest.approx(full["acceptance"]["p_collapse_design"], rel=1e-12)
        # the same design-level analyses: the median θ_max/θ_ot of the pairs, to the last digit
        ratios = [r["theta_max_over_theta_ot"] for r in full["records"]]
        assert cell["median_theta_max_over_theta_c"] == pytest.approx(sorted(ratios)[0] / 2 + sorted(ratios)[1] / 2,
                                                                     rel=1e-12)
        verdicts.append(cell["verdict"])
    assert sorted(set(verdicts)) == ["FAIL", "PASS"]     # the grid spans the boundary (the test can fail)
    # the variants were checked together, their 3D analyses in shared rounds — and each equals its own check
    shared = data["settings"]["shared_batches"]
    assert shared["variants"] >= len(data["cells"]) and shared["driver_calls"] < shared["batches"], shared


def test_cells_hold_the_cylinders_numbers(grid):
    _, out, _ = grid
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert data["project"]["kind"] == "cylinder" and len(data["cells"]) == 4
    for c in data["cells"]:
        d, h = c["values"]["cylinder.diameter"], c["values"]["cylinder.height"]
        alpha = math.atan(d / h)                                       # Eq 2.1: tan α = B/H
        assert c["alpha"] == pytest.approx(alpha, rel=1e-12)
        assert c["theta_overturn"] == pytest.approx(1.5 * alpha, rel=1e-12)        # default overturn_tilt
        assert c["uplift_acceleration"] == pytest.approx(9.81 * d / h, rel=1e-12)  # g tan α
        assert c["column_material"] == pytest.approx(2600 * math.pi * (d / 2) ** 2 * h, rel=1e-12)
        assert c["superstructure_shear_p84"] is None and c["theta_c"] is None
        # the ACMR of every scanned variant (the collapse margin is information under the binomial rule)
        assert (c["acmr"] is None) == bool(c["decided_at_design_level"])
        assert c["acmr"] is None or c["acmr_required"] == pytest.approx(math.exp(-0.525 * norm.ppf(0.10)))
        assert c["n_ground_motions"] == 2 and c["acceptance"] == "binomial" and c["binomial_limit"] == 0.8
        k = c["n_unacceptable"]
        assert c["p_overturn"] == k / 2
        # the one-sided 95 % Clopper–Pearson bound: the 95 % quantile of Beta(k + 1, n − k) (scipy)
        bound = 1.0 if k == 2 else beta.ppf(0.95, k + 1, 2 - k)
        assert c["p_overturn_bound"] == pytest.approx(bound, rel=1e-9)
        assert (c["verdict"] == "PASS") <= (bound <= 0.8)
        if c["verdict"] == "FAIL" and c["decided_at_design_level"]:
            assert c["n_incremental_unacceptable"] is None and "not needed" in c["reason"]
            # the two pairs once in 3D, then scanned below the design level for the distance to the flip
            # alone (no planar runs, no scan above the design level, no ensemble)
            assert c["analyses"] >= 2 and c["flip_margin"] is not None and c["flip_margin"] <= 1.0
    # the recommended design: the robust passing variant with the least mass, said so in its reason
    passing = [c for c in data["cells"] if c["verdict"] == "PASS"]
    passing = [c for c in passing if c["robust"]] or passing
    rec = data["recommended"]
    assert rec["index"] == min(passing, key=lambda c: c["column_material"])["index"]
    assert "least material: the cylinder's mass" in rec["reason"]
    # through the kind's door like a podium's: diameter and height (lengths) each ± 1 %, the other nominal
    hood = rec["neighbourhood"]
    assert [(n["key"], n["side"]) for n in hood] == [("cylinder.diameter", "−"), ("cylinder.diameter", "+"),
                                                     ("cylinder.height", "−"), ("cylinder.height", "+")]
    d, h = rec["values"]["cylinder.diameter"], rec["values"]["cylinder.height"]
    assert hood[1]["values"] == {"cylinder.diameter": pytest.approx(1.01 * d), "cylinder.height": h}
    assert hood[2]["values"] == {"cylinder.diameter": d, "cylinder.height": pytest.approx(0.99 * h)}
    assert rec["tolerance_robust"] == all(n["verdict"] == "PASS" for n in hood)
    assert data["settings"]["tolerances"]["cylinder.diameter"] == {"relative": 0.01, "source": "default"}
    rows = (out / "design.csv").read_text(encoding="utf-8").splitlines()
    assert rows[0].startswith("cylinder.diameter [m],cylinder.height [m],analysed,verdict,robust,draws_n,")
    assert "p_overturn_bound [-]" in rows[0] and "theta_overturn [rad]" in rows[0] and len(rows) == 5


def test_an_impossible_diameter_is_an_invalid_cell(two_pairs, tmp_path):
    """tan α = B/H ≥ 1 is refused by the loader: a named INVALID cell, the other cell still runs."""
    path = tmp_path / "cyl.toml"
    path.write_text(TOML, encoding="utf-8")
    out = tmp_path / "d"
    res = runner.invoke(app, ["design", str(path), "--vary", "cylinder.diameter=0.7m:3.2m:2", "-o", str(out)])
    assert res.exit_code == 0, res.output
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    ok, bad = data["cells"]
    assert ok["verdict"] == "PASS" and bad["verdict"] == "INVALID"
    assert "cylinder.diameter" in bad["reason"] and "too squat" in bad["reason"] and bad["analyses"] == 0
    assert data["recommended"]["index"] == [0]
    assert (out / "design.pdf").read_bytes()[:5] == b"%PDF-"        # the report with charts, and the full check
    assert data["recommended"]["check"]["verdict"] == "PASS"
    html = (out / "design.html").read_text(encoding="utf-8")
    assert "P(overturn) bound" in html and "θ<sub>ot</sub>" in html and "superstructure shear" not in html
    assert (out / "design_overturning.svg").is_file() and not (out / "design_shear.svg").exists()


def test_options_a_cylinder_does_not_use_are_refused(two_pairs, tmp_path):
    path = tmp_path / "cyl.toml"
    path.write_text(TOML, encoding="utf-8")
    res = runner.invoke(app, ["design", str(path), "--vary", VARY[0], "-o", str(tmp_path / "d"), "--records-dir",
                              str(tmp_path)])
    assert res.exit_code == 2 and "--records-dir" in res.output and "Traceback" not in res.output


def test_cylinder_charts_render_for_two_variables(grid):
    from rockdesign.report.design_figures import cell_reason, design_figures
    _, out, _ = grid
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    figs = design_figures(data)
    assert figs["verdict"] is not None and figs["overturning"] is not None and figs["rotation"] is not None
    assert figs["shear"] is None and figs["thesis_plane"] is None
    assert (figs["acmr"] is None) == all(c["acmr"] is None for c in data["cells"])
    reasons = {cell_reason(c) for c in data["cells"]}
    assert "P ≤ 0.78" in reasons and "P ≤ 0.97" in reasons
    from types import SimpleNamespace

    from rockdesign.library import load_project
    from rockdesign.report.design_report import write_design_report
    folder, _, _ = grid
    (folder / "report2").mkdir()
    written = write_design_report(SimpleNamespace(project=load_project(folder / "cyl.toml")), data,
                                  folder / "report2", pdf=False)
    html = written["html"].read_text(encoding="utf-8")
    scanned = any(c["acmr"] is not None for c in data["cells"])
    assert {"verdict", "overturning", "rotation", "flip"} | ({"acmr"} if scanned else set()) == set(written) - {"html"}
    table = html[html.index("Variants</h2>"):]
    assert "median θ<sub>max</sub>/θ<sub>ot</sub>" in table and "P(overturn) bound (limit)" in table
    assert ("ACMR (required)" in table) == scanned and "shear coeff." not in table


def test_no_passing_variant_exits_1(two_pairs, tmp_path):
    """Slender variants that the design-level pairs already fail: exit 1, no recommendation, no scans."""
    path = tmp_path / "cyl.toml"
    path.write_text(TOML, encoding="utf-8")
    out = tmp_path / "d"
    res = runner.invoke(app, ["design", str(path), "--vary", "cylinder.diameter=0.4m:0.42m:2", "--vary",
                              "cylinder.height=2.8m:3m:2", "-o", str(out), "--no-pdf"])
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert res.exit_code == 1, res.output
    assert {c["verdict"] for c in data["cells"]} == {"FAIL"} and data["recommended"] is None
    assert "no variant passes" in res.output


def test_a_suite_too_small_for_the_rule_stops_the_grid(two_pairs, tmp_path):
    """ASCE 7-22 needs 11 ground motions: the two-pair suite under the default rule is an input error of the
    whole grid (exit 2, before any analysis), not an INVALID cell per variant."""
    path = tmp_path / "cyl.toml"
    path.write_text(TOML.replace('acceptance = "binomial"\n', ""), encoding="utf-8")
    res = runner.invoke(app, ["design", str(path), "--vary", VARY[0], "-o", str(tmp_path / "d"), "--no-pdf"])
    assert res.exit_code == 2, res.output
    assert "11" in res.output and "excitation" in res.output and "Traceback" not in res.output


def test_the_pairs_are_read_once_for_all_variants(two_pairs, tmp_path, monkeypatch):
    """Variants of one [excitation] share the read and scaled pairs: the suite is read once for four
    variants; a variant whose target differs (the default excitation moves with tan α) reads its own."""
    from rockdesign.cylinder import check as cylinder_check
    from rockdesign.design_space.run import design
    reads = []
    real = cylinder_check.suite_pairs
    monkeypatch.setattr(cylinder_check, "suite_pairs", lambda name, **kw: reads.append(name) or real(name, **kw))
    path = tmp_path / "cyl.toml"
    path.write_text(TOML, encoding="utf-8")
    chart = design(path, ["cylinder.diameter=0.4m:0.42m:2", "cylinder.height=2.8m:3m:2"])
    assert len(chart.grid.cells) == 4 and reads == [SUITE]
    keys = {cylinder_check.suite_pairs_key(c.project) for c in _variants(path, ["cylinder.diameter=0.4m:0.6m:2"])}
    assert len(keys) == 1
    default = TOML.replace('scale = { method = "resultant_pga", target = "0.3 g" }\n', "")
    path.write_text(default, encoding="utf-8")
    keys = {cylinder_check.suite_pairs_key(c.project) for c in _variants(path, ["cylinder.diameter=0.4m:0.6m:2"])}
    assert len(keys) == 2          # 1.5 g tan α: a different target per diameter


def _variants(path, vary):
    from rockdesign.design_space.variants import variants
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    return variants(raw, [parse_vary(v, raw) for v in vary], file=str(path))


def test_a_key_replaces_its_alternative(two_pairs, tmp_path):
    """cylinder.slenderness replaces the project's diameter, cylinder.mass its density (CONTRACT §1: one of
    each pair): the variants are valid and the notes say what was replaced."""
    from rockdesign.design_space.run import design
    path = tmp_path / "cyl.toml"
    path.write_text(TOML, encoding="utf-8")
    chart = design(path, ["cylinder.slenderness=0.2:0.22:2", "cylinder.mass=2t:3t:2"])
    cells = chart.grid.cells
    assert all(c["verdict"] in ("PASS", "FAIL") for c in cells), [c["reason"] for c in cells]
    assert cells[0]["notes"] == ["cylinder.slenderness replaces cylinder.diameter",
                                 "cylinder.mass replaces cylinder.density"]
    for c in cells:
        assert c["uplift_shear_coefficient"] == pytest.approx(c["values"]["cylinder.slenderness"], rel=1e-12)
        assert c["column_material"] == pytest.approx(c["values"]["cylinder.mass"], rel=1e-12)
