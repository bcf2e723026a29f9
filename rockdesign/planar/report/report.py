"""The planar kind's calculation report (columns, frames, podiums): its figures, its HTML from the
``report.html.j2`` template, and the PDF (:mod:`rockdesign.report.render`)."""
from __future__ import annotations

import jinja2

from ...paths import templates_dir
from ...report.formatting import DIGITS
from ...report.render import TEMPLATE, environment, stylesheet
from ...report.scaling_figures import has_target, scaling_figure
from ...report.svg import ink_box, svg
from . import figures
from .demand_figures import demand_figure, demand_history_figure
from .drawing import structure_drawing
from .verification import normalise
from .context import build_context, given_value


def _given_inputs(project) -> dict:
    """The project file's texts of the inputs the structure drawing labels (units as given)."""
    return {"cap_beam_mass": given_value(project, "podium", "cap_beam_mass"),
            "superstructure_mass": given_value(project, "superstructure", "mass"),
            "superstructure_period": given_value(project, "superstructure", "period"),
            "superstructure_damping": given_value(project, "superstructure", "damping")}


def make_figures(result) -> dict[str, tuple]:
    """Every report figure as ``name: (matplotlib Figure, id prefix, crop box or None)``, not yet drawn
    (``history:<record id>`` for time histories).  Each figure lays itself out when drawn and fills its
    ``figsize``; the structure drawing (to scale) is cropped to its ink (:func:`figures.ink_box`)."""
    system = result.project.system
    drawing = structure_drawing(system, _given_inputs(result.project))
    out = {
        "drawing": (drawing, "drawing", ink_box(drawing)),
        "pushover": (figures.pushover_figure(result.figure_data["pushover"]), "pushover", None),
        "spectra": (figures.spectra_figure(result), "spectra", None),
        "scatter": (figures.polyakov_scatter_figure(result), "scatter", None),
        "ecdf": (figures.ecdf_figure(result), "ecdf", None),
        "margins": (figures.margin_figure(result), "margins", None),
    }
    scaling = result.scaling
    if has_target(scaling):
        out["scaling"] = (scaling_figure(scaling, system.g), "scaling", None)
    if getattr(result, "fragility", None) and result.fragility.get("capacities"):
        from ...report.fragility_figures import fragility_figure
        out["fragility"] = (fragility_figure(result), "fragility", None)
    for name, make in (("demand", demand_figure), ("demand_history", demand_history_figure)):
        fig = make(result)
        if fig is not None:
            out[name] = (fig, name, None)
    for k, rid in enumerate(result.histories):
        out[f"history:{rid}"] = (figures.history_figure(result, rid), f"history{k}", None)
    return out


def draw_figures(made: dict) -> dict[str, str]:
    """The SVG of each figure of :func:`make_figures`."""
    return {name: svg(fig, prefix, crop=crop if crop is not None else False) for name, (fig, prefix, crop) in made.items()}


def render_figures(result) -> dict[str, str]:
    """Inline SVG of every report figure, keyed by name (``history:<record id>`` for time histories)."""
    return draw_figures(make_figures(result))


def verification_statement(result) -> dict:
    """The engine's error on a closed-form case at the check's tolerance (:mod:`.verification`), as the check
    recorded it (results.json ``settings.engine_accuracy`` or ``verification``); {} when it recorded none
    (the report then has no verification paragraph: it runs no analysis)."""
    data = result.as_json()
    recorded = data.get("settings", {}).get("engine_accuracy") or data.get("verification")
    return normalise(recorded) if isinstance(recorded, dict) and recorded else {}


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


