"""The named method sections of a calculation report's appendix, and the citation of them.

A signed calculation cites the thesis, published sources and the tool's own method sections printed
in the report itself — never files of the software's repository.  Texts that the library writes for
results.json (model-selection reasons, check sources, quantity references) name the developer
documentation (``docs/model.md §7``); :func:`cite` rewrites such a reference to the appendix section
that states the same method (``Appendix M4``), so the report is self-contained while results.json
stays as it is.  Each kind lists its own sections (:class:`Method`) in its report package.

    cite(text) -> text                 every repository reference replaced by its appendix section
"""
from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Method:
    """One appendix section: its label (``M4``), title and paragraphs (plain text with thesis symbols)."""

    label: str
    title: str
    paragraphs: tuple[str, ...]


_SECTION = {"2": "M1", "3": "M2", "4": "M1", "5": "M1", "6": "M3", "7": "M4", "8": "M4", "9": "M2"}
"""Section of the developer model description → appendix section of the report."""


_REFERENCES = (
    (re.compile(r"\(ours, docs/model\.md §6\)"), "(rockdesign's, Appendix M3)"),
    (re.compile(r"rockdesign's docs/model\.md §(\d)"), lambda m: f"Appendix {_SECTION.get(m.group(1), 'M1')}"),
    (re.compile(r"docs/model\.md\s*§(\d)(?:,\s*§(\d))?"),
     lambda m: f"Appendix {_SECTION.get(m.group(1), 'M1')}"),
    (re.compile(r"docs/model\.md(?:, \"[^\"]*\")?"), "Appendix M1"),
    (re.compile(r"docs/engine\.md(?:, \"[^\"]*\")?(?: \(engine statuses\))?"), "Appendix M5"),
    (re.compile(r"docs/tolerances\.md"), "Appendix M5"),
    (re.compile(r"docs/early_termination\.md"), "Appendix M5"),
    (re.compile(r"docs/fragility\.md(?: \(perturbation ensembles\))?"), "Appendix M6"),
    (re.compile(r"docs/project-file\.md"), "Appendix M7"),
    (re.compile(r"docs/cylinder\.md"), "Appendix C1–C2"),
    (re.compile(r"tests/golden"), "the pinned reference outputs of the test suite"),
)


def cite(text: str | None) -> str | None:
    """``text`` with every reference to a file of the repository replaced by the appendix section that
    states the same method; other text unchanged (None → None)."""
    if not text:
        return text
    out = str(text)
    for pattern, replacement in _REFERENCES:
        out = pattern.sub(replacement, out)
    return out
