"""The calculation report of ``rockdesign check`` for a ``[cylinder]`` project (thesis Ch. 5):
jinja2 template ``cylinder_report.html.j2`` (with the planar report's ``report.css``) → HTML →
WeasyPrint PDF.

    write_cylinder_report(result, out_dir, pdf=True, html=True) -> {"html": Path, "pdf": Path}
    render_cylinder_html(result) -> str

As in the planar report every number is printed by the ``fmt`` filter from ``result.as_json()``
(results.json), so the report and results.json agree.  Figures: the wobbling period T_w·p against
θ/α next to Housner's planar period (Fig 5.2), 3D against planar θ_max/α per pair, and θ(t) with the
plan-view orbit of the governing pairs (Figs 5.9–5.15).
"""
from __future__ import annotations

from pathlib import Path

import jinja2

from ..paths import templates_dir
from .formatting import DIGITS

TEMPLATE = "cylinder_report.html.j2"

SCALING_TEXT = {"resultant_pga": "each pair scaled to a peak resultant ground acceleration max √(ü_gx² + ü_gy²) "
                                 "of {target} (Table 5.4's scaling)",
                "factor": "every pair multiplied by the factor {value}"}


def render_cylinder_figures(result) -> dict[str, str]:
    """Inline SVG of the report's figures: ``wobbling``, ``comparison`` and ``history:<pair id>``."""
    from ..checks.cylinder_check import comparison_figure
    from ..cylinder.figures import cylinder_history_figure, wobbling_figure
    from .figures import svg
    cyl = result.project.system
    out = {"wobbling": svg(wobbling_figure(cyl), "wobbling"),
           "comparison": svg(comparison_figure(result.as_json()), "comparison")}
    for k, (rid, (response, pair)) in enumerate(result.histories.items()):
        out[f"history:{rid}"] = svg(cylinder_history_figure(response, cyl.g, title=rid, pair=pair), f"history{k}")
    return out


def verdict_reason(data: dict) -> str:
    """One sentence: why the verdict is what it is (the governing check against its limit)."""
    s, lim = data["summary"], data["settings"]["overturn_probability_limit"]
    from .formatting import fmt
    hi = s["p_overturn_ci90"][1]
    relation = "is within" if data["verdict"] == "PASS" else "exceeds"
    return (f"{s['n_overturned']} of {s['n_records']} record pairs overturn the cylinder in 3D (θ reaching θ_ot); "
            f"the one-sided 95 % upper bound of P(overturn), {fmt(hi)}, {relation} the limit {fmt(lim)}.")


def planar_answer(data: dict) -> str:
    """"Is a planar analysis enough?" answered from the summary (the informative check)."""
    from .formatting import fmt
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
    return (f"No: {unsafe} pair(s) overturn in 3D but not in the planar analysis "
            f"({', '.join(s['planar_unconservative_records']) or '—'}); planar {kp} of {n}, 3D {k3} of {n}. "
            f"The wobbling cylinder needs the 3D analysis.")


def check_rows(checks: list[dict]) -> list[dict]:
    """The checks as the report's table prints them: a check that decides the verdict passes or FAILS; an
    informative one is "met"/"not met", and a question ("Does a planar analysis suffice?") is answered
    yes/no with its ratio of overturning pairs (3D over planar) rather than a utilisation."""
    from .formatting import fmt
    rows = []
    for c in checks:
        if c["governs_verdict"]:
            value, result = fmt(c["utilisation"]), "passed" if c["passed"] else "FAILED"
        elif c["name"].startswith("Does a planar analysis suffice"):
            value = f"{fmt(c['utilisation'])} (pairs overturning 3D/planar)"
            result = "yes" if c["passed"] else "no"
        else:
            value, result = fmt(c["utilisation"]), "met" if c["passed"] else "not met"
        rows.append(dict(c, value_text=value, result_text=result))
    return rows


def build_cylinder_context(result, *, figures: dict, date: str | None = None) -> dict:
    """The template's data: results.json (``data``) plus texts, figures and the input echo."""
    from .. import __version__
    from ..checks.cylinder_check import governing_ids
    from ..cylinder.engine import SPIN_TILT_MIN
    from ..cylinder.quantities import cylinder_quantities
    from .methods import CYLINDER_METHODS
    from .context import given_value, report_date, software_versions
    from .formatting import fmt
    project, data = result.project, result.as_json()
    scaling = data["summary"]["scaling"]
    text = SCALING_TEXT[scaling["method"]]
    scaling_text = text.format(target=fmt(scaling.get("target"), "m/s^2"), value=fmt(scaling.get("value")))
    governing = [c for c in data["checks"] if c["governs_verdict"]]
    quantities = cylinder_quantities(project.system)
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
                       for name, q in quantities.items()],
        "verdict_reason": verdict_reason(data), "governing": governing[0] if governing else None,
        "planar_answer": planar_answer(data), "scaling_text": scaling_text,
        "histories": [{"id": rid, "row": rows[rid], "figure": figures.get(f"history:{rid}")}
                      for rid in governing_ids(data) if f"history:{rid}" in figures],
        "figures": figures, "date": date or report_date(), "tool_version": __version__,
        "software": software_versions(), "digits": DIGITS,
        "given": {key: given_value(project, "cylinder", key) for key in ("height", "diameter", "mass", "density")},
        "check_rows": check_rows(data["checks"]), "methods": CYLINDER_METHODS, "spin_tilt_min": SPIN_TILT_MIN,
    }


def render_cylinder_html(result, *, figures: dict | None = None, date: str | None = None) -> str:
    """The cylinder report as one self-contained HTML document (CSS and SVG figures inline)."""
    from .render import environment, stylesheet
    folder = templates_dir()
    env = environment(folder)
    ctx = build_cylinder_context(result, figures=figures if figures is not None else render_cylinder_figures(result),
                                 date=date)
    ctx["css"] = jinja2.utils.markupsafe.Markup(stylesheet(folder))
    return env.get_template(TEMPLATE).render(**ctx)


def write_cylinder_report(result, out_dir, *, pdf: bool = True, html: bool = True) -> dict[str, Path]:
    """Write ``report.html`` and/or ``report.pdf`` of a cylinder check into ``out_dir``."""
    from .render import write_report
    return write_report(result, out_dir, pdf=pdf, html=html, render=render_cylinder_html)


def cylinder_output_folder(target, *, key: str = "out_dir"):
    """The :class:`~rockdesign.outdir.OutputFolder` of a cylinder check (it also owns the two PNG figures)."""
    from ..checks.cylinder_check import FIGURE_FILES
    from ..outdir import RUN_FILES, OutputFolder
    return OutputFolder(target, key=key, owned=RUN_FILES | set(FIGURE_FILES))


def write_cylinder_folder(result, out_dir, *, pdf: bool = True, html: bool = True) -> Path:
    """results.json, results.csv, the figures and report.pdf/html of a cylinder check, written all or
    nothing into ``out_dir`` (a path or a locked OutputFolder of :func:`cylinder_output_folder`).

    Returns:
        The output folder.
    """
    from ..checks.cylinder_check import write_cylinder_results
    from ..cylinder.figures import wobbling_figure
    from ..outdir import OutputFolder
    from ..plots import save
    folder = out_dir if isinstance(out_dir, OutputFolder) else cylinder_output_folder(out_dir)
    with folder.staging() as tmp:
        write_cylinder_results(result.as_json(), tmp)
        save(wobbling_figure(result.project.system), tmp / "wobbling_period.png")   # Fig 5.2 for this cylinder
        write_cylinder_report(result, tmp, pdf=pdf, html=html)
    return folder.target
