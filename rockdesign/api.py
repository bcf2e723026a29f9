"""The library API a user calls from a notebook; the CLI is a thin layer over it.

    >>> from rockdesign.api import load_project, design_quantities
    >>> proj = load_project("examples/podium_flat.toml")
    >>> design_quantities(proj.system)["theta_c"].value
"""
from __future__ import annotations

from .design.quantities import design_quantities
from .project import Project, load_project

__all__ = ["load_project", "design_quantities", "quantities_json", "quantities_table"]


def quantities_json(project: Project) -> dict:
    """The ``quantities --json`` object of CONTRACT §3 (SI values)."""
    q = design_quantities(project.system)
    return {"quantities": {name: x.as_json() for name, x in q.items()}, "warnings": list(project.warnings)}


def quantities_table(project: Project, console, units: str | None = None) -> None:
    """Print the design quantities of a project as a table."""
    from .display import quantities_table as _table
    _table(design_quantities(project.system), console, units, project.system.g,
           f"{project.name} — design quantities ({project.system.kind})", project.warnings)
