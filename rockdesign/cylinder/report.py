"""The calculation report of ``rockdesign check`` for a ``[cylinder]`` project (thesis Ch. 5):
jinja2 template ``cylinder_report.html.j2`` (with the planar report's ``report.css``) → HTML →
WeasyPrint PDF.

    write_cylinder_report(result, out_dir, pdf=True, html=True) -> {"html": Path, "pdf": Path}
    render_cylinder_html(result) -> str

As in the planar report every number is printed by the ``fmt`` filter from ``result.as_json()``
(results.json), so the report and results.json agree.  Figures: the wobbling period T_w·p against
θ/α next to Housner's planar period (Fig 5.2), 3D against planar θ_max/α per pair, the overturning
fragility with the collapse margin (shared with every kind, :mod:`rockdesign.report.fragility_figures`)
and θ(t) with the plan-view orbit of the governing pairs (Figs 5.9–5.15).
"""
from __future__ import annotations

from pathlib import Path

import jinja2

from .. import __version__
from .check import CSV_COLUMNS, governing_ids
from .engine import SPIN_TILT_MIN
from ..paths import templates_dir
from ..plots import save
from ..report.context import given_value, quality_note, report_date, software_versions
from ..report.fragility_figures import fragility_figure
from .figures import comparison_figure, cylinder_history_figure, wobbling_figure
from ..report.svg import svg
from ..report.formatting import DIGITS, fmt
from .methods import CYLINDER_METHODS
from ..report.document import ReportParts
from ..display import utilisation_text
from ..report.render import environment, stylesheet

FIGURE_FILES = ("cylinder_vs_planar.png", "wobbling_period.png")
"""The figures written beside results.json (besides the report, which embeds its own)."""

TEMPLATE = "cylinder_report.html.j2"

SCALING_TEXT = {"resultant_pga": "each pair scaled to a peak resultant ground acceleration max √(ü_gx² + ü_gy²) "
                                 "of {target} (Table 5.4's scaling)",
                "factor": "every pair multiplied by the factor {value}"}


def render_cylinder_figures(result) -> dict[str, str]:
    """Inline SVG of the report's figures: ``wobbling``, ``comparison``, ``fragility`` (when the pairs were
    scanned) and ``history:<pair id>``."""
    cyl = result.project.system
    out = {"wobbling": svg(_wobbling(result), "wobbling"),
           "comparison": svg(comparison_figure(result.as_json()), "comparison")}
    if result.fragility and result.fragility.get("capacities"):
        out["fragility"] = svg(fragility_figure(result), "fragility")
    for k, (rid, (response, pair)) in enumerate(result.histories.items()):
        out[f"history:{rid}"] = svg(cylinder_history_figure(response, cyl.g, title=rid, pair=pair), f"history{k}")
    return out


def _wobbling(result):
    """Fig 5.2 for the checked cylinder, from the curve the check computed."""
    return wobbling_figure(result.figure_data["wobbling"], result.project.system.tan_alpha)


def planar_answer(data: dict) -> str:
    """"Is a planar analysis enough?" answered from the summary (the informative check)."""
    s = data["summary"]
    kp, k3, n = s["planar"]["n_overturned"], s["n_overturned"], s["n_records"]
    unsafe = s["n_planar_unconservative"]
    ratio = s.get("median_theta_ratio_3d_over_planar")
    if unsafe == 0 and kp >= k3:
        text = (f"Yes for the overturning verdict of this cylinder and excitation: the planar Housner analysis along "
                f"each component overturns {kp} of {n} pairs, the 3D analysis {k3}, and no pair overturns in 3D but "
                f"not in the planar analysis.")
        if ratio is not None and ratio > 1.0:
            text += (f" It does not predict the tilts: the median θ_max of the 3D cylinder is {fmt(ratio)} times the "
                     f"planar one where neither overturns.")
        return text
    return (f"No: {unsafe} {'pair overturns' if unsafe == 1 else 'pairs overturn'} in 3D but not in the planar analysis "
            f"({', '.join(s['planar_unconservative_records']) or '—'}); planar {kp} of {n}, 3D {k3} of {n}. "
            f"The wobbling cylinder needs the 3D analysis.")


def check_rows(checks: list[dict]) -> list[dict]:
    """The checks as the report's table prints them: a check that decides the verdict passes or FAILS; an
    informative one is "met"/"not met", and a question ("Does a planar analysis suffice?") is answered
    yes/no with its ratio of overturning pairs (3D over planar) rather than a utilisation; a utilisation is written
    as a multiple of the limit (:func:`rockdesign.display.utilisation_text`)."""
    rows = []
    for c in checks:
        if c["governs_verdict"]:
            value, result = utilisation_text(c["utilisation"]), "passed" if c["passed"] else "FAILED"
        elif c["name"].startswith("Does a planar analysis suffice"):
            value = f"{fmt(c['utilisation'])} (pairs overturning 3D/planar)"
            result = "yes" if c["passed"] else "no"
        else:
            value, result = utilisation_text(c["utilisation"]), "met" if c["passed"] else "not met"
        rows.append(dict(c, value_text=value, result_text=result))
    return rows


def build_cylinder_context(result, *, figures: dict, date: str | None = None) -> dict:
    """The template's data: results.json (``data``) plus texts, figures and the input echo."""
    project, data = result.project, result.as_json()
    scaling = data["summary"]["scaling"]
    text = SCALING_TEXT[scaling["method"]]
    scaling_text = text.format(target=fmt(scaling.get("target"), "m/s^2"), value=fmt(scaling.get("value")))
    governing = [dict(c, ratio=utilisation_text(c["utilisation"])) for c in data["checks"] if c["governs_verdict"]]
    rows = {r["id"]: r for r in data["records"]}
    return {
        "data": data, "summary": data["summary"], "checks": data["checks"], "verdict": data["verdict"],
        "title": "Calculation report — rocking and wobbling cylinder (3D)",
        "project": {"name": project.name, "file": Path(project.path).name if project.path else "",
                    "sha256": project.sha256,
                    "engineer": project.info.get("engineer"), "notes": project.info.get("notes"),
                    "source_text": project.source_text},
        "quantities": [dict(q.as_json(), name=name, symbol=q.symbol, description=q.description,
                            formula=q.formula, substituted=q.substituted, note=q.note)
                       for name, q in result.quantities.items()],
        "verdict_reason": data["verdict_reason"], "governing": governing[0] if governing else None,
        "polyakov_median": next((c["utilisation"] for c in data["checks"] if c["criterion"] == "polyakov_rule_2"),
                                None),
        "robustness": [c for c in data["checks"] if c["role"] == "robustness"],
        "planar_answer": planar_answer(data), "scaling_text": scaling_text,
        "histories": [{"id": rid, "row": rows[rid], "figure": figures.get(f"history:{rid}")}
                      for rid in governing_ids(data) if f"history:{rid}" in figures],
        "figures": figures, "date": date or report_date(), "tool_version": __version__,
        "software": software_versions(), "digits": DIGITS,
        "given": {key: given_value(project, "cylinder", key) for key in ("height", "diameter", "mass", "density")},
        "check_rows": check_rows(data["checks"]), "methods": CYLINDER_METHODS, "spin_tilt_min": SPIN_TILT_MIN,
        "quality_note": quality_note(project, data), "record_word": "record pair",
        "fragility_appendix": "Appendix C3",
    }


def render_cylinder_html(result, *, figures: dict | None = None, date: str | None = None) -> str:
    """The cylinder report as one self-contained HTML document (CSS and SVG figures inline)."""
    folder = templates_dir()
    env = environment(folder)
    ctx = build_cylinder_context(result, figures=figures if figures is not None else render_cylinder_figures(result),
                                 date=date)
    ctx["css"] = jinja2.utils.markupsafe.Markup(stylesheet(folder))
    return env.get_template(TEMPLATE).render(**ctx)


def cylinder_report_parts(result) -> ReportParts:
    """The cylinder report's parts: its HTML, and the comparison and wobbling-period figures (Fig 5.2 for this
    cylinder) as files beside it."""
    data = result.as_json()
    return ReportParts(html=lambda: render_cylinder_html(result),
                       files={"cylinder_vs_planar.png": lambda path: save(comparison_figure(data), path),
                              "wobbling_period.png": lambda path: save(_wobbling(result), path)})
