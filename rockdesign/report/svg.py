"""Figures as the reports embed them: matplotlib figures → compact, deterministic SVG (ids salted per
figure, presentation attributes kept, the drawing cropped to its ink where asked)."""
from __future__ import annotations

import io
import re

from .. import mplfig as plt


SVG_SALT = "rockdesign-report"


def ink_box(fig):
    """The box (inches) that ``bbox_inches="tight"`` would crop ``fig`` to, found by laying the figure out
    once without drawing it: for figures whose axes keep an aspect ratio (drawings to scale), which leave
    blank bands in their figure size.  Saving with it crops the same way, and the size is known before
    drawing."""
    import matplotlib
    fig.draw_without_rendering()
    return fig.get_tightbbox().padded(matplotlib.rcParams["savefig.pad_inches"])


def svg(fig, prefix: str, *, crop=True) -> str:
    """SVG markup of ``fig`` for inline use (XML prolog dropped, ids prefixed), and close the figure.

    ``crop``: True cuts the drawing to its ink (``bbox_inches="tight"``, one more drawing pass); a box
    of :func:`ink_box` cuts it to that box; False keeps the figure size, which the figure's layout
    engine fills."""
    buf = io.StringIO()
    # every line stays vector (WeasyPrint draws the SVG into the PDF), and
    # text stays text (searchable in the PDF)
    with plt.rc_context({"svg.hashsalt": SVG_SALT, "svg.fonttype": "none"}):
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None},
                    bbox_inches="tight" if crop is True else (crop or None))
    plt.close(fig)
    text = buf.getvalue()
    text = text[text.index("<svg"):]
    text = re.sub(r'id="([^"]+)"', lambda m: f'id="{prefix}-{m.group(1)}"', text)
    text = re.sub(r'(xlink:href|href)="#([^"]+)"', lambda m: f'{m.group(1)}="#{prefix}-{m.group(2)}"', text)
    text = re.sub(r"url\(#([^)]+)\)", lambda m: f"url(#{prefix}-{m.group(1)})", text)
    # size the figure by the page (CSS), keeping the aspect ratio of the viewBox
    text = re.sub(r'<svg([^>]*?) width="[^"]+" height="[^"]+"', r'<svg\1', text, count=1)
    return slim_svg(text)


PRESENTATION_ATTRIBUTES = frozenset({
    "fill", "fill-opacity", "fill-rule", "stroke", "stroke-width", "stroke-opacity", "stroke-linecap",
    "stroke-linejoin", "stroke-dasharray", "stroke-dashoffset", "stroke-miterlimit", "opacity",
    "font-size", "font-family", "font-weight", "font-style", "text-anchor", "clip-path"})
"""CSS properties of matplotlib's SVG that SVG also accepts as presentation attributes."""


_MPL_STYLE = '<style type="text/css">*{stroke-linejoin: round; stroke-linecap: butt}</style>'


def slim_svg(text: str) -> str:
    """The same drawing with less for WeasyPrint to parse (≈ 10 % of the report's PDF time): no RDF
    metadata, matplotlib's universal ``*{stroke-linejoin; stroke-linecap}`` rule as inherited attributes
    of the root, and ``style="…"`` declarations as presentation attributes (only the properties SVG
    accepts as attributes; anything else stays in ``style``)."""
    text = re.sub(r"\s*<metadata>.*?</metadata>", "", text, count=1, flags=re.S)
    if _MPL_STYLE in text:
        text = text.replace(_MPL_STYLE, "", 1)
        text = text.replace("<svg ", '<svg stroke-linejoin="round" stroke-linecap="butt" ', 1)
        text = re.sub(r"\s*<defs>\s*</defs>", "", text, count=1)

    def attributes(match) -> str:
        attrs, rest = [], []
        for decl in match.group(1).split(";"):
            if ":" not in decl:
                continue
            name, value = (part.strip() for part in decl.split(":", 1))
            (attrs if name in PRESENTATION_ATTRIBUTES and '"' not in value else rest).append((name, value))
        out = " ".join(f'{name}="{value}"' for name, value in attrs)
        if rest:
            out += (" " if out else "") + 'style="' + "; ".join(f"{n}: {v}" for n, v in rest) + '"'
        return out

    return re.sub(r'style="([^"]*)"', attributes, text)
