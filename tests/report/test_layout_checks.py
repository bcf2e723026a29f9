"""The layout checks see what they look for (tests/report/figure_layout.py, page_layout.py): each is shown a
figure or a page with the fault and one without it."""
from __future__ import annotations

import numpy as np
import pytest

from figure_layout import covered_data, layout_problems, overlapping_texts, texts_cut_off
from rockdesign import mplfig as plt
from rockdesign.plots import clear_position, fit_text, legend_above, upright_ticks_if_crowded


def _figure():
    fig, ax = plt.subplots(figsize=(4.0, 3.0))
    ax.plot([0, 1], [0, 1], label="line")
    return fig, ax


def test_touching_tick_labels_collide():
    fig, ax = _figure()
    ax.set_xticks(np.linspace(0, 1, 12))
    ax.set_xticklabels([f"{v:.4f}" for v in np.linspace(0.3333, 0.3667, 12)])
    assert any(a.role == b.role == "tick label" for a, b in overlapping_texts(fig))
    assert upright_ticks_if_crowded(fig, ax)
    assert not overlapping_texts(fig)


def test_a_legend_on_a_line_and_a_note_on_a_marker_cover_the_data():
    fig, ax = _figure()
    ax.plot([0.1], [0.9], "o")
    ax.legend(loc="center")
    note = ax.text(0.1, 0.9, "a note", ha="center", va="center")
    covered = dict(covered_data(fig))
    assert any(what.startswith("legend") for what in covered) and "free 'a note'" in covered
    legend_above(ax)
    assert clear_position(ax, note, [(0.1, 0.9, "center", "center"), (0.9, 0.1, "right", "bottom")])
    assert covered_data(fig) == []


def test_a_text_beyond_the_canvas_is_cut_off():
    fig, ax = _figure()
    ax.text(1.3, 0.5, "outside", transform=ax.transAxes)
    assert [t.text for t in texts_cut_off(fig)] == ["outside"]


def test_a_clean_figure_has_no_problem():
    fig, ax = _figure()
    ax.set_xlabel("x [m]")
    legend_above(ax)
    fig.tight_layout()
    assert layout_problems(fig) == []


@pytest.mark.parametrize("text, fits", [("PASS", True), ("fails 1/10 draws", True), ("x" * 60, False)])
def test_a_cell_text_shrinks_or_breaks_to_fit(text, fits):
    fig, ax = _figure()
    t = ax.text(0.5, 0.5, text, fontsize=7)
    fig.draw_without_rendering()
    assert fit_text(t, 40.0) is fits
    if fits:
        assert t.get_window_extent(fig._get_renderer()).width <= 40.0


def _page(body: str, css: str = "") -> str:
    from rockdesign.report.render import stylesheet
    return (f"<html><head><style>{stylesheet()}{css}</style></head><body>"
            '<div class="running running-project">p</div><div class="running running-tool">t</div>'
            f"{body}</body></html>")


def _figure_html(caption: str, height_mm: float) -> str:
    import base64
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 400 300"><rect width="400" height="300" fill="#ddd"/>'
           '<text x="20" y="150" font-size="20">axis label of the figure</text></svg>')
    data = base64.b64encode(svg.encode()).decode()
    return (f'<figure><img class="figure" src="data:image/svg+xml;base64,{data}" style="height: {height_mm}mm; max-height: none">'
            f"<figcaption>{caption}</figcaption></figure>")


@pytest.mark.parametrize("broken", [True, False])
def test_the_page_checks_see_a_broken_header_a_stranded_heading_and_a_lone_caption(tmp_path, broken):
    """The same pages with the faults (a header allowed to break anywhere in a narrow column, a heading and its one
    line left at a page foot before a figure, a figure too tall for its caption to follow on its page) and
    without them (the report's stylesheet: headers break at spaces, a lead paragraph keeps with what follows)."""
    from page_layout import broken_headers, captions_apart, stranded_headings
    from rockdesign.report.render import html_to_pdf
    css = "th { overflow-wrap: anywhere; } p.lead { break-after: auto; }" if broken else ""
    filler = "<p>" + "Filler text of the report. " * 120 + "</p>"
    body = (f'<table style="width: 30mm"><tr><th>podium.curvature</th><th>x</th></tr><tr><td>1</td><td>2</td></tr>'
            f'</table>{filler * 3}<h2>7 Time histories</h2><p class="lead">One line before the figure.</p>'
            + _figure_html("Figure 1. The first figure of the report.", 258 if broken else 200))
    html = _page(body, css)
    pdf = html_to_pdf(html, tmp_path / "page.pdf")
    found = (broken_headers(html, pdf), stranded_headings(html, pdf), captions_apart(html, pdf))
    if broken:
        assert all(found), found
    else:
        assert found == ([], [], []), found
