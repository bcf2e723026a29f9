"""The reports' PDF: WeasyPrint lays out the text and tables, each figure is stamped in as vector PDF.

WeasyPrint draws an SVG figure node by node in Python: in the check's 22-page report the figures
took ≈ 40 % of the PDF's time.  Here the report's HTML goes to WeasyPrint with every figure replaced
by an empty SVG of the same ``viewBox`` (:func:`slot_html`), so the page layout is exactly the one the
figures would get; :func:`layout_pdf` writes that PDF and returns where each figure's box landed
(:class:`Slot`).  :func:`figure_pdfs` turns the figures' SVG into a PDF of one page per figure with
typst (its SVG renderer is compiled: ≈ 0.1 s for the check's 12 figures, text stays text), and
:func:`stamp` places each page into its box as a Form XObject with pikepdf (qpdf; no content stream
is parsed).  Written here only because no
library does the whole route; each step is a library call.

The two halves are independent, so ``rockdesign check`` runs them at the same time: the layout in
its PDF worker (:mod:`rockdesign.report.pdf_worker`) while it draws the figures
(:func:`rockdesign.report.render.write_report`).  :func:`html_to_pdf` is the same route in one
process, for every report.  If typst refuses a figure, WeasyPrint draws the figures itself
(:func:`drawn_by_weasyprint`: the same pages, slower).  Measurements: docs/engine.md, "Where a warm check spends its time".
"""
from __future__ import annotations

import base64
import io
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

FIGURE_IMAGE = re.compile(r'<img class="figure"(?P<attrs>[^>]*?) src="data:image/svg\+xml;base64,(?P<data>[A-Za-z0-9+/=]+)">')
"""A figure of the report's HTML (:func:`rockdesign.report.render.svg_image` writes them)."""
SLOT_ID = "figure-slot-"
PX_TO_PT = 0.75
"""CSS pixels (1/96 in) to PDF points (1/72 in)."""


@dataclass(frozen=True)
class Slot:
    """Where a figure's box landed: page index, and the box's content rectangle in PDF points from the
    page's lower-left corner (PDF coordinates)."""
    page: int
    x: float
    y: float
    width: float
    height: float


def view_box(svg_text: str) -> str:
    """The ``viewBox`` of an SVG document's root element ("" when it has none)."""
    root = re.search(r"<svg\b[^>]*>", svg_text)
    found = re.search(r'viewBox="([^"]+)"', root.group(0)) if root else None
    return found.group(1) if found else ""


def empty_svg(box: str) -> str:
    """An SVG with nothing in it and the given ``viewBox``: the same box in the layout as the figure."""
    return f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{box}"></svg>'


def slot_html(html_text: str) -> tuple[str, list[str]]:
    """``(html, figures)``: the HTML with each figure replaced by an empty SVG of the same viewBox and the
    id ``figure-slot-<k>``, and the figures' SVG texts in document order (k)."""
    figures: list[str] = []

    def replace(match) -> str:
        svg = base64.b64decode(match.group("data")).decode("utf-8")
        empty = base64.b64encode(empty_svg(view_box(svg)).encode("utf-8")).decode("ascii")
        figures.append(svg)
        return (f'<img class="figure" id="{SLOT_ID}{len(figures) - 1}"{match.group("attrs")} '
                f'src="data:image/svg+xml;base64,{empty}">')

    return FIGURE_IMAGE.sub(replace, html_text), figures


def layout_pdf(html_text: str, path: Path, base_url: str | None = None) -> list[Slot]:
    """Write ``html_text`` (from :func:`slot_html`) to the PDF ``path`` with WeasyPrint and return the
    figure slots' rectangles, in the order of their ids."""
    from weasyprint import HTML

    from ..paths import templates_dir
    document = HTML(string=html_text, base_url=base_url or str(templates_dir())).render()
    found: dict[int, Slot] = {}
    for index, page in enumerate(document.pages):
        for box in page._page_box.descendants():     # (WeasyPrint's layout boxes: pinned below 71)
            element = getattr(box, "element", None)
            name = element.get("id", "") if getattr(box, "element_tag", None) == "img" else ""
            if name.startswith(SLOT_ID):
                x, y = box.content_box_x(), box.content_box_y()
                found[int(name[len(SLOT_ID):])] = Slot(
                    index, x * PX_TO_PT, (page.height - y - box.height) * PX_TO_PT,
                    box.width * PX_TO_PT, box.height * PX_TO_PT)
    document.write_pdf(str(path))
    return [found[k] for k in sorted(found)]


def _fonts_folder() -> str:
    """matplotlib's own fonts (DejaVu): the figures' text was measured with them."""
    import matplotlib
    return str(Path(matplotlib.get_data_path()) / "fonts" / "ttf")


def figure_pdfs(svgs: list[str]) -> bytes:
    """The SVG figures as one PDF, page k being figure k at its viewBox's size (typst, one compilation:
    the fonts are read and embedded once; they are matplotlib's, no system font is read, no date is
    written)."""
    if not svgs:
        return b""
    import typst
    source = "#set document(date: none)\n#set page(width: auto, height: auto, margin: 0pt)\n"
    with tempfile.TemporaryDirectory(prefix="rockdesign-figures-") as folder:
        for k, svg in enumerate(svgs):
            (Path(folder) / f"figure{k}.svg").write_text(svg, encoding="utf-8")
            source += ("#pagebreak()\n" if k else "") + f'#image("figure{k}.svg")\n'
        (Path(folder) / "figures.typ").write_text(source, encoding="utf-8")
        return typst.compile(str(Path(folder) / "figures.typ"), font_paths=[_fonts_folder()],
                             ignore_system_fonts=True)


def figure_pdfs_or_none(svgs: list[str]) -> bytes | None:
    """:func:`figure_pdfs`, or None when typst refuses a figure (the caller lets WeasyPrint draw the
    figures: :func:`drawn_by_weasyprint`)."""
    try:
        return figure_pdfs(svgs)
    except Exception:   # noqa: BLE001 — any refusal of typst's: the figures are drawn another way
        return None


def stamp(path: Path, slots: list[Slot], figures: bytes) -> Path:
    """Place page k of the PDF ``figures`` (:func:`figure_pdfs`) into slot k of the PDF ``path``
    (rewritten in place)."""
    import pikepdf
    path = Path(path)
    if not slots and not figures:
        return path
    with pikepdf.open(path) as pdf, pikepdf.open(io.BytesIO(figures)) as source:
        if len(slots) != len(source.pages):
            raise ValueError(f"{len(source.pages)} figures for {len(slots)} figure boxes in {path}")
        for slot, page in zip(slots, source.pages):
            pdf.pages[slot.page].add_overlay(page, pikepdf.Rectangle(
                slot.x, slot.y, slot.x + slot.width, slot.y + slot.height))
        staged = path.with_name(path.name + ".part")
        pdf.save(staged, deterministic_id=True)
    staged.replace(path)
    return path


def html_to_pdf(html_text: str, path: Path, base_url: str | None = None) -> Path:
    """The report's HTML (figures as SVG images) to the PDF ``path``: figures, layout, stamps in turn
    (:func:`drawn_by_weasyprint` if typst cannot draw a figure)."""
    slotted, svgs = slot_html(html_text)
    figures = figure_pdfs_or_none(svgs)
    if figures is None:
        return drawn_by_weasyprint(html_text, Path(path), base_url)
    return stamp(Path(path), layout_pdf(slotted, Path(path), base_url), figures)


def drawn_by_weasyprint(html_text: str, path: Path, base_url: str | None = None) -> Path:
    """The report's HTML to the PDF ``path`` with WeasyPrint drawing the SVG figures itself: the same
    pages (the boxes are the figures' own), ≈ 2 s slower for the check's report."""
    from weasyprint import HTML

    from ..paths import templates_dir
    HTML(string=html_text, base_url=base_url or str(templates_dir())).write_pdf(str(path))
    return path
