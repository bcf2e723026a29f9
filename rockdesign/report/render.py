"""The calculation report of ``rockdesign check``: jinja2 template → HTML (figures inline as SVG) →
WeasyPrint PDF (CONTRACT §4: ``report.html``, ``report.pdf``).

    write_report(result, out_dir, pdf=True, html=True) -> {"html": Path, "pdf": Path}
    render_html(result) -> str

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

from ..paths import templates_dir
from .context import build_context
from .formatting import DIGITS, fmt, number
from .methods import cite

TEMPLATE = "report.html.j2"
STYLESHEET = "report.css"

_SUBSCRIPT = re.compile(r"(?<![A-Za-z]{4})_([A-Za-z0-9α-ωΑ-Ω,]{1,5})(?![A-Za-z0-9_])")
"""A thesis subscript (``SD_max``, ``u_B,max``, ``ü_g,up``); longer words (``mass_distribution``) are names."""


def symbols(text) -> str:
    """HTML for a text with thesis symbols: escaped, ``x_ab`` → x<sub>ab</sub> (``SD_max``, ``u_B(θc)``);
    identifiers such as ``mass_distribution`` are left alone; references to the developer documentation
    become the report's appendix sections (:func:`~rockdesign.report.methods.cite`)."""
    if text is None:
        return ""
    escaped = html_lib.escape(cite(str(text)), quote=False)
    return _SUBSCRIPT.sub(r"<sub>\1</sub>", escaped)


def environment(folder: Path | None = None) -> jinja2.Environment:
    """The jinja2 environment of the report, with the filters ``fmt``, ``number`` and ``sym``."""
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(folder or templates_dir())),
                             autoescape=jinja2.select_autoescape(["html", "j2", "xml"], default=True),
                             undefined=jinja2.Undefined,   # a key missing from results.json prints "—"
                             trim_blocks=False, lstrip_blocks=False, keep_trailing_newline=True)
    env.filters["fmt"] = lambda value, unit=None: "—" if isinstance(value, jinja2.Undefined) else fmt(value, unit)
    env.filters["number"] = lambda value: "—" if isinstance(value, jinja2.Undefined) else number(value)
    env.filters["sym"] = lambda text: jinja2.utils.markupsafe.Markup(symbols(text))
    env.filters["svgimg"] = svg_image
    env.filters["cite"] = lambda text: "" if isinstance(text, jinja2.Undefined) else cite(text)
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


def _given_inputs(project) -> dict:
    """The project file's texts of the inputs the structure drawing labels (units as given)."""
    from .context import given_value
    return {"cap_beam_mass": given_value(project, "podium", "cap_beam_mass"),
            "superstructure_mass": given_value(project, "superstructure", "mass"),
            "superstructure_period": given_value(project, "superstructure", "period"),
            "superstructure_damping": given_value(project, "superstructure", "damping")}


def render_figures(result) -> dict[str, str]:
    """Inline SVG of every report figure, keyed by name (``history:<record id>`` for time histories)."""
    from . import figures
    from .drawing import structure_drawing
    system = result.project.system
    out = {
        "drawing": figures.svg(structure_drawing(system, _given_inputs(result.project)), "drawing"),
        "pushover": figures.svg(figures.pushover_figure(system), "pushover"),
        "spectra": figures.svg(figures.spectra_figure(result), "spectra"),
        "scatter": figures.svg(figures.polyakov_scatter_figure(result), "scatter"),
        "ecdf": figures.svg(figures.ecdf_figure(result), "ecdf"),
        "margins": figures.svg(figures.margin_figure(result), "margins"),
    }
    if getattr(result, "fragility", None) and result.fragility.get("capacities"):
        from .fragility_figures import fragility_figure
        out["fragility"] = figures.svg(fragility_figure(result), "fragility")
    from .demand_figures import demand_figure, demand_history_figure
    for name, make in (("demand", demand_figure), ("demand_history", demand_history_figure)):
        fig = make(result)
        if fig is not None:
            out[name] = figures.svg(fig, name)
    for k, rid in enumerate(result.histories):
        out[f"history:{rid}"] = figures.svg(figures.history_figure(result, rid), f"history{k}")
    return out


def verification_statement(result) -> dict:
    """The engine's error on a closed-form case at the check's tolerance (see :mod:`.verification`):
    taken from results.json when the check recorded it (``settings.engine_accuracy`` or
    ``verification``), else measured now."""
    from .verification import engine_accuracy_statement, normalise
    data = result.as_json()
    recorded = data.get("settings", {}).get("engine_accuracy") or data.get("verification")
    if isinstance(recorded, dict) and recorded:
        return normalise(recorded)
    s = result.settings
    return engine_accuracy_statement(float(s.get("rtol", 1e-10)), float(s.get("atol", 1e-12)))


def render_html(result, *, figures: dict | None = None, date: str | None = None) -> str:
    """The report as one self-contained HTML document (CSS and SVG figures inline)."""
    folder = templates_dir()
    env = environment(folder)
    css = stylesheet(folder)
    ctx = build_context(result, figures=figures if figures is not None else render_figures(result),
                        verification=verification_statement(result), date=date)
    ctx["css"] = jinja2.utils.markupsafe.Markup(css)
    ctx["digits"] = DIGITS
    return env.get_template(TEMPLATE).render(**ctx)


def warm_up(pdf: bool = True) -> None:
    """Load the report's libraries, fonts and style sheets (matplotlib with mathtext, WeasyPrint with the
    report's CSS, unless ``pdf`` is False) by rendering a small figure and page into memory.  The first
    report of a process is ≈ 1 s slower without it; ``rockdesign check`` calls this while its rocking
    engine is still compiling on the first run, when this process would otherwise wait
    (:mod:`rockdesign.dynamics.compilation`)."""
    from . import figures
    fig, ax = figures.plt.subplots(figsize=(2.0, 1.5))
    ax.plot([0.0, 1.0], [0.0, 1.0], "o-", label=r"$F_R/(m_C\,g)$, θ")
    ax.set_xlabel("θ [rad]")
    ax.legend()
    fig.tight_layout()
    figure = figures.svg(fig, "warm-up")
    if pdf:
        warm_up_pdf(figure)


WARM_UP_SVG = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
               'viewBox="0 0 144 108"><defs><path id="warm-up-m" d="M 0 -3 L 3 3 L -3 3 z"/></defs>'
               '<path d="M 10 90 L 130 20" style="fill: none; stroke: #1f77b4; stroke-width: 1.5"/>'
               '<use xlink:href="#warm-up-m" x="10" y="90" style="fill: #1f77b4"/>'
               '<text style="font: 10px \'DejaVu Sans\'; text-anchor: middle" x="72" y="104">θ [rad]</text></svg>')
"""A small figure in the form of the report's (a line, a marker, text) for :func:`warm_up_pdf`."""


def warm_up_pdf(figure: str = WARM_UP_SVG) -> None:
    """Load WeasyPrint, the fonts and the report's style sheet by rendering a small page with ``figure``
    (SVG) into memory: the PDF part of :func:`warm_up`, without matplotlib (the PDF worker of
    :mod:`rockdesign.report.pdf_worker` calls it)."""
    import io

    from weasyprint import HTML
    folder = templates_dir()
    css = stylesheet(folder)
    page = (f"<html><head><style>{css}</style></head><body><h1>θ</h1><p>SD<sub>max</sub> <b>b</b> <i>i</i> "
            f"<code>c</code></p><table><tr><th>a</th><td>1</td></tr></table>{svg_image(figure)}</body></html>")
    HTML(string=page, base_url=str(folder)).write_pdf(io.BytesIO())


def html_to_pdf(html_text: str, path: Path, base_url: str | None = None) -> Path:
    """Render HTML to a PDF file with WeasyPrint."""
    from weasyprint import HTML
    HTML(string=html_text, base_url=base_url or str(templates_dir())).write_pdf(str(path))
    return path


def write_report(result, out_dir, *, pdf: bool = True, html: bool = True, render=None,
                 pdf_worker=None) -> dict[str, Path]:
    """Write ``report.html`` and/or ``report.pdf`` of a check result into ``out_dir``.

    ``render(result) -> str`` makes the HTML (default :func:`render_html`, the planar CheckResult's report).
    ``pdf_worker``: a started :class:`~rockdesign.report.pdf_worker.PdfWorker` writes the PDF (this
    process does if it fails); the file is the same.

    Returns:
        {"html": path, "pdf": path} for the files written.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    written: dict[str, Path] = {}
    if not (pdf or html):
        return written
    text = (render or render_html)(result)
    if html:
        path = out_dir / "report.html"
        path.write_text(text, encoding="utf-8")
        written["html"] = path
    if pdf:
        written["pdf"] = _pdf(text, out_dir / "report.pdf", pdf_worker)
    return written


def _pdf(text: str, path: Path, pdf_worker) -> Path:
    return html_to_pdf(text, path) if pdf_worker is None else pdf_worker.pdf(text, path)
