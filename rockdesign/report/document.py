"""A kind's calculation report as the shared layer writes it: :class:`ReportParts` (what the kind makes)
→ ``report.html`` and ``report.pdf`` (how: :mod:`rockdesign.report.render`, one route in this process).

    write_document(parts, folder, pdf=True, html=True) -> {"html": Path, "pdf": Path}
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable


@dataclass
class ReportParts:
    """What a kind's calculation report is made of; the kind never sees how it becomes a PDF.

    Attributes:
        html: ``html() -> str``: the whole report as one self-contained HTML document (CSS inline, figures as
            SVG images, :func:`rockdesign.report.render.svg_image`); called only when a report is written.
        files: name → ``writer(path)``: files written beside the report whatever is asked (the cylinder's
            ``cylinder_vs_planar.png``); their names are the kind's ``report_files``.
    """

    html: Callable[[], str]
    files: dict[str, Callable[[Path], object]] = field(default_factory=dict)


def write_document(parts: ReportParts, folder, *, pdf: bool = True, html: bool = True) -> dict[str, Path]:
    """Write the files of ``parts`` into ``folder``, and ``report.html`` and/or ``report.pdf``.

    Returns:
        {"html": path, "pdf": path} for the report files written.
    """
    from .render import html_to_pdf, write_html      # (jinja2, the report's filters: only when a report is written)
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for name, writer in parts.files.items():
        writer(folder / name)
    if not (pdf or html):
        return {}
    text = parts.html()
    written: dict[str, Path] = {}
    if html:
        written["html"] = write_html(text, folder)
    if pdf:
        written["pdf"] = html_to_pdf(text, folder / "report.pdf")
    return written
