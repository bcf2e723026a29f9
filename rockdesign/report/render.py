"""Rendering shared by every report (the kinds' calculation reports, the design chart's, the validation's):
jinja2 → HTML (figures inline as SVG images) → PDF by WeasyPrint, in this process (CONTRACT §4:
``report.html``, ``report.pdf``).  The figures stay vector in the PDF, their text stays text.

    environment(), stylesheet()       the jinja2 environment (filters fmt, number, sym, svgimg, cite) and CSS
    html_to_pdf(html, path)           the PDF of an HTML document

The template is ``templates/report.html.j2`` with ``report.css`` (folder
:func:`rockdesign.paths.templates_dir`).  Numbers are printed by the ``fmt`` filter
(:func:`rockdesign.report.formatting.fmt`) from the values of ``result.as_json()``, so the report
and results.json agree.  Rendering is deterministic apart from the date (``SOURCE_DATE_EPOCH``
fixes it).
"""
from __future__ import annotations

import base64

import html as html_lib
import re
from pathlib import Path

import jinja2

from ..display import readable_units
from ..paths import templates_dir
from .formatting import fmt, number, plural
from .methods import cite

TEMPLATE = "report.html.j2"
STYLESHEET = "report.css"

_SUBSCRIPT = re.compile(r"(?<![A-Za-z_]{4})_([A-Za-z0-9α-ωΑ-Ω,]{1,5})(?![A-Za-z0-9_])")
"""A thesis subscript (``SD_max``, ``u_B,max``, ``ü_g,up``); longer words (``mass_distribution``) and the parts of a
name (``margin_max_scale``) are names."""


def symbols(text) -> str:
    """HTML for a text with thesis symbols: escaped, ``x_ab`` → x<sub>ab</sub> (``SD_max``, ``u_B(θc)``);
    identifiers such as ``mass_distribution`` are left alone; references to the developer documentation
    become the report's appendix sections (:func:`~rockdesign.planar.report.methods.cite`)."""
    if text is None:
        return ""
    escaped = html_lib.escape(readable_units(cite(str(text))), quote=False)     # m/s^2 → m/s², as fmt writes it
    return _SUBSCRIPT.sub(r"<sub>\1</sub>", escaped)


def environment(folder: Path | None = None) -> jinja2.Environment:
    """The jinja2 environment of the report, with the filters ``fmt``, ``number``, ``sym``, ``svgimg``, ``cite``
    and ``plural`` (``{{ n|plural("ground motion") }}`` → "1 ground motion", "2 ground motions")."""
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(folder or templates_dir())),
                             autoescape=jinja2.select_autoescape(["html", "j2", "xml"], default=True),
                             undefined=jinja2.Undefined,   # a key missing from results.json prints "—"
                             trim_blocks=False, lstrip_blocks=False, keep_trailing_newline=True)
    env.filters["fmt"] = lambda value, unit=None: "—" if isinstance(value, jinja2.Undefined) else fmt(value, unit)
    env.filters["number"] = lambda value: "—" if isinstance(value, jinja2.Undefined) else number(value)
    env.filters["sym"] = lambda text: jinja2.utils.markupsafe.Markup(symbols(text))
    env.filters["svgimg"] = svg_image
    env.filters["cite"] = lambda text: "" if isinstance(text, jinja2.Undefined) else cite(text)
    env.filters["plural"] = lambda count, word, words=None: plural(count, word, words)    # 1 ground motion, 2 …
    return env


def stylesheet(folder: Path | None = None) -> str:
    """The report's CSS (``report.css`` in the templates folder), "" when the folder has none."""
    path = (folder or templates_dir()) / STYLESHEET
    return path.read_text(encoding="utf-8") if path.exists() else ""


def svg_image(svg_text) -> str:
    """An SVG figure as an ``<img>`` with a data URI: still a vector figure, but WeasyPrint renders it
    through its SVG module instead of cascading the page's CSS over every path (≈ 3× faster)."""
    if isinstance(svg_text, jinja2.Undefined) or not svg_text:
        return ""
    data = base64.b64encode(str(svg_text).encode("utf-8")).decode("ascii")
    return jinja2.utils.markupsafe.Markup(f'<img class="figure" alt="figure" src="data:image/svg+xml;base64,{data}">')


def html_to_pdf(html_text: str, path: Path, base_url: str | None = None) -> Path:
    """Render an HTML document (figures as SVG images, :func:`svg_image`) to the PDF ``path`` with WeasyPrint.

    One route for every report, in this process.  (Measured against laying out the pages with empty figure
    boxes while another process drew the figures, and stamping the figures in from a typst PDF: that made
    ``check`` ≈ 13 % cheaper in CPU, less than a fifth of the command, for two more dependencies, a second
    process and a private WeasyPrint API: docs/engine.md, "Speed".)"""
    from weasyprint import HTML
    path = Path(path)
    HTML(string=html_text, base_url=base_url or str(templates_dir())).write_pdf(str(path))
    return path


def write_html(text: str, out_dir: Path) -> Path:
    """``report.html`` in ``out_dir``."""
    path = out_dir / "report.html"
    path.write_text(text, encoding="utf-8")
    return path


