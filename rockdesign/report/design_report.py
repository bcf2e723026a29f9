"""The design report of ``rockdesign design``: inputs, charts, the table of variants and the recommended
design's full check summary → ``design.html`` and ``design.pdf`` (template ``templates/design.html.j2``);
the figures are also written as SVG files beside them."""
from __future__ import annotations

import datetime as _dt
import os
from pathlib import Path

from markupsafe import Markup

from .design_figures import cell_reason, design_figures
from .render import environment, html_to_pdf, stylesheet
from .svg import svg

TEMPLATE = "design.html.j2"

CAPTIONS = {
    "verdict": "Pass/fail region: the verdict of the check (ASCE 7-22 §16.4 count per ground motion and FEMA P695 "
               "collapse margin at the risk category's target) for every variant, with the governing reason; "
               "filled: robust PASS, hatched: PASS that fails in some perturbation draw, dotted outline: not "
               "analysed (its analysed neighbours all agree); black frame: the recommended design.",
    "acmr": "Adjusted collapse margin ratio ACMR of the variants whose margin was analysed (cells the count rule "
            "already fails at the design level need no margin scan and are left blank).",
    "shear": "Superstructure shear coefficient |f_s|/g, 84th percentile over the records that did not overturn "
             "(the two-degree-of-freedom podium of thesis Ch. 4: the superstructure on the rocking storey) — the force "
             "the building above is designed for.",
    "flip": "Distance of each analysed variant's verdict to its flip: the factor λ on the design intensity at which "
            "the verdict changes — the smaller of the factor at which more ground motions than allowed are "
            "unacceptable at or below λ × the design intensity (from each ground motion's first overturning factor) "
            "and ACMR / ACMR required. Above 1 the variant passes, at or below 1 it fails; the line λ = 1 is the "
            "edge between them, and the grid infers a cell only between neighbours beyond λ = 1.25 (or below 0.8). "
            "The values are as fine as the incremental scans (first overturning factors bisected to 1 %, bands "
            "narrower than the scan's ratio 1.2 can be missed).",
    "overturning": "Overturning of the record pairs at the design level (θ reaching θ_ot, thesis Sec 5.5.1): under "
                   "acceptance = \"binomial\" the one-sided 95 % bound of P(overturn) (Clopper–Pearson) with the "
                   "limit (its contour is the design level's pass/fail boundary), otherwise the pairs that overturn "
                   "with the ASCE 7-22 §16.4.1.1 allowance.",
    "rotation": "Median θ_max/θc of the suite at the design level (Eq 3.56: θc the rotation capacity).",
    "thesis_plane": "The variants in the plane of the thesis's two curved-base design parameters: the uplift "
                    "base-shear coefficient tan α (Eq 3.34) and the rotation capacity θc (Eq 3.56); one mark per "
                    "analysed variant, and variants that fall on one point (equal tan α and θc) drawn as a small "
                    "block of marks around it.",
}


COLUMNS = (
    ("ACMR (required)", "acmr", ""), ("P(collapse)", "p_collapse_design", ""), ("flip λ", "flip_margin", ""),
    ("P(overturn) bound (limit)", "p_overturn_bound", ""), ("incremental unacceptable", "n_incremental_unacceptable", ""),
    ("shear coeff. p84", "superstructure_shear_p84", ""), ("drift p84", "superstructure_drift_p84", "m"),
    ("median θ_max/θc", "median_theta_max_over_theta_c", ""), ("tan α", "uplift_shear_coefficient", ""),
    ("θc", "theta_c", "rad"), ("θ_ot", "theta_overturn", "rad"), ("material", "column_material", "kg"),
)
"""Columns of the variants table after the verdict and the count: (header, cell key, unit), each shown when
a cell has the number (a cylinder has no shear or θc, but a P(overturn) bound and θ_ot)."""


def write_design_report(result, data: dict, out_dir: Path, *, pdf: bool = True, recommended_check=None) -> dict:
    """Write ``design.html``, ``design.pdf`` (``pdf``) and the figures ``design_<name>.svg`` into ``out_dir``;
    ``recommended_check``: the full :class:`~rockdesign.planar.checks.check.CheckResult` of the recommended variant
    (its summary goes into the report).  Returns the paths written."""
    out_dir = Path(out_dir)
    figs = {k: f for k, f in design_figures(data).items() if f is not None}
    captions = dict(CAPTIONS)
    columns = [col for col in COLUMNS if any(c.get(col[1]) is not None for c in data["cells"])]
    rule = (data.get("settings") or {}).get("verdict_rule")
    if rule:
        captions["verdict"] = f"Pass/fail region: the verdict of the check ({rule}) for every variant, with the " \
                              "governing reason; filled: robust PASS, hatched: PASS that fails in some perturbation " \
                              "draw, dotted outline: not analysed (its analysed neighbours all agree); black frame: " \
                              "the recommended design."
    if any(c.get("theta_overturn") is not None for c in data["cells"]):
        columns = [("median θ_max/θ_ot", k, u) if k == "median_theta_max_over_theta_c" else (h, k, u)
                   for h, k, u in columns]
        captions["rotation"] = ("Median θ_max/θ_ot of the record pairs at the design level (θ_ot = overturn_tilt·α, "
                                "thesis Sec 5.5.1: the tilt at which the cylinder counts as overturned).")

    svgs = {k: svg(f, f"design-{k}", crop=False) for k, f in figs.items()}      # text stays text (searchable)
    written = {}
    for k, text in svgs.items():
        path = out_dir / f"design_{k}.svg"
        path.write_text(text, encoding="utf-8")
        written[k] = path
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    date = (_dt.datetime.fromtimestamp(int(epoch), _dt.timezone.utc) if epoch else _dt.datetime.now(_dt.timezone.utc))
    from ..display import verdict_words
    rows = [{**c, "short_reason": cell_reason(c), "words": verdict_words(c)} for c in data["cells"]]
    check = None
    if recommended_check is not None:
        r = recommended_check
        from ..display import check_order, utilisation_text
        shown = [c for c in r.checks if c.get("governs_verdict") or c.get("role") == "robustness"]
        check = {"verdict": r.verdict, "reason": r.verdict_reason, "robust": getattr(r, "verdict_robust", None),
                 "checks": [dict(c, ratio=utilisation_text(c.get("utilisation")))
                            for c in check_order(shown, getattr(r, "governing_check", None))],
                 "acceptance": r.acceptance or {},
                 "superstructure": (r.statistics.get("superstructure") or {})}
    env = environment()
    html = env.get_template(TEMPLATE).render(
        css=Markup(stylesheet()), data=data, rows=rows, figures=svgs, captions=captions, check=check, columns=columns,
        project=result.project, date=date.strftime("%Y-%m-%d"))
    path = out_dir / "design.html"
    path.write_text(html, encoding="utf-8")
    written["html"] = path
    if pdf:
        written["pdf"] = html_to_pdf(html, out_dir / "design.pdf")
    return written
