"""Where rockdesign finds its data: the bundled records and suites, templates, and ../shared.

The built-in record sets, suite manifests and the report/project templates live at the top of the
checkout (``ground_motions/`` and ``templates/``).  The wheel carries them as package data
(``rockdesign/data/ground_motions`` and ``rockdesign/data/templates``, mapped by the build backend),
so :func:`data_dir` looks in the installed package first and then in the checkout beside the
package: an installed wheel, an editable install and a plain checkout all go through that one lookup,
and every command works from any directory.  ``ROCKDESIGN_GROUND_MOTIONS`` /
``ROCKDESIGN_TEMPLATES`` point rockdesign at other folders.
"""
from __future__ import annotations

import os
from importlib import resources
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
REPO_ROOT = PACKAGE_DIR.parent
"""The folder above the package: the checkout's root in a source tree (site-packages when installed)."""


def data_dir(name: str) -> Path:
    """The folder of built-in data ``name`` (``ground_motions`` | ``templates``): the installed wheel's
    package data (``rockdesign/data/NAME``, found by :mod:`importlib.resources`), else the checkout's
    top-level folder ``NAME`` beside the package (editable install or plain checkout)."""
    folder = resources.files("rockdesign") / "data" / name
    if isinstance(folder, Path) and folder.is_dir():
        return folder
    checkout = REPO_ROOT / name
    if checkout.is_dir() and (PACKAGE_DIR / "__init__.py").is_file():
        return checkout
    raise RuntimeError(f"rockdesign's built-in data '{name}' was found neither in the package ({folder}) "
                       f"nor in the checkout ({checkout})")


def ground_motions_dir() -> Path:
    """Folder of the built-in record sets and suite manifests (``ground_motions/`` of the checkout, package data in the wheel)."""
    env = os.environ.get("ROCKDESIGN_GROUND_MOTIONS")
    return Path(env) if env else data_dir("ground_motions")


def templates_dir() -> Path:
    """Folder of the report and project templates (``templates/`` of the checkout, package data in the wheel)."""
    env = os.environ.get("ROCKDESIGN_TEMPLATES")
    return Path(env) if env else data_dir("templates")


def shared_dir() -> Path | None:
    """``../shared`` beside the checkout (staged accelerograms for tests and benchmarks), if present.

    ``ROCKDESIGN_SHARED`` overrides the search; set it to a folder without ``SPEC.md`` (e.g.
    ``/nonexistent``) to run the tests as in a clean clone.
    """
    env = os.environ.get("ROCKDESIGN_SHARED")
    if env:
        return Path(env) if (Path(env) / "SPEC.md").exists() else None
    for c in (REPO_ROOT.parent / "shared", REPO_ROOT.parent.parent / "shared"):
        if (c / "SPEC.md").exists():
            return c
    return None
