"""Files of ``rockdesign validate -o DIR``: validation.json, the CDF figure (PNG, SVG) and the report
(HTML → PDF) rendered from ``templates/validate.html.j2`` with the check report's jinja2 environment."""
from __future__ import annotations

import datetime
import io
import json
import os
from pathlib import Path

import jinja2

from .. import __version__
from ..paths import templates_dir
from ..plots import plt
from ..report.render import environment, html_to_pdf
from .figures import validation_figure

TEMPLATE = "validate.html.j2"
LABELS = {"tests": "tests", "analyses": "model, theoretical c_r", "analyses_measured_cr": "model, measured c_r"}
ROWS = [("25", "25th percentile"), ("50", "50th percentile"), ("75", "75th percentile"),
        ("conditional_mean", "CM"), ("conditional_sd", "CSD")]


def _date() -> str:
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    when = datetime.datetime.fromtimestamp(int(epoch), datetime.timezone.utc) if epoch else \
        datetime.datetime.now(datetime.timezone.utc)
    return when.strftime("%Y-%m-%d")


def render_validation_html(result, files: dict, title: str, figure_svg: str) -> str:
    """The validation report as one self-contained HTML document."""
    folder = templates_dir()
    env = environment(folder)
    css = (folder / "report.css").read_text(encoding="utf-8") if (folder / "report.css").exists() else ""
    labels = {k: jinja2.utils.markupsafe.Markup(v.replace("c_r", "c<sub>r</sub>")) for k, v in LABELS.items()}
    return env.get_template(TEMPLATE).render(data=result.as_json(), files=files, title=title, labels=labels,
                                             rows=ROWS, figure=figure_svg, date=_date(), tool_version=__version__,
                                             css=jinja2.utils.markupsafe.Markup(css))


def write_validation(result, out_dir, files: dict, *, title: str = "validation", pdf: bool = True) -> dict:
    """Write validation.json, validation.png/.svg, report.html and (optionally) report.pdf."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = {}
    path = out / "validation.json"
    path.write_text(json.dumps(result.as_json(), indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    written["json"] = path
    fig = validation_figure(result, title)
    fig.savefig(out / "validation.png", dpi=150)
    buffer = io.StringIO()
    fig.savefig(buffer, format="svg")
    plt.close(fig)
    svg = buffer.getvalue()
    (out / "validation.svg").write_text(svg, encoding="utf-8")
    written["figure"] = out / "validation.png"
    html = render_validation_html(result, files, title, svg)
    (out / "report.html").write_text(html, encoding="utf-8")
    written["html"] = out / "report.html"
    if pdf:
        written["pdf"] = html_to_pdf(html, out / "report.pdf")
    return written
