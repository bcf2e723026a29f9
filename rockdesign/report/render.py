"""The calculation report of ``rockdesign check``: jinja2 template → HTML (figures inline as SVG) →
PDF: pages by WeasyPrint, figures stamped in (:mod:`rockdesign.report.stamped_pdf`) (CONTRACT §4:
``report.html``, ``report.pdf``).

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


def make_figures(result) -> dict[str, tuple]:
    """Every report figure as ``name: (matplotlib Figure, id prefix, crop box or None)``, not yet drawn
    (``history:<record id>`` for time histories).  Each figure lays itself out when drawn and fills its
    ``figsize``; the structure drawing (to scale) is cropped to its ink (:func:`figures.ink_box`)."""
    from . import figures
    from .drawing import structure_drawing
    system = result.project.system
    drawing = structure_drawing(system, _given_inputs(result.project))
    out = {
        "drawing": (drawing, "drawing", figures.ink_box(drawing)),
        "pushover": (figures.pushover_figure(system), "pushover", None),
        "spectra": (figures.spectra_figure(result), "spectra", None),
        "scatter": (figures.polyakov_scatter_figure(result), "scatter", None),
        "ecdf": (figures.ecdf_figure(result), "ecdf", None),
        "margins": (figures.margin_figure(result), "margins", None),
    }
    if getattr(result, "fragility", None) and result.fragility.get("capacities"):
        from .fragility_figures import fragility_figure
        out["fragility"] = (fragility_figure(result), "fragility", None)
    from .demand_figures import demand_figure, demand_history_figure
    for name, make in (("demand", demand_figure), ("demand_history", demand_history_figure)):
        fig = make(result)
        if fig is not None:
            out[name] = (fig, name, None)
    for k, rid in enumerate(result.histories):
        out[f"history:{rid}"] = (figures.history_figure(result, rid), f"history{k}", None)
    return out


def figure_boxes(made: dict) -> dict[str, str]:
    """An empty SVG per figure of :func:`make_figures` with the viewBox its drawing will have (the figure
    size in points): the report laid out with these has the figures' page layout."""
    from .figures import view_box_of
    from .stamped_pdf import empty_svg
    return {name: empty_svg(view_box_of(fig, crop)) for name, (fig, _, crop) in made.items()}


def draw_figures(made: dict) -> dict[str, str]:
    """The SVG of each figure of :func:`make_figures` (the viewBox :func:`figure_boxes` announced)."""
    from .figures import svg
    return {name: svg(fig, prefix, crop=crop if crop is not None else False) for name, (fig, prefix, crop) in made.items()}


def render_figures(result) -> dict[str, str]:
    """Inline SVG of every report figure, keyed by name (``history:<record id>`` for time histories)."""
    return draw_figures(make_figures(result))


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
    return html_renderer(result, date=date)(figures if figures is not None else render_figures(result))


def html_renderer(result, *, date: str | None = None):
    """``render(figures) -> str``: :func:`render_html` of ``result`` with the context built once, for
    rendering the same report with different figures (empty boxes first, then the drawings)."""
    folder = templates_dir()
    template = environment(folder).get_template(TEMPLATE)
    ctx = build_context(result, figures={}, verification=verification_statement(result), date=date)
    ctx["css"] = jinja2.utils.markupsafe.Markup(stylesheet(folder))
    ctx["digits"] = DIGITS

    def render(figures: dict) -> str:
        histories = [{**h, "svg": figures.get(f"history:{h['id']}", "")} for h in ctx["histories"]]
        return template.render(**{**ctx, "figures": figures, "histories": histories})
    return render


def warm_up(pdf: bool = True) -> None:
    """Load the report's libraries, fonts and style sheets (matplotlib with mathtext, typst, and
    WeasyPrint with the report's CSS unless ``pdf`` is False) by rendering a small figure and page into
    memory.  The first report of a process is ≈ 1 s slower without it; ``rockdesign check`` calls this
    while its rocking engine is still compiling on the first run, when this process would otherwise
    wait (:mod:`rockdesign.dynamics.compilation`)."""
    from . import figures
    from .stamped_pdf import figure_pdfs
    fig, ax = figures.plt.subplots(figsize=(2.0, 1.5))
    ax.plot([0.0, 1.0], [0.0, 1.0], "o-", label=r"$F_R/(m_C\,g)$, θ")
    ax.set_xlabel("θ [rad]")
    ax.legend()
    fig.set_layout_engine("tight")
    figure_pdfs([figures.svg(fig, "warm-up", crop=False)])
    if pdf:
        warm_up_pdf()


def warm_up_pdf() -> None:
    """Load WeasyPrint, the fonts and the report's style sheet by rendering a small page (with an empty
    figure box, as the report's pages are laid out) into memory: the PDF part of :func:`warm_up`,
    without matplotlib (the PDF worker of :mod:`rockdesign.report.pdf_worker` calls it)."""
    import io

    from weasyprint import HTML

    from .stamped_pdf import empty_svg
    folder = templates_dir()
    css = stylesheet(folder)
    page = (f"<html><head><style>{css}</style></head><body><h1>θ</h1><p>SD<sub>max</sub> <b>b</b> <i>i</i> "
            f"<code>c</code></p><table><tr><th>a</th><td>1</td></tr></table>"
            f"{svg_image(empty_svg('0 0 144 108'))}</body></html>")
    HTML(string=page, base_url=str(folder)).write_pdf(io.BytesIO())


def html_to_pdf(html_text: str, path: Path, base_url: str | None = None) -> Path:
    """Render HTML (figures as SVG images) to a PDF file: WeasyPrint for the pages, the figures stamped
    in (:mod:`rockdesign.report.stamped_pdf`)."""
    from .stamped_pdf import html_to_pdf as stamped
    return stamped(html_text, Path(path), base_url)


def write_report(result, out_dir, *, pdf: bool = True, html: bool = True, render=None,
                 pdf_worker=None) -> dict[str, Path]:
    """Write ``report.html`` and/or ``report.pdf`` of a check result into ``out_dir``.

    ``render(result) -> str`` makes the HTML (default: the planar CheckResult's report, whose pages are
    laid out — by ``pdf_worker`` when given — while its figures are drawn; see :func:`_planar_report`).
    ``pdf_worker``: a started :class:`~rockdesign.report.pdf_worker.PdfWorker` lays out the PDF (this
    process does if it fails); the file is the same.

    Returns:
        {"html": path, "pdf": path} for the files written.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    if not (pdf or html):
        return {}
    if render is None and pdf:
        return _planar_report(result, out_dir, html=html, pdf_worker=pdf_worker)
    text = (render or render_html)(result)
    written: dict[str, Path] = {}
    if html:
        written["html"] = _write_html(text, out_dir)
    if pdf:
        written["pdf"] = _pdf(text, out_dir / "report.pdf", pdf_worker)
    return written


def _write_html(text: str, out_dir: Path) -> Path:
    path = out_dir / "report.html"
    path.write_text(text, encoding="utf-8")
    return path


def _planar_report(result, out_dir: Path, *, html: bool, pdf_worker) -> dict[str, Path]:
    """The check's report with its two halves at once: the pages are laid out with an empty box per
    figure (each figure's size is known before it is drawn), by the worker when there is one, while
    this process draws the figures; then the figures are stamped into their boxes."""
    from . import stamped_pdf
    made = make_figures(result)
    render = html_renderer(result)
    slotted, boxes = stamped_pdf.slot_html(render(figure_boxes(made)))
    path = out_dir / "report.pdf"
    job = pdf_worker.begin_layout(slotted, path) if pdf_worker is not None else None
    text = render(draw_figures(made))
    written = {"html": _write_html(text, out_dir)} if html else {}
    _, svgs = stamped_pdf.slot_html(text)
    same_boxes = [stamped_pdf.view_box(b) for b in boxes] == [stamped_pdf.view_box(s) for s in svgs]
    figures = stamped_pdf.figure_pdfs_or_none(svgs) if same_boxes else None
    if figures is None:
        # a figure drawn at another size than it announced, or one typst refused: the PDF again, whole
        if job is not None:
            job.result()        # (the worker writes the same file: wait for it)
        written["pdf"] = stamped_pdf.html_to_pdf(text, path)
        return written
    slots = job.result() if job is not None else stamped_pdf.layout_pdf(slotted, path)
    written["pdf"] = stamped_pdf.stamp(path, slots, figures)
    return written


def _pdf(text: str, path: Path, pdf_worker) -> Path:
    if pdf_worker is None:
        return html_to_pdf(text, path)
    from .stamped_pdf import drawn_by_weasyprint, figure_pdfs_or_none, slot_html, stamp
    slotted, svgs = slot_html(text)
    job = pdf_worker.begin_layout(slotted, path)
    figures = figure_pdfs_or_none(svgs)
    slots = job.result()        # (the worker writes the file: wait for it either way)
    return stamp(path, slots, figures) if figures is not None else drawn_by_weasyprint(text, path)
