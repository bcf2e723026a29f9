"""The design's stored variants and output folder (issue 42): a stored variant is reused only when everything
that decides its result is the same, is placed in the current grid, and a file that cannot be used is
analysed again with a warning; ``-o`` is written all or nothing and never over a user's files.

The variants' checks are replaced by a stand-in (the kind's ``grid_check``/``grid_cell``) whose verdict
follows the width and the records: these tests are about what is stored and written, not the analysis
(tests/design_space/test_grid.py compares real cells with ``rockdesign check``)."""
from __future__ import annotations

import json
from types import SimpleNamespace

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from support import stocky_podium_toml

runner = CliRunner()
SUITE = """name = "mine"
[[records]]
id = "p695-ff/{a}a"
[[records]]
id = "p695-ff/{b}a"
"""


@pytest.fixture
def fake(monkeypatch):
    """The check of a variant, instantly: PASS for 2B ≥ 0.5 m, unless the records include p695-ff/2a."""
    import rockdesign.execution.compilation as compilation
    from rockdesign.planar.kind import Planar
    calls = []

    def grid_check(self, project, *, records, records_dir, executor, progress):
        ids = [r.id for r in records[1].records]
        calls.append((project.system.column.half_width * 2, tuple(ids)))
        return SimpleNamespace(project=project, ids=ids)

    def grid_cell(self, result, analyses):
        width = result.project.system.column.half_width * 2
        ok = width >= 0.5 - 1e-9 and "p695-ff/2a" not in result.ids
        return {"verdict": "PASS" if ok else "FAIL", "reason": f"stand-in for 2B = {width:.3g} m",
                "governing": "count", "decided_at_design_level": not ok, "acmr": 2.5 if ok else None,
                "acmr_required": 1.96, "p_collapse_design": None, "target_p_collapse": 0.1,
                "n_unacceptable": 0 if ok else 2, "allowed_unacceptable": 1, "n_ground_motions": 2,
                "n_failed_analyses": 0, "superstructure_shear_p84": None, "superstructure_drift_p84": None,
                "median_theta_max_over_theta_c": 0.1, "uplift_acceleration": 1.0, "uplift_shear_coefficient": 0.1,
                "theta_c": 0.2, "column_material": 1000.0 * width, "material": 1000.0 * width, "demand": None,
                "model": "stand-in", "analyses": 2,
                "analyses_saved": 0}
    monkeypatch.setattr(Planar, "grid_check", grid_check)
    monkeypatch.setattr(Planar, "grid_cell", grid_cell)
    monkeypatch.setattr(Planar, "grid_batches", lambda self: None)
    monkeypatch.setattr(Planar, "grid_draws", lambda self, result, *, records, executor:
                        {"n": 1, "failed": 0, "size": 1, "first_failure": None})
    monkeypatch.setattr(compilation, "prepare", lambda *a, **k: 0.0)
    return calls


def project(folder, a=1, b=3, exact=True):
    """A project whose suite file names p695-ff/{a}a and p695-ff/{b}a; ``exact``: its width is built exactly
    ([design.tolerance] 0 %: no tolerance neighbours are checked)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "suite.toml").write_text(SUITE.format(a=a, b=b), encoding="utf-8")
    text = stocky_podium_toml(records=[]).replace("records = []", 'suites = ["suite.toml"]')
    if exact:
        text += '\n[design.tolerance]\n"podium.width" = "0%"\n'

    (folder / "p.toml").write_text(text, encoding="utf-8")
    return folder / "p.toml"


def design(path, out, *vary, extra=("--no-pdf",)):
    args = ["design", str(path), "-o", str(out), "--json", *extra]
    for v in vary:
        args += ["--vary", v]
    res = runner.invoke(app, args)
    return res, (json.loads(res.stdout) if res.stdout.strip().startswith("{") else None)


def test_another_projects_results_are_not_reused(tmp_path, fake):
    """Project B (the same text beside another suite file) run into A's folder reported A's verdicts."""
    a = project(tmp_path / "A", 1, 3, exact=False)
    b = project(tmp_path / "B", 2, 4, exact=False)          # p695-ff/2a: every cell of B fails
    assert a.read_text() == b.read_text()
    out = tmp_path / "out"
    res, data = design(a, out, "podium.width=0.4m:0.6m:3")
    assert res.exit_code == 0 and [c["verdict"] for c in data["cells"]] == ["FAIL", "PASS", "PASS"]
    # 0.5 m fails at its tolerance neighbour 0.495 m (the stand-in passes from 0.5 m): 0.6 m is recommended,
    # its neighbours 0.594 and 0.606 m pass; 3 cells + 4 neighbour checks
    assert data["recommended"]["labels"] == {"podium.width": "0.6 m"} and data["recommended"]["tolerance_robust"]
    assert [n["verdict"] for n in data["recommended"]["neighbourhood"]] == ["PASS", "PASS"]
    assert len(fake) == 7
    res, data = design(b, out, "podium.width=0.4m:0.6m:3")
    assert data["variants_resumed"] == 0 and [c["verdict"] for c in data["cells"]] == ["FAIL"] * 3
    assert res.exit_code == 1
    res, data = design(a, out, "podium.width=0.4m:0.6m:3")      # A again: both stored, A's reused
    assert data["variants_resumed"] == 3 and [c["verdict"] for c in data["cells"]] == ["FAIL", "PASS", "PASS"]
    assert len(fake) == 10          # A's cells and its tolerance neighbours all stored: nothing checked again


def test_a_resumed_variant_takes_its_place_in_the_current_grid(tmp_path, fake):
    """Resuming another grid kept the stored cells' old index and labels: two cells shared an index and the
    recommendation named a width not in the grid (with two variables: a KeyError after design.json was rewritten)."""
    p = project(tmp_path / "A")
    out = tmp_path / "out"
    design(p, out, "podium.width=0.4m:0.6m:3")
    res, data = design(p, out, "podium.width=0.5m:0.6m:2")
    assert res.exit_code == 0, res.output
    assert data["variants_resumed"] == 2
    assert [c["index"] for c in data["cells"]] == [[0], [1]]
    assert [c["labels"] for c in data["cells"]] == [{"podium.width": "0.5 m"}, {"podium.width": "0.6 m"}]
    assert data["recommended"]["labels"] == {"podium.width": "0.5 m"}
    res, data = design(p, out, "podium.width=0.5m:0.6m:2", "podium.columns=20:22:2")
    assert res.exit_code == 0, res.output
    assert [c["index"] for c in data["cells"]] == [[0, 0], [0, 1], [1, 0], [1, 1]]
    assert data["variants_resumed"] == 2                      # columns = 20 is the stored one
    assert all(set(c["labels"]) == {"podium.width", "podium.columns"} for c in data["cells"])


@pytest.mark.parametrize("damage", [
    lambda f: f.write_text(f.read_text()[:40]),                                   # truncated
    lambda f: f.write_text("[1, 2, 3]"),                                          # wrong shape
    lambda f: f.write_text(json.dumps({**json.loads(f.read_text()), "format": 1})),
    lambda f: f.write_text(f.read_text().replace('"PASS"', '"MAYBE"').replace('"FAIL"', '"MAYBE"')),
    lambda f: f.write_bytes(b"\xff\xfe\x00"),
])
def test_a_stored_variant_that_cannot_be_used_is_analysed_again(tmp_path, fake, damage):
    p = project(tmp_path / "A")
    out = tmp_path / "out"
    design(p, out, "podium.width=0.4m:0.6m:2")
    stored = sorted((out / "variants").glob("*.json"))
    assert len(stored) == 2
    damage(stored[0])
    res, data = design(p, out, "podium.width=0.4m:0.6m:2")
    assert res.exit_code == 0, res.output
    assert data["variants_resumed"] == 1 and len(fake) == 3
    assert "warning:" in res.stderr and "analysed again" in res.stderr and stored[0].name in res.stderr
    assert len(data["warnings"]) == 1
    json.loads(stored[0].read_text())["cell"]["verdict"]      # stored again, readable


def test_the_folder_is_written_all_or_nothing(tmp_path, fake, monkeypatch):
    """A stale design.pdf stayed beside a new design.json; a failed run left half a folder."""
    p = project(tmp_path / "A")
    out = tmp_path / "out"
    res, _ = design(p, out, "podium.width=0.4m:0.6m:2")
    assert res.exit_code == 0
    (out / "design.pdf").write_text("an earlier run's report")
    (out / "design_verdict.svg").write_text("<svg/>")
    res, _ = design(p, out, "podium.width=0.4m:0.6m:2")
    assert sorted(x.name for x in out.iterdir()) == ["design.csv", "design.json", "variants"]
    # a run that fails while writing leaves the folder as it was (its finished variants stored)
    before = (out / "design.json").read_text()
    import rockdesign.report.design_results as results

    def broken(*a, **k):
        raise RuntimeError("disk full")
    monkeypatch.setattr(results, "write_design_csv", broken)
    res, _ = design(p, out, "podium.width=0.4m:0.5m:3")
    assert res.exit_code == 3
    assert (out / "design.json").read_text() == before
    assert len(list((out / "variants").glob("*.json"))) == 4       # the new variants are stored for a resume
    assert not [x for x in tmp_path.iterdir() if x.name.startswith(".out")]     # no temporary folder left


def test_the_library_call(tmp_path, fake):
    """rd.design: a Project in (parsed once), callbacks for progress, files all or nothing."""
    import rockdesign as rd
    p = rd.load_project(project(tmp_path / "A"))
    seen = []
    chart = rd.design(p, ["podium.width=0.4m:0.6m:3"], out_dir=tmp_path / "out", pdf=False, html=False,
                      progress=lambda done, total, cell: seen.append((done, total, cell["verdict"])))
    assert chart.verdicts == ["FAIL", "PASS", "PASS"] and chart.exit_code == 0
    assert [s[:2] for s in seen] == [(1, 3), (2, 3), (3, 3)]
    assert chart.recommended["labels"] == {"podium.width": "0.5 m"}
    assert json.loads((tmp_path / "out" / "design.json").read_text())["cells"][1]["verdict"] == "PASS"
    again = rd.design(p, "podium.width=0.4m:0.6m:3", out_dir=tmp_path / "out", pdf=False, html=False)
    assert again.grid.resumed == 3
    memory = rd.design(p, "podium.width=0.4m:0.6m:3")                # no folder: nothing stored or written
    assert memory.grid.resumed == 0 and memory.verdicts == chart.verdicts


def _boxes(box):
    yield box
    for child in getattr(box, "children", []) or []:
        yield from _boxes(child)


def test_the_design_reports_variants_table_fits_its_page(tmp_path, fake):
    """The variants table ran off the page ("anal…"): every box of every page lies within the page."""
    from weasyprint import HTML

    import rockdesign as rd
    p = rd.load_project(project(tmp_path / "A"))
    chart = rd.design(p, ["podium.width=0.4m:0.6m:3", "podium.cap_beam_mass=150t:250t:2"],
                      out_dir=tmp_path / "out", pdf=False, full_check=False)
    html = (tmp_path / "out" / "design.html").read_text(encoding="utf-8")
    assert chart.out_dir == tmp_path / "out" and "analyses</th>" in html
    doc = HTML(string=html, base_url=str(tmp_path)).render()
    variants_pages = 0
    for page in doc.pages:
        width = page.width
        for box in _boxes(page._page_box):
            x, w = getattr(box, "position_x", None), getattr(box, "width", None)
            if isinstance(x, (int, float)) and isinstance(w, (int, float)) and w > 0:
                assert x + w <= width + 0.5, (type(box).__name__, x, w, width)
        if any(getattr(b, "element_tag", None) == "table" and "variants" in (b.element.get("class") or "")
               for b in _boxes(page._page_box) if getattr(b, "element", None) is not None):
            variants_pages += 1
            assert page.width > page.height          # the variants table is on a landscape page
    assert variants_pages >= 1


def test_a_long_silent_stage_says_why(tmp_path, fake, monkeypatch):
    """design was silent for minutes inside one cylinder variant: after a while without progress it says what
    runs and why that can take long; inside a variant checked alone its stages are shown."""
    import time

    import rockdesign.cli.design as cli_design
    from rockdesign.design_space.run import SLOW_ANALYSIS
    from rockdesign.planar.kind import Planar
    real = Planar.grid_check

    def slow(self, project, *, progress, **kw):
        progress("design-level suite", 0, 2)
        time.sleep(1.0)
        progress("design-level suite", 2, 2)
        return real(self, project, progress=progress, **kw)
    monkeypatch.setattr(Planar, "grid_check", slow)
    monkeypatch.setattr(cli_design, "SLOW", 0.4)
    monkeypatch.setattr(cli_design, "WATCH_EVERY", 0.1)
    res, data = design(project(tmp_path / "A"), tmp_path / "out", "podium.width=0.4m:0.6m:2")
    assert res.exit_code == 0, res.output
    text = " ".join(res.stderr.split())
    assert "still working (design-level suite" in text and " ".join(SLOW_ANALYSIS.split()) in text
    assert "design-level suite: 2 to do" in text            # the stages of a variant checked alone are shown


def test_no_robust_pass_is_said_on_the_console_in_design_json_and_on_page_one(tmp_path, fake, monkeypatch):
    """Every passing variant fails a perturbation draw: the console, design.json and the report's first
    section say that no variant passes robustly and name the fragile candidates."""
    from rockdesign.planar.kind import Planar
    monkeypatch.setattr(Planar, "grid_draws", lambda self, result, *, records, executor:
                        {"n": 2, "failed": 1, "size": 10, "first_failure": "c_r + 2 %: 2 of 2 unacceptable"})
    p = project(tmp_path / "A")
    out = tmp_path / "out"
    res = runner.invoke(app, ["design", str(p), "-o", str(out), "--vary", "podium.width=0.4m:0.6m:3",
                              "--no-pdf"])
    assert res.exit_code == 0, res.output
    assert "no variant passes robustly" in res.output and "(PASS, not robust)" in res.output
    assert "2 PASS (not robust)" in res.output
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    rec = data["recommended"]
    assert rec["robust"] is False and [c["labels"]["podium.width"] for c in rec["fragile_candidates"]] == \
        ["0.5 m", "0.6 m"]                       # least material first
    assert [c["robust"] for c in data["cells"]] == [None, False, False]
    assert [c["draws"] for c in data["cells"]] == [{"n": 0, "failed": 0}] + [{"n": 2, "failed": 1}] * 2
    from rockdesign.report.design_report import write_design_report     # the report from design.json
    written = write_design_report(SimpleNamespace(project=SimpleNamespace(name="A")), data, tmp_path, pdf=False)
    html = written["html"].read_text(encoding="utf-8")
    first = html.split("3&#160;&#160;Design charts")[0]
    assert "No variant passes robustly" in first and "podium.width = 0.5 m; podium.width = 0.6 m" in first
    assert "PASS (not robust: fails in 1 of 2 draws)" in html


def test_prefer_names_its_choices(tmp_path, fake):
    p = project(tmp_path / "A")
    res = runner.invoke(app, ["design", str(p), "-o", str(tmp_path / "o"), "--vary", "podium.width=0.4m:0.6m:3",
                              "--no-pdf", "--prefer", "mass"])
    assert res.exit_code == 2 and "--prefer" in res.output and "material or shear" in res.output
    assert "Traceback" not in res.output


def test_an_audit_that_disagrees_makes_every_inferred_cell_analysed(tmp_path, fake, monkeypatch):
    """A stand-in landscape that is smooth except for one FAIL inside a passing region (2B = 0.45 m): the coarse
    corners all pass far from their flip, so the cells between them are inferred; when the audit's sample hits a
    cell that disagrees, every cell left out is analysed and the FAIL is found (SPEC §15: never infer across an
    edge).  Without the hit, the audit says how many cells were inferred and that the sample agreed."""
    from types import SimpleNamespace

    from rockdesign.design_space import refine
    from rockdesign.planar.kind import Planar

    def grid_check(self, project, *, records, records_dir, executor, progress):
        width = project.system.column.half_width * 2
        fake.append((round(width, 4), ()))
        ok = abs(width - 0.45) > 1e-6
        return SimpleNamespace(project=project, ok=ok, acceptance={"flip": {
            "value": 2.0 if ok else 0.5, "lower_bound": False, "governing": "count", "note": "stand-in"}})

    def grid_cell(self, result, analyses):
        ok = result.ok
        return {"verdict": "PASS" if ok else "FAIL", "reason": "stand-in", "governing": "count",
                "decided_at_design_level": not ok, "acmr": None, "acmr_required": None, "p_collapse_design": None,
                "target_p_collapse": 0.1, "n_unacceptable": 0 if ok else 2, "allowed_unacceptable": 1,
                "n_ground_motions": 2, "n_failed_analyses": 0, "superstructure_shear_p84": None,
                "superstructure_drift_p84": None, "median_theta_max_over_theta_c": 0.1, "uplift_acceleration": 1.0,
                "uplift_shear_coefficient": 0.1, "theta_c": 0.2, "column_material": 1.0, "model": "stand-in",
                "analyses": 1, "analyses_saved": 0}
    monkeypatch.setattr(Planar, "grid_check", grid_check)
    monkeypatch.setattr(Planar, "grid_cell", grid_cell)
    p = project(tmp_path / "A")
    vary = "podium.width=0.3m:0.7m:9"                        # 0.30, 0.35, … 0.70: coarse 0.30, 0.50, 0.70
    picked = []

    def sample(left_out, seed, pick=None):
        chosen = [i for i in left_out if i == pick] or left_out[:1]
        picked.append(chosen)
        return chosen
    monkeypatch.setattr(refine, "audit_sample", lambda left, seed: sample(left, seed, (1,)))   # 0.35 m: agrees
    res, data = design(p, tmp_path / "o1", vary)
    settings = data["settings"]
    assert settings["inference_audit"]["n"] == 1 and settings["inference_audit"]["agreed"] == 1
    assert settings["cells_inferred"] == sum(not c["analysed"] for c in data["cells"]) > 0
    assert not next(c for c in data["cells"] if c["labels"]["podium.width"] == "0.45 m")["analysed"]   # missed
    monkeypatch.setattr(refine, "audit_sample", lambda left, seed: sample(left, seed, (3,)))   # 0.45 m: the FAIL
    res, data = design(p, tmp_path / "o2", vary)
    settings = data["settings"]
    assert settings["inference_audit"]["n"] == 1 and settings["inference_audit"]["agreed"] == 0
    assert "fallback" in settings["inference_audit"] and settings["cells_inferred"] == 0
    assert all(c["analysed"] for c in data["cells"])
    assert [c["verdict"] for c in data["cells"]].count("FAIL") == 1
