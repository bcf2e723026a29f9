"""Where rockdesign finds its data: the bundled records and suites, templates, and ../shared.

The built-in record sets, suite manifests and the report/project templates are package data
(``rockdesign/data/ground_motions`` and ``rockdesign/data/templates``): they ship inside the wheel
and the sdist and are found with :mod:`importlib.resources`, so every command works from any
directory with a normal (non-editable) install, an editable install or a plain checkout alike.
They live inside the package rather than at the top of the repository because one lookup then
serves every kind of installation; ``ROCKDESIGN_GROUND_MOTIONS`` / ``ROCKDESIGN_TEMPLATES``
point rockdesign at other folders.
"""
from __future__ import annotations

import os
from importlib import resources
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
REPO_ROOT = PACKAGE_DIR.parent
"""The folder above the package: the checkout's root in a source tree (site-packages when installed)."""


def child_environment() -> dict[str, str]:
    """The environment for a helper process (``python -c``) that must import this very rockdesign
    package, not another one on its path: this process's environment with the folder above the
    package first on ``PYTHONPATH`` (the compile helper, the PDF worker)."""
    here = str(PACKAGE_DIR.parent)
    return {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (here, os.environ.get("PYTHONPATH")) if p)}


def data_dir(name: str) -> Path:
    """A folder of package data (``ground_motions`` | ``templates``) found by :mod:`importlib.resources`."""
    folder = resources.files("rockdesign") / "data" / name
    if not isinstance(folder, Path):   # a zipped install: not supported (setuptools installs unzipped)
        raise RuntimeError(f"rockdesign's package data '{name}' is not on the file system ({folder})")
    return folder


def ground_motions_dir() -> Path:
    """Folder of the built-in record sets and suite manifests (package data ``rockdesign/data/ground_motions``)."""
    env = os.environ.get("ROCKDESIGN_GROUND_MOTIONS")
    return Path(env) if env else data_dir("ground_motions")


def templates_dir() -> Path:
    """Folder of the report and project templates (package data ``rockdesign/data/templates``)."""
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
