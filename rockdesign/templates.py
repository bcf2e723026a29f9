"""``rockdesign init``: commented template project files (package data ``templates``)."""
from __future__ import annotations

from pathlib import Path

from .errors import ProjectError
from .outdir import refuse_wrong_type
from .paths import templates_dir

KINDS = ("podium", "column", "cylinder")


def template_text(kind: str) -> str:
    """The commented template for ``kind`` (podium | column | cylinder)."""
    if kind not in KINDS:
        raise ProjectError("unknown template", key="init KIND", expected="'podium', 'column' or 'cylinder'", found=f"'{kind}'")
    return (templates_dir() / f"project_{kind}.toml").read_text(encoding="utf-8")


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
