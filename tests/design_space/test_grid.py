"""The design grid against ``rockdesign check``: each cell's verdict is the check's verdict of that
variant's own project file; the shared-work runner stops a decided variant early and resumes."""
from __future__ import annotations

import json
import tomllib

import pytest

import rockdesign as rd
from support import stocky_podium_toml
from rockdesign.design_space.grid import recommended
from rockdesign.design_space.run import design
from rockdesign.design_space.variants import parse_vary, variant_document, variant_toml

# 11 ground motions (one component each), the ASCE 7-22 minimum
SMALL = stocky_podium_toml(records=[f"p695-ff/{k}a" for k in range(1, 12)], pga="0.4 g", analysis="",
                           height="2.5 m")
VARY = ["podium.width=0.35m:0.65m:2"]


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    folder = tmp_path_factory.mktemp("design")
    path = folder / "small.toml"
    path.write_text(SMALL, encoding="utf-8")
    return folder, path


@pytest.fixture(scope="module")
def grid(small):
    folder, path = small
    return design(path, VARY, out_dir=folder / "out", pdf=False, html=False)


def test_each_cell_verdict_equals_the_check_of_its_project_file(small, grid):
    folder, path = small
    raw = tomllib.loads(SMALL)
    variables = [parse_vary(v, raw) for v in VARY]
    verdicts = []
    for cell in grid.grid.cells:
        doc, _ = variant_document(raw, variables, tuple(cell["index"]))
        file = folder / f"variant_{'_'.join(map(str, cell['index']))}.toml"
        file.write_text(variant_toml(doc), encoding="utf-8")
        full = rd.check(rd.load_project(file))
        assert cell["verdict"] == full.verdict, (cell["labels"], cell["reason"], full.verdict_reason)
        assert cell["n_unacceptable"] == full.acceptance["n_unacceptable"]
        if not cell["decided_at_design_level"]:      # the margin was analysed: the same numbers
            assert cell["acmr"] == pytest.approx(full.acceptance["acmr"], rel=1e-12)
            # the cell's scans stop once its numbers are decided: the same distance to the flip as the check's
            # full scans (SPEC §15)
            assert cell["flip_margin"] == pytest.approx(full.acceptance["flip_margin"], rel=1e-12)
            assert cell["flip_governing"] == full.acceptance["flip"]["governing"]
        else:     # scanned below the design level only: the count's flip of the full scans
            assert cell["flip_margin"] == pytest.approx(full.acceptance["flip"]["count"]["value"], rel=1e-12)
        # robustness: the cell's draws are the check's own c_r runs and ensemble (same seed), run separately
        if cell["verdict"] == "PASS":
            assert cell["robust"] in (True, False) and cell["draws"]["n"] >= 1
            if cell["draws"]["failed"]:
                assert not full.verdict_robust, (cell["robustness"], full.verdict_reason)
            if cell["robust"]:
                assert full.verdict_robust and cell["draws"]["n"] == 2 + 8, full.verdict_reason
        else:
            assert cell["robust"] is None and cell["draws"] == {"n": 0, "failed": 0}
        assert cell["analysed"] is True
        verdicts.append(full.verdict)
    assert sorted(verdicts) == ["FAIL", "PASS"]      # the grid spans the boundary (the test can fail)


def test_a_decided_variant_scans_only_below_the_design_level_for_its_flip(grid):
    cells = {c["verdict"]: c for c in grid.grid.cells}
    fail, ok = cells["FAIL"], cells["PASS"]
    assert fail["decided_at_design_level"] and fail["n_unacceptable"] > fail["allowed_unacceptable"]
    assert fail["acmr"] is None and fail["analyses"] < ok["analyses"]
    # no margin: the count decides, and its distance to the flip lies at or below the design level
    assert fail["flip_governing"] == "count" and fail["flip_margin"] <= 1.0
    assert ok["flip_margin"] > 1.0
    # saved at least: c_r ± (2 per record), 8 ensemble runs per record
    assert fail["analyses_saved"] >= 11 * (2 + 8)
    # the analyses run: the cells' and the recommendation's tolerance neighbours'
    tolerance = grid.settings["tolerance_analyses"]
    assert tolerance > 0 and len(grid.recommended["neighbourhood"]) == 2
    assert grid.grid.analyses_run == sum(c["analyses"] for c in grid.grid.cells) + tolerance


def test_recommended_is_the_passing_cell_and_the_run_resumes(small, grid):
    folder, path = small
    rec = grid.recommended
    passing = [c for c in grid.grid.cells if c["verdict"] == "PASS"]
    assert rec is not None and rec["index"] == passing[0]["index"]
    again = design(path, VARY, out_dir=folder / "out", pdf=False, html=False)   # finished variants are not re-run
    assert again.grid.resumed == 2 and again.grid.analyses_run == 0
    assert [c["verdict"] for c in again.grid.cells] == [c["verdict"] for c in grid.grid.cells]
    assert json.dumps(again.as_json()["cells"][0]["values"]) == json.dumps(grid.as_json()["cells"][0]["values"])


def test_recommendation_prefers_low_shear_then_less_material():
    cells = [
        {"verdict": "PASS", "demand": 0.30, "material": 1.0, "index": [0], "values": {},
         "labels": {}, "acmr": 2.5, "acmr_required": 1.96, "n_unacceptable": 0, "n_ground_motions": 22,
         "allowed_unacceptable": 1},
        {"verdict": "PASS", "demand": 0.2001, "material": 5.0, "index": [1], "values": {},
         "labels": {}, "acmr": 2.0, "acmr_required": 1.96, "n_unacceptable": 1, "n_ground_motions": 22,
         "allowed_unacceptable": 1},
        {"verdict": "PASS", "demand": 0.2002, "material": 4.0, "index": [2], "values": {},
         "labels": {}, "acmr": 2.1, "acmr_required": 1.96, "n_unacceptable": 0, "n_ground_motions": 22,
         "allowed_unacceptable": 1},
        {"verdict": "FAIL", "demand": 0.01, "material": 0.1, "index": [3], "values": {},
         "labels": {}},
    ]
    rec = recommended(cells)
    assert rec["index"] == [2]              # 0.2001 ≈ 0.2002 to 3 digits: the smaller column wins
    assert "ACMR 2.1 ≥ 1.96" in rec["reason"]
    assert recommended([cells[3]]) is None


@pytest.mark.slow
def test_grid_on_dask_equals_local_and_resumes_after_an_interruption(small, grid, dask_cluster, tmp_path):
    """``--dask ADDRESS``: the same cells as the local grid; an interrupted run (one variant stored)
    re-runs only the other."""
    from typer.testing import CliRunner

    from rockdesign.cli import app
    folder, path = small
    out = tmp_path / "d"
    first = design(path, VARY[:1], out_dir=out, pdf=False, html=False)   # both variants stored ...
    stored = [f for f in sorted((out / "variants").glob("*.json"))     # (the grid's, not the tolerance neighbours')
              if not str(json.loads(f.read_text())["cell"].get("robustness")).startswith("not evaluated")]
    assert len(stored) == 2
    stored[0].unlink()                                             # ... one lost: the run was interrupted
    res = CliRunner().invoke(app, ["design", str(path), "--vary", VARY[0], "-o", str(out), "--no-pdf", "--json",
                                   "--dask", dask_cluster.scheduler_address])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["variants_resumed"] == 1
    keep = ("verdict", "n_unacceptable", "acmr", "median_theta_max_over_theta_c")
    assert [{k: c[k] for k in keep} for c in data["cells"]] == [{k: c[k] for k in keep} for c in grid.grid.cells]
    assert [c["verdict"] for c in first.grid.cells] == [c["verdict"] for c in grid.grid.cells]


def test_design_report_and_files(grid, tmp_path):
    from rockdesign.report.design_report import write_design_report
    from rockdesign.report.design_results import write_design_csv, write_design_json
    data = grid.as_json()
    assert set(data) >= {"project", "variables", "cells", "recommended", "analyses_run", "analyses_saved"}
    assert all(set(c) >= {"values", "verdict", "reason", "acmr", "p_collapse_design", "n_unacceptable",
                          "superstructure_shear_p84", "median_theta_max_over_theta_c", "analyses"}
               for c in data["cells"])
    write_design_json(data, tmp_path / "design.json")
    rows = write_design_csv(data, tmp_path / "design.csv").read_text(encoding="utf-8").splitlines()
    assert len(rows) == 1 + len(data["cells"])
    assert rows[0].startswith("podium.width [m],analysed,verdict,robust,draws_n,draws_failed,")
    written = write_design_report(grid, data, tmp_path, pdf=False)
    html = written["html"].read_text(encoding="utf-8")
    assert "Recommended design" in html and "podium.width = 0.65 m" in html
    assert {"verdict", "acmr", "flip", "rotation", "thesis_plane"} <= set(written)   # rigid superstructure: no shear chart
    assert "FAIL" in html and "unacc." in html


def test_variants_checked_together_equal_variants_checked_one_after_the_other(small, grid, monkeypatch, tmp_path):
    """The grid's shared batches (every variant's analyses merged into shared calls of the batch driver)
    change nothing in a cell: the same grid checked one variant after the other gives the same cells."""
    from rockdesign.planar.kind import Planar
    shared = grid.grid.shared_batches
    # the two cells, then the recommendation's two tolerance neighbours
    assert shared["variants"] == 2 + len(grid.recommended["neighbourhood"]) and shared["driver_calls"] < shared["batches"]
    assert shared["analyses"] == grid.grid.analyses_run
    monkeypatch.setattr(Planar, "grid_batches", lambda self: None)
    folder, path = small
    alone = design(path, VARY)
    assert alone.grid.shared_batches is None
    assert alone.as_json()["cells"] == grid.as_json()["cells"]


def test_an_error_in_one_variant_stops_the_grid_without_hanging(small, monkeypatch, tmp_path):
    """A variant that raises (a bug, Ctrl-C in its thread) cancels the others at their next batch and the
    error reaches the caller; nothing waits forever for the failed variant's batches."""
    from rockdesign.planar import grid as planar_grid
    real = planar_grid.grid_check
    calls = []

    def failing(project, **kw):
        calls.append(project.system.column.half_width)
        if len(calls) == 2:
            raise RuntimeError("boom")
        return real(project, **kw)
    monkeypatch.setattr(planar_grid, "grid_check", failing)
    folder, path = small
    with pytest.raises(RuntimeError, match="boom"):
        design(path, VARY)


def test_more_variants_than_threads_queue_and_share_what_runs(small, grid, monkeypatch, tmp_path):
    from rockdesign.design_space import batches
    monkeypatch.setattr(batches, "at_once", lambda: 1)   # one variant at a time: nothing shared
    folder, path = small
    waves = design(path, VARY)
    assert waves.grid.shared_batches["driver_calls"] == waves.grid.shared_batches["batches"]
    assert waves.as_json()["cells"] == grid.as_json()["cells"]
