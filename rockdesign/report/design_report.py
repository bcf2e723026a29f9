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
    "rotation": "Median {symbol} of the suite at the design level: {meaning}.",
}


COLUMNS = (
    ("ACMR (required)", "acmr", ""), ("P(collapse)", "p_collapse_design", ""), ("flip λ", "flip_margin", ""),
    ("P(overturn) bound (limit)", "p_overturn_bound", ""),
    ("shear coeff. p84", "superstructure_shear_p84", ""), ("drift p84", "superstructure_drift_p84", "m"),
    ("median {symbol}", "median_theta_max_over_theta_c", ""),
)
"""The shared columns of the variants table after the verdict and the count: (header, cell key, unit); the kind's own
columns with a heading (design.json ``columns``) follow, and each is shown when a cell has the number."""


def table_columns(data: dict) -> list[tuple[str, str, str]]:
    """The variants table's columns for a design.json: the shared :data:`COLUMNS` (the median response ratio named
    by the kind, design.json ``response``) and the kind's own columns that have a heading."""
    symbol = (data.get("response") or {}).get("symbol") or "response ratio"
    own = [(c["heading"], c["key"], "" if c["unit"] in ("", "-") else c["unit"])
           for c in data.get("columns") or [] if c.get("heading")]
    columns = [(h.format(symbol=symbol), k, u) for h, k, u in COLUMNS] + own
    return [col for col in columns if any(c.get(col[1]) is not None for c in data["cells"])]


def write_design_report(result, data: dict, out_dir: Path, *, pdf: bool = True, recommended_check=None) -> dict:
    """Write ``design.html``, ``design.pdf`` (``pdf``) and the figures ``design_<name>.svg`` into ``out_dir``;
    ``recommended_check``: the full check of the recommended variant (:class:`~rockdesign.kinds.base.CheckResult`;
    the shared sections of its results.json go into the report).  Returns the paths written."""
    out_dir = Path(out_dir)
    figs = {k: f for k, f in design_figures(data).items() if f is not None}
    response = data.get("response") or {"symbol": "response ratio", "meaning": "the peak response over the capacity"}
    captions = dict(CAPTIONS, rotation=CAPTIONS["rotation"].format(**response))
    if data.get("plane"):
        captions["thesis_plane"] = data["plane"]["caption"]
    columns = table_columns(data)
    rule = (data.get("settings") or {}).get("verdict_rule")
    if rule:
        captions["verdict"] = f"Pass/fail region: the verdict of the check ({rule}) for every variant, with the " \
                              "governing reason; filled: robust PASS, hatched: PASS that fails in some perturbation " \
                              "draw, dotted outline: not analysed (its analysed neighbours all agree); black frame: " \
                              "the recommended design."

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
        doc = recommended_check.as_json()          # its results.json: the shared sections of every kind's check
        from ..display import check_order, utilisation_text
        shown = [c for c in doc.get("checks") or [] if c.get("governs_verdict") or c.get("role") == "robustness"]
        check = {"verdict": doc["verdict"], "reason": doc["verdict_reason"], "robust": doc.get("verdict_robust"),
                 "checks": [dict(c, ratio=utilisation_text(c.get("utilisation")))
                            for c in check_order(shown, getattr(recommended_check, "governing_check", None))],
                 "acceptance": doc.get("acceptance") or {},
                 "superstructure": ((doc.get("summary") or {}).get("superstructure") or {})}
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
