"""The registry of kinds of structure: the one place that knows there is more than one.

    KINDS = (Cylinder(), Planar())        # asked in this order; Planar claims every other document

:func:`kind_of_document` chooses the parser of a TOML document, :func:`kind_of` the kind of a loaded
project (or of a check result, through its project).  The library (``rd.load_project``,
``rd.design_quantities``, ``rd.simulate``, ``rd.check``, ``rd.write_report``) dispatches through
these two functions once per call; ``tests/architecture`` fails on any other branch on the kind of a
structure.  A new kind of structure is one :class:`~rockdesign.kinds.base.StructureKind` subclass
(its module here, built on its own modules below) and one entry in :data:`KINDS`
(docs/architecture.md, "Adding a kind of structure").
"""
from __future__ import annotations

from ..errors import RockdesignError
from .base import StructureKind
from .cylinder import Cylinder
from .planar import Planar

KINDS: tuple[StructureKind, ...] = (Cylinder(), Planar())
"""Every kind of structure, in the order a document is offered to them (the first that claims it
parses it; :class:`Planar` claims any document, so it comes last)."""


def kind_of_document(raw: dict) -> StructureKind:
    """The kind whose parser reads the TOML document ``raw``."""
    return next(kind for kind in KINDS if kind.claims(raw))


def kind_of(subject) -> StructureKind:
    """The kind of a :class:`~rockdesign.project_tables.Project`, or of a result that carries one
    (``result.project``)."""
    project = getattr(subject, "project", subject)
    system_kind = getattr(getattr(project, "system", None), "kind", None)
    for kind in KINDS:
        if system_kind in kind.systems:
            return kind
    raise RockdesignError("not a project of a known kind of structure", key="project",
                          expected="a Project (rd.load_project or rd.parse_project) or a check result",
                          found=type(subject).__name__)


def parse_document(raw: dict, *, file: str = "<project>", text: str = ""):
    """The validated :class:`~rockdesign.project_tables.Project` of an already-parsed TOML document, by the
    parser of its kind."""
    return kind_of_document(raw).parse(raw, file=file, text=text)
