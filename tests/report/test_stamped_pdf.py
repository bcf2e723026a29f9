"""The reports' PDF route (report.stamped_pdf): pages laid out by WeasyPrint with an empty box per
figure, the figures drawn by typst and stamped into their boxes.

The reference is WeasyPrint itself drawing the same SVG figures in the same HTML (the route this one
replaces): every figure must land on the same page, at the same place and size, to a pixel at 96 dpi,
and keep its text as text.
"""
from __future__ import annotations

import base64

import numpy as np
import pypdf
import pypdfium2 as pdfium      # (a test dependency: the figures are found in the rendered pages)
import pytest

from rockdesign.report import render, stamped_pdf


DPI = 96


def _figure(width: float, height: float, box: tuple[float, float, float, float], label: str) -> str:
    """An SVG of the given viewBox with one black rectangle (x, y, w, h in viewBox units) and a label."""
    x, y, w, h = box
    return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}">'
            f'<rect x="{x}" y="{y}" width="{w}" height="{h}" fill="#000000"/>'
            f'<text x="4" y="{height - 6}" style="font: 9px \'DejaVu Sans\'">{label}</text></svg>')


FIGURES = [(_figure(460.8, 244.8, (100.0, 40.0, 120.0, 80.0), "first figure θ/α"), ""),
           (_figure(504.0, 446.4, (300.0, 200.0, 60.0, 150.0), "second figure SD_max"), ' class="narrow"'),
           (_figure(475.2, 187.2, (20.0, 20.0, 400.0, 30.0), "third figure u_B"), ' class="history"')]


def _html() -> str:
    paragraphs = "".join(f"<p>Paragraph {k}: text that pushes the figures down the pages.</p>" for k in range(14))
    body = ""
    for k, (svg, cls) in enumerate(FIGURES):
        body += f"<h2>Section {k}</h2>{paragraphs}<figure{cls}>{render.svg_image(svg)}<figcaption>Figure {k}" \
                f"</figcaption></figure>"
    return f"<html><head><style>{render.stylesheet()}</style></head><body>{body}</body></html>"


def _black_boxes(pdf_bytes: bytes) -> list[tuple[int, tuple[int, int, int, int]]]:
    """(page, (left, top, right, bottom) in pixels at DPI) of the black ink on each page that has some."""
    doc = pdfium.PdfDocument(pdf_bytes)
    out = []
    for index in range(len(doc)):
        image = np.asarray(doc[index].render(scale=DPI / 72).to_pil().convert("L"))
        rows, cols = np.nonzero(image < 40)
        if rows.size:
            out.append((index, (int(cols.min()), int(rows.min()), int(cols.max()), int(rows.max()))))
    return out


def test_slots_keep_each_figure_and_its_box():
    html = _html()
    slotted, svgs = stamped_pdf.slot_html(html)
    assert svgs == [svg for svg, _ in FIGURES]
    for k, svg in enumerate(svgs):
        assert f'id="{stamped_pdf.SLOT_ID}{k}"' in slotted
        empty = base64.b64encode(stamped_pdf.empty_svg(stamped_pdf.view_box(svg)).encode()).decode()
        assert empty in slotted
    assert "black" not in slotted and "#000000" not in slotted


def test_figures_land_where_weasyprint_draws_them(tmp_path):
    """Each black rectangle, drawn by WeasyPrint from the SVG (reference) and stamped from typst's PDF:
    the same page and the same pixels (± 1 px at 96 dpi; the figures span 300–650 px)."""
    from weasyprint import HTML
    html = _html()
    reference = _black_boxes(HTML(string=html, base_url=str(render.templates_dir())).write_pdf())
    ours = _black_boxes(stamped_pdf.html_to_pdf(html, tmp_path / "stamped.pdf").read_bytes())
    assert len(reference) == 3 and [p for p, _ in ours] == [p for p, _ in reference]
    assert len({p for p, _ in reference}) >= 2          # the figures fall on more than one page
    for (_, a), (_, b) in zip(ours, reference):
        assert np.max(np.abs(np.subtract(a, b))) <= 1, (a, b)


def test_figure_text_stays_text(tmp_path):
    path = stamped_pdf.html_to_pdf(_html(), tmp_path / "stamped.pdf")
    pages = [page.extract_text() for page in pypdf.PdfReader(str(path)).pages]
    for k, label in enumerate(("first figure θ/α", "second figure SD_max", "third figure u_B")):
        # on the page of its own caption
        assert any(label in text and f"Figure {k}" in text for text in pages), label


def test_a_figure_without_its_box_is_refused(tmp_path):
    slotted, svgs = stamped_pdf.slot_html(_html())
    slots = stamped_pdf.layout_pdf(slotted, tmp_path / "pages.pdf")
    assert len(slots) == 3
    with pytest.raises(ValueError, match="2 figures for 3 figure boxes"):
        stamped_pdf.stamp(tmp_path / "pages.pdf", slots, stamped_pdf.figure_pdfs(svgs[:2]))


def test_every_figure_of_the_check_report_is_stamped(curved_out):
    """Each figure of report.html is painted once in report.pdf, each by a Form XObject of its own."""
    import re
    html_figures = len(stamped_pdf.slot_html(curved_out.html)[1])
    reader = pypdf.PdfReader(str(curved_out.out / "report.pdf"))
    painted = []
    for page in reader.pages:
        forms = {name for name, x in page.get("/Resources", {}).get("/XObject", {}).items()
                 if x.get_object().get("/Subtype") == "/Form"}
        painted += [n for n in re.findall(rb"(/\S+) Do\b", page.get_contents().get_data()) if n.decode() in forms]
    assert len(painted) == html_figures == len(set(painted)) and html_figures >= 8


def test_a_report_without_figures(tmp_path):
    html = f"<html><head><style>{render.stylesheet()}</style></head><body><p>No figure here.</p></body></html>"
    path = stamped_pdf.html_to_pdf(html, tmp_path / "plain.pdf")
    assert "No figure here." in pypdf.PdfReader(str(path)).pages[0].extract_text()


def test_a_figure_typst_refuses_is_drawn_by_weasyprint(tmp_path, monkeypatch):
    """The figures are never lost: when typst cannot draw one, WeasyPrint draws them all, in place."""
    from weasyprint import HTML

    def refuse(svgs):
        raise RuntimeError("typst: unsupported SVG")
    monkeypatch.setattr(stamped_pdf, "figure_pdfs", refuse)
    ours = _black_boxes(stamped_pdf.html_to_pdf(_html(), tmp_path / "fallback.pdf").read_bytes())
    assert ours == _black_boxes(HTML(string=_html(), base_url=str(render.templates_dir())).write_pdf())
    assert len(ours) == 3


def test_the_check_report_survives_a_figure_it_cannot_stamp(curved_out, tmp_path, monkeypatch):
    """A figure typst refuses: the check's report is laid out again, whole, with every figure in it (slower,
    same content)."""
    from rockdesign.kinds import kind_of
    from rockdesign.report.document import write_document
    monkeypatch.setattr(stamped_pdf, "figure_pdfs", lambda svgs: (_ for _ in ()).throw(RuntimeError("typst")))
    written = write_document(kind_of(curved_out.result).report(curved_out.result), tmp_path, html=False)
    text = "".join(page.extract_text() for page in pypdf.PdfReader(str(written["pdf"])).pages)
    assert "Pushover curve" in text and "θ [rad]" in text      # the section and its figure's axis label
