"""The calculation report of a cylinder check: PDF with the verdict and Fig 5.2, numbers equal to
results.json, the governing histories, and the library API (rd.check / rd.write_report).

A small suite (three FEMA P695 far-field pairs, registered for the test) keeps the runs short."""
from __future__ import annotations

import base64
import html
import json
import re

import pytest
from typer.testing import CliRunner

import rockdesign as rd
from rockdesign.cylinder.check import MAX_HISTORIES, CylinderCheckResult, governing_ids
from rockdesign.cli import app
from rockdesign.cylinder import pairs
from rockdesign.report.formatting import fmt

runner = CliRunner()
SUITE = "test-three-pairs"
TOML = ('[project]\nname = "report cylinder"\nengineer = "T. Tester"\n[cylinder]\nheight = "3 m"\n'
        'slenderness = 0.2\nmass = "2 t"\n'
        f'[excitation]\nsuites = ["{SUITE}"]\nscale = {{ method = "resultant_pga", target = "0.3 g" }}\n'
        '[analysis]\nacceptance = "binomial"\noverturn_probability_limit = 0.8   # a small test suite: the binomial rule needs 2 pairs at 80 %\n')


@pytest.fixture(scope="module")
def small_suite():
    with pytest.MonkeyPatch.context() as mp:
        mp.setitem(pairs.PAIR_SUITES, SUITE, ("p695-ff", range(1, 4)))
        yield SUITE


@pytest.fixture(scope="module")
def report(small_suite, tmp_path_factory):
    """``check`` through the CLI with the PDF: (results.json, report.html text, PDF text, folder)."""
    from pypdf import PdfReader
    d = tmp_path_factory.mktemp("cylrep")
    (d / "cyl.toml").write_text(TOML)
    out = d / "out"
    r = runner.invoke(app, ["check", str(d / "cyl.toml"), "-o", str(out)])
    data = json.loads((out / "results.json").read_text(encoding="utf-8"))
    assert r.exit_code == (0 if data["verdict"] == "PASS" else 1), r.output
    pdf_text = "\n".join(p.extract_text() for p in PdfReader(out / "report.pdf").pages)
    return data, (out / "report.html").read_text(encoding="utf-8"), pdf_text, out


def _cells(html_text: str, row_id: str) -> list[str]:
    """The text of the cells of the per-pair table row of ``row_id``."""
    table = html_text[html_text.index('id="pairs"'):]
    table = table[:table.index("</table>")]
    row = re.search(r'<tr[^>]*><td class="nobreak">' + re.escape(row_id) + r"</td>(.*?)</tr>", table, re.S)
    assert row, row_id
    return [html.unescape(re.sub(r"<[^>]+>", "", c)) for c in re.findall(r"<td[^>]*>(.*?)</td>", row.group(1), re.S)]


@pytest.mark.slow
def test_pdf_holds_verdict_reason_and_fig_5_2(report):
    data, page, pdf_text, out = report
    assert sorted(p.name for p in out.iterdir()) == ["cylinder_vs_planar.png", "report.html", "report.pdf",
                                                     "results.csv", "results.json", "wobbling_period.png"]
    flat = " ".join(pdf_text.split())
    assert data["verdict"] in flat and "Verdict" in flat
    s = data["summary"]
    # the verdict's reason is criteria.decide's sentence, as in a planar check's report
    assert f"{s['n_overturned']} of {s['n_records']} record pairs overturn at the design level" in flat
    assert data["verdict_reason"].split(";")[0] in flat.replace("≤ ", "≤ ")
    assert "Robustness" in flat
    assert "Is a planar analysis enough?" in flat and "Fig 5.2" in flat
    # the figure is an <img> whose SVG draws both curves of Fig 5.2
    fig = re.search(r'<figure class="narrow" id="fig-wobbling"><img[^>]*src="data:image/svg\+xml;base64,([^"]+)"',
                    page)
    assert fig
    svg = base64.b64decode(fig.group(1)).decode("utf-8")
    assert "Eq 5.29" in svg and "Housner (Eq 2.8)" in svg
    for eq in ("Eq 5.20", "Eq 5.21", "Eq 5.27", "Eq 5.41", "Eq 5.24", "Eq 5.38", "Eq 5.29"):
        assert eq in flat
    # one θ(t)/orbit figure per governing pair
    for rid in governing_ids(data):
        assert re.search(r'<figure class="history-cyl"><img[^>]*>\s*<figcaption>' + re.escape(rid), page)


@pytest.mark.slow
def test_report_numbers_are_those_of_results_json(report):
    data, page, pdf_text, _ = report
    flat = " ".join(pdf_text.split())
    units = {"m^2": "m²", "m/s^2": "m/s²", "-": ""}
    for name, q in data["quantities"].items():
        text = fmt(q["value"], q["unit"])
        assert text in page, name
        assert (text.split()[0] if units.get(q["unit"], q["unit"]) == "" else text) in flat, name
    assert len(data["records"]) == 3
    for r in data["records"]:
        cells = _cells(page, r["id"])
        assert cells[1:7] == [fmt(r["scale"]), fmt(r["resultant_pga"]), fmt(r["theta_max_over_alpha"]),
                              fmt(r["overturned"]), fmt(r["quasi_impacts"]), fmt(r["uplift_time"])]
        assert cells[7:] == [fmt(r["planar_x"]["theta_max_over_alpha"]), fmt(r["planar_y"]["theta_max_over_alpha"]),
                             fmt(r["planar_overturned"]), fmt(r["polyakov_ratio_x"]), fmt(r["polyakov_ratio_y"])]
    s = data["summary"]
    # the comparison table: 3D against planar P(overturn) and median θ_max/α
    for key in ("p_overturn", "median_theta_max_over_alpha"):
        assert f"{fmt(s[key])}</td><td class=\"num\">{fmt(s['planar'][key])}</td>" in page
    assert fmt(data["cylinder"]["height"], "m") == "3 m" and "3 m" in flat
    # the mass as the project gives it ("2 t"), not converted to kg
    assert "<tr><th>Mass m</th><td>2 t</td></tr>" in page and fmt(data["cylinder"]["mass"], "kg") not in flat


@pytest.mark.slow
def test_report_shows_the_fragility_and_collapse_margin(report):
    """One acceptance for every kind: the cylinder's report has the fragility table and figure and the collapse
    margin as a podium's does, with the counted Ŝ_CT that decides and the fitted median beside it."""
    data, page, pdf_text, _ = report
    f, cm, acc = data["fragility"], data["collapse_margin"], data["acceptance"]
    assert f["im"] == "resultant_pga" and f["n_records"] == 3 and cm["median_definition"] == "counted"
    assert acc["acmr"] == cm["ACMR"] and acc["p_collapse_design"] == cm["p_collapse_design"]
    flat = " ".join(pdf_text.split())
    assert "Overturning fragility and collapse margin" in flat and "Appendix C3" in flat
    for value in (cm["ACMR"], cm["ACMR_target"], cm["median_capacity"], f["design_intensity"], cm["beta_tot"]):
        assert fmt(value) in page
    if cm["ACMR_fitted"] is not None:
        assert fmt(cm["ACMR_fitted"]) in page and fmt(cm["median_fitted"]) in page
    assert "counted (FEMA P695 §6.4)" in page and "Fitted lognormal median (information)" in page
    fig = re.search(r'<figure><img[^>]*src="data:image/svg\+xml;base64,([^"]+)"[^>]*>\s*<figcaption>Overturning fragility',
                    page)
    assert fig and "P(overturn)" in base64.b64decode(fig.group(1)).decode("utf-8")


def test_library_check_and_write_report_for_a_cylinder(small_suite, tmp_path):
    """rd.check returns a CylinderCheckResult; the governing histories are the analyses behind the rows;
    rd.write_report writes the folder (HTML without PDF here) with results.json = as_json()."""
    project = rd.parse_project(TOML, name="cyl.toml")
    result = rd.check(project)
    assert isinstance(result, CylinderCheckResult) and result.verdict in ("PASS", "FAIL")
    # typed outcomes, one per record pair (one ground motion each)
    assert all(o.ground_motion == o.id for o in result.records)
    rows = {r["id"]: r for r in result.as_json()["records"]}
    ids = governing_ids(result.as_json())
    n_overturned = sum(r["overturned"] for r in rows.values())     # every overturning pair, at least two
    assert list(result.histories) == ids and len(ids) == min(max(2, n_overturned), MAX_HISTORIES)
    top = max(r["theta_max_over_alpha"] for r in rows.values() if not r["overturned"]) \
        if not any(r["overturned"] for r in rows.values()) else None
    if top is not None:
        assert rows[ids[0]]["theta_max_over_alpha"] == top
    for rid, (response, pair) in result.histories.items():
        assert response.theta_max / project.system.alpha == pytest.approx(rows[rid]["theta_max_over_alpha"],
                                                                         rel=1e-12)
        assert response.quasi_impacts == rows[rid]["quasi_impacts"]
    out = rd.write_report(result, tmp_path / "lib", pdf=False)
    assert sorted(p.name for p in out.iterdir()) == ["cylinder_vs_planar.png", "report.html", "results.csv",
                                                     "results.json", "wobbling_period.png"]
    assert json.loads((out / "results.json").read_text(encoding="utf-8")) == json.loads(json.dumps(result.as_json()))
    page = (out / "report.html").read_text(encoding="utf-8")
    assert f'<span class="word">{result.verdict}</span>' in page


def test_governing_ids_show_every_overturning_pair():
    """Five overturning pairs: all five histories are shown (not only two); none: the two largest θ_max/α."""
    rows = [{"id": f"p{k}", "overturned": k < 5, "theta_max_over_alpha": 1.0 + k} for k in range(12)]
    assert governing_ids({"records": rows}) == ["p4", "p3", "p2", "p1", "p0"]
    calm = [dict(r, overturned=False) for r in rows]
    assert governing_ids({"records": calm}) == ["p11", "p10"]
    many = [dict(r, overturned=True) for r in rows]
    assert len(governing_ids({"records": many})) == MAX_HISTORIES
