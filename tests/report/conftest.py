"""Session fixtures of the report tests: each example is checked once and its report written once.

- ``podium_out``: examples/podium_flat.toml (2DOF podium, flat columns), without the margin
  analysis (the slowest part), report written by ``rockdesign.write_report`` (results.json + PDF).
- ``curved_out``: examples/bridge_pier.toml (solitary column on curved extensions), with margins.
- ``default_result``: a small curved column whose project gives only ``design_pga`` (the default
  FEMA P695 far-field suite), without margins; HTML only.
"""
from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path

import pytest

from rockdesign.paths import REPO_ROOT

EXAMPLES = REPO_ROOT / "examples"

NUMBER = re.compile(r"−?\d+(?:\.\d+)?(?:·10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?")
"""A number as rockdesign.report.formatting writes it."""


@dataclass
class Written:
    """A checked project and the files written for it."""

    result: object
    out: Path
    data: dict            # results.json as read back from disk
    html: str
    pdf_text: str | None  # text of report.pdf (pypdf), whitespace as extracted
    pages: int | None

    @property
    def tokens(self) -> set[str]:
        """Every number in the PDF text."""
        return set(NUMBER.findall(self.pdf_text or ""))

    @property
    def flat_text(self) -> str:
        """PDF text with runs of whitespace collapsed to one space."""
        return re.sub(r"\s+", " ", self.pdf_text or "")


def pdf_text(path: Path) -> tuple[str, int]:
    pypdf = pytest.importorskip("pypdf")
    reader = pypdf.PdfReader(str(path))
    return "\n".join(page.extract_text() or "" for page in reader.pages), len(reader.pages)


def _write(project_path: Path, out: Path, *, margins: bool, pdf: bool) -> Written:
    import rockdesign as rd
    result = rd.check(rd.load_project(project_path), margins=margins)
    rd.write_report(result, out, pdf=pdf, html=True)
    data = json.loads((out / "results.json").read_text(encoding="utf-8"))
    html = (out / "report.html").read_text(encoding="utf-8")
    text, pages = pdf_text(out / "report.pdf") if pdf else (None, None)
    return Written(result, out, data, html, text, pages)


@pytest.fixture(scope="session")
def podium_out(tmp_path_factory) -> Written:
    return _write(EXAMPLES / "podium_flat.toml", tmp_path_factory.mktemp("podium"), margins=False, pdf=True)


@pytest.fixture(scope="session")
def curved_out(tmp_path_factory) -> Written:
    return _write(EXAMPLES / "bridge_pier.toml", tmp_path_factory.mktemp("curved"), margins=True, pdf=True)


DEFAULT_PROJECT = """\
# A small column on curved feet whose project gives only the design PGA: the check runs the
# default FEMA P695 far-field suite scaled to it (CONTRACT §1).
[project]
name = "Default-excitation test column"

[column]
height = "500 mm"
width = "50 mm"
extended_width = "150 mm"
radius = "125 mm"
mass = "0.329 kg"
mass_distribution = 0.543

[excitation]
design_pga = "0.2 g"
"""


@pytest.fixture(scope="session")
def default_out(tmp_path_factory) -> Written:
    folder = tmp_path_factory.mktemp("default")
    project = folder / "default_excitation.toml"
    project.write_text(DEFAULT_PROJECT, encoding="utf-8")
    return _write(project, folder / "out", margins=False, pdf=False)
