"""Where rockdesign finds its data: the bundled records and suites, templates, and ../shared."""
from __future__ import annotations

import os
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
REPO_ROOT = PACKAGE_DIR.parent


def ground_motions_dir() -> Path:
    """Folder of the built-in record sets and suite manifests (``ground_motions/`` of the repo)."""
    env = os.environ.get("ROCKDESIGN_GROUND_MOTIONS")
    return Path(env) if env else REPO_ROOT / "ground_motions"


def templates_dir() -> Path:
    """Folder of the report and project templates (``templates/`` of the repo)."""
    env = os.environ.get("ROCKDESIGN_TEMPLATES")
    return Path(env) if env else REPO_ROOT / "templates"


def shared_dir() -> Path | None:
    """``../shared`` beside the checkout (validation data for tests and benchmarks), if present."""
    env = os.environ.get("ROCKDESIGN_SHARED")
    candidates = [Path(env)] if env else []
    candidates += [REPO_ROOT.parent / "shared", REPO_ROOT.parent.parent / "shared"]
    for c in candidates:
        if (c / "SPEC.md").exists():
            return c
    return None
