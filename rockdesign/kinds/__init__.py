"""The registry of kinds of structure: the one place that knows there is more than one.

    BUILT_IN = ("rockdesign.cylinder.kind:Cylinder", "rockdesign.planar.kind:Planar")

A kind is a :class:`~rockdesign.kinds.base.StructureKind` living in a package of its own
(``rockdesign/planar/``, ``rockdesign/cylinder/``).  :func:`kind_of_document` chooses the parser of a TOML
document (the first kind that claims it), :func:`kind_of` the kind of a loaded project (or of a check result,
through its project): the kind a project carries (``project.kind``, set by :func:`parse_document` when
it was parsed) without asking the registry again.  The library (``rd.load_project``, ``rd.design_quantities``, ``rd.simulate``,
``rd.check``, ``rd.write_report``, ``rd.spectrum``, ``rd.design``) dispatches through these functions once per
call; ``tests/architecture`` fails on any other branch on the kind of a structure.

A new kind is one package and one entry: a line in :data:`BUILT_IN`, or — for a kind that lives outside
rockdesign — :func:`register` (or an entry point in the group ``rockdesign.kinds`` naming the kind's class).
The built-in kinds are imported on first use, so importing the registry loads no kind.
"""
from __future__ import annotations

import dataclasses
import importlib
from importlib.metadata import entry_points

from ..errors import RockdesignError
from .base import StructureKind
from .options import CliOption, registry_options

BUILT_IN: tuple[str, ...] = ("rockdesign.cylinder.kind:Cylinder", "rockdesign.planar.kind:Planar")
"""The built-in kinds (``module:class``), in the order a document is offered to them; the planar kind claims
any document (its parser names what is missing), so it comes last."""
ENTRY_POINT_GROUP = "rockdesign.kinds"
"""Installed packages may add kinds: an entry point of this group names a StructureKind subclass."""

_registered: list[StructureKind] = []
_kinds: tuple[StructureKind, ...] | None = None


def _instance(spec: str) -> StructureKind:
    module, _, name = spec.partition(":")
    return getattr(importlib.import_module(module), name)()


def registered() -> tuple[StructureKind, ...]:
    """Every kind, in the order a document is offered to them: kinds added by :func:`register` or by an
    entry point first (a new kind claims its own section), then the built-in ones."""
    global _kinds
    if _kinds is None:
        plugins = [entry.load()() for entry in sorted(entry_points(group=ENTRY_POINT_GROUP), key=lambda e: e.name)]
        _kinds = tuple(_registered) + tuple(plugins) + tuple(_instance(spec) for spec in BUILT_IN)
    return _kinds


def register(kind: StructureKind) -> StructureKind:
    """Add a kind of structure (an instance of a :class:`StructureKind` subclass); it is offered documents
    before the built-in kinds.  Returns the kind (registering the same name again replaces it)."""
    global _kinds
    if not isinstance(kind, StructureKind):
        raise TypeError(f"register() takes a StructureKind instance, not {type(kind).__name__}")
    _registered[:] = [k for k in _registered if k.name != kind.name] + [kind]
    _kinds = None
    return kind


def unregister(name: str) -> None:
    """Remove a kind added by :func:`register` (built-in kinds stay)."""
    global _kinds
    _registered[:] = [k for k in _registered if k.name != name]
    _kinds = None


def kind_of_document(raw: dict) -> StructureKind:
    """The kind whose parser reads the TOML document ``raw``."""
    return next(kind for kind in registered() if kind.claims(raw))


def kind_of(subject) -> StructureKind:
    """The kind of a :class:`~rockdesign.project_tables.Project`, or of a result that carries one
    (``result.project``)."""
    project = getattr(subject, "project", subject)
    carried = getattr(project, "kind", None)
    if isinstance(carried, StructureKind):      # the kind that parsed it (:func:`parse_document`): asked once
        return carried
    system_kind = getattr(getattr(project, "system", None), "kind", None)
    for kind in registered():
        if system_kind in kind.systems:
            return kind
    raise RockdesignError("not a project of a known kind of structure", key="project",
                          expected="a Project (rd.load_project or rd.parse_project) or a check result",
                          found=type(subject).__name__)


def parse_document(raw: dict, *, file: str = "<project>", text: str = ""):
    """The validated :class:`~rockdesign.project_tables.Project` of an already-parsed TOML document, by the
    parser of its kind."""
    kind = kind_of_document(raw)
    project = kind.parse(raw, file=file, text=text)
    if dataclasses.is_dataclass(project) and getattr(project, "kind", "") is None:
        project = dataclasses.replace(project, kind=kind)      # the project carries its kind (``kind_of``)
    return project


def spectrum_cli_options() -> tuple[CliOption, ...]:
    """The options of ``rockdesign spectrum`` the registered kinds declare
    (:attr:`~rockdesign.kinds.base.StructureKind.spectrum_cli`), merged by name (:func:`~rockdesign.kinds.options.merged_options`): the
    built-in kinds' first, the default kind's first, then those of the kinds added to the registry.  Imports the
    kinds (not pint or the engines: a kind's module imports those where it uses them); the same tuple while the
    registry does not change."""
    return registry_options(tuple(reversed(registered())))
