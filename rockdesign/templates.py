"""``rockdesign init``: commented template project files (package data ``templates``).

Each kind of structure declares the templates it offers (:attr:`~rockdesign.kinds.base.StructureKind.templates`)
and reads their text (:meth:`~rockdesign.kinds.base.StructureKind.template_text`); this module asks the registry.
"""
from __future__ import annotations

from pathlib import Path

from .errors import ProjectError
from .outdir import refuse_wrong_type


def template_names() -> tuple[str, ...]:
    """The templates ``rockdesign init`` offers, the built-in kinds' first (default kind first), then the kinds
    added to the registry."""
    from .kinds import registered
    return tuple(name for kind in reversed(registered()) for name in kind.templates)


def template_text(kind: str) -> str:
    """The commented template named ``kind`` (a name of :func:`template_names`)."""
    from .kinds import registered
    owner = next((k for k in registered() if kind in k.templates), None)
    if owner is None:
        quoted = [f"'{name}'" for name in template_names()]
        raise ProjectError("unknown template", key="init KIND",
                           expected=" or ".join([", ".join(quoted[:-1]), quoted[-1]] if len(quoted) > 1 else quoted),
                           found=f"'{kind}'")
    return owner.template_text(kind)


def write_template(kind: str, path: Path | None = None, *, force: bool = False) -> Path:
    """Write the template for ``kind`` to ``path`` (default ``KIND.toml``); never overwrites unless forced."""
    text = template_text(kind)
    out = Path(path) if path is not None else Path(f"{kind}.toml")
    if out.is_dir():
        out = out / f"{kind}.toml"
    if out.exists() and not force:
        raise ProjectError("file exists", file=str(out), expected="a new file name (or --force to overwrite)",
                           found="an existing file")
    refuse_wrong_type(out, "path", folder=False)
    for parent in out.parents:      # a file or a dangling link where a folder of the path goes
        refuse_wrong_type(parent, "path", folder=True)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text, encoding="utf-8")
    return out
