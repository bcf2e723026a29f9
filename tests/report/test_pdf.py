"""The reports' PDF: one route, WeasyPrint in this process, the figures drawn from their SVG.

What a signed report needs from it, checked on the check report of examples/bridge_pier.toml: every figure
of report.html is in report.pdf, drawn as vector graphics (no raster image anywhere), with its text as text
(axis labels extractable on the page of the figure's caption); a report without figures is a plain PDF.
"""
from __future__ import annotations

import re

import pypdf
import pytest

from rockdesign.report import render

FIGURE_IMAGE = re.compile(r'<img class="figure"[^>]*src="data:image/svg\+xml;base64,')


def _xobjects(page, subtype: str) -> list:
    found = []
    stack = [page.get("/Resources", {})]
    while stack:
        resources = stack.pop()
        for _, x in (resources.get("/XObject") or {}).items():
            x = x.get_object()
            if x.get("/Subtype") == subtype:
                found.append(x)
            if x.get("/Subtype") == "/Form" and "/Resources" in x:
                stack.append(x["/Resources"])
    return found


@pytest.mark.slow   # a full check with margins to PDF (≈ 12 s)
def test_every_figure_is_in_the_pdf_as_vector_graphics_with_its_text(curved_out):
    figures = len(FIGURE_IMAGE.findall(curved_out.html))
    reader = pypdf.PdfReader(str(curved_out.out / "report.pdf"))
    assert figures >= 8
    assert sum(len(_xobjects(page, "/Image")) for page in reader.pages) == 0      # nothing rasterised
    drawn = sum(len(_xobjects(page, "/Form")) for page in reader.pages)
    assert drawn >= figures                                                       # each figure a vector drawing
    pages = [page.extract_text() for page in reader.pages]
    caption = next(k for k, text in enumerate(pages) if "Pushover curve" in text)
    assert "θ [rad]" in pages[caption]            # the pushover figure's axis label, as text, beside its caption


def test_a_report_without_figures(tmp_path):
    html = f"<html><head><style>{render.stylesheet()}</style></head><body><p>No figure here.</p></body></html>"
    path = render.html_to_pdf(html, tmp_path / "plain.pdf")
    assert "No figure here." in pypdf.PdfReader(str(path)).pages[0].extract_text()
