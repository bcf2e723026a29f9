"""The example reports as a checking engineer reads them, page by page (issue 50): the ASCE 7-22 example's report
shows its §16.2 figure; on it and on the cylinder template's report no figure has colliding texts or a legend on
its data, no table header is broken inside a word, no heading is left at a page foot, every caption is on its
figure's page, units are written once (m/s², not m/s^2) and counted words agree with their number."""
from __future__ import annotations

import re

import pytest

from figure_layout import layout_problems
from page_layout import broken_headers, captions_apart, pages_text, stranded_headings
from rockdesign.paths import REPO_ROOT

pytestmark = pytest.mark.slow       # full checks with their PDF reports (≈ 40 s and 20 s)


def _write(project, out):
    import rockdesign as rd
    result = rd.check(project)
    rd.write_report(result, out, pdf=True, html=True)
    html = (out / "report.html").read_text(encoding="utf-8")
    return result, html, out / "report.pdf"


@pytest.fixture(scope="module")
def asce(tmp_path_factory):
    import rockdesign as rd
    return _write(rd.load_project(REPO_ROOT / "examples" / "podium_asce7_22.toml"), tmp_path_factory.mktemp("asce"))


@pytest.fixture(scope="module")
def cylinder(tmp_path_factory):
    import rockdesign as rd
    from rockdesign.templates import template_text
    return _write(rd.parse_project(template_text("cylinder"), name="cylinder.toml"), tmp_path_factory.mktemp("cyl"))


def test_the_asce7_22_report_shows_the_16_2_figure(asce):
    result, html, pdf = asce
    block = result.as_json()["excitation"]["scaling"]
    pages = pages_text(pdf)
    page = next(k for k, text in enumerate(pages) if "the governing period (red)" in text)
    bare = re.sub(r"\s+", "", pages[page])
    assert "governingperiod0.073s" in bare and "90%ofthetarget" in bare
    assert block["standard"] == "ASCE 7-22 §16.2.3" and block["conformant"] is True


def test_the_quantities_table_and_the_period_range_name_the_same_rocking_period(asce):
    """T_R(α/2; p) in the table, T_R(α/2; p̂) = 1.03 s in its note and in the §16.2.1 range: one value per name."""
    result, html, pdf = asce
    basis = result.as_json()["excitation"]["scaling"]["period_range_basis"]
    note = result.quantities["rocking_period"].note
    assert "T_R(α/2; p̂)" in basis and "T_R(α/2; p̂) = (4/p̂) acosh 2 = 1.03 s" in note
    assert re.search(r"T_R\(α/2; p̂\)[^)]*\)[^)]*\) 1\.03 s", basis)
    assert "T<sub>R</sub>(α/2; p)" in html


@pytest.mark.parametrize("which", ["asce", "cylinder"])
def test_every_figure_is_laid_out_clean(which, request):
    result, _, _ = request.getfixturevalue(which)
    if which == "asce":
        from rockdesign.planar.report.report import make_figures
        figures = {name: fig for name, (fig, _, _) in make_figures(result).items() if name != "drawing"}
        assert "scaling" in figures
    else:
        from rockdesign.cylinder.figures import comparison_figure, cylinder_history_figure, wobbling_figure
        from rockdesign.report.fragility_figures import fragility_figure
        system = result.project.system
        figures = {"wobbling": wobbling_figure(result.figure_data["wobbling"], system.tan_alpha),
                   "comparison": comparison_figure(result.as_json()),
                   "fragility": fragility_figure(result)}
        figures.update({rid: cylinder_history_figure(r, system.g, title=rid, pair=pair)
                        for rid, (r, pair) in result.histories.items()})
    problems = {name: layout_problems(fig) for name, fig in figures.items()}
    assert {k: v for k, v in problems.items() if v} == {}


@pytest.mark.parametrize("which", ["asce", "cylinder"])
def test_the_pages_read_as_a_report(which, request):
    result, html, pdf = request.getfixturevalue(which)
    assert broken_headers(html, pdf) == []
    assert stranded_headings(html, pdf) == []
    assert captions_apart(html, pdf) == []
    text = "\n".join(pages_text(pdf))
    echo = result.project.source_text
    for raw in ("m/s^2", "t/m^3", "(s) "):
        found = [m.start() for m in re.finditer(re.escape(raw), text)]
        found = [k for k in found if text[max(0, k - 30):k + 10] not in echo]
        assert not found, [text[max(0, k - 40):k + 20] for k in found]
