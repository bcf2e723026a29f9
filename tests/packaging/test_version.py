"""`rockdesign --version` prints the installed package's version, which is pyproject's and CHANGELOG's."""
from __future__ import annotations

import re
import subprocess
import sys
import tomllib
from importlib.metadata import version
from pathlib import Path

import rockdesign

ROOT = Path(__file__).resolve().parents[2]
PYPROJECT_VERSION = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]


def test_cli_version_is_the_installed_metadata_and_pyproject():
    script = Path(sys.executable).with_name("rockdesign")  # the console script pip installed
    command = [str(script)] if script.exists() else [sys.executable, "-c", "from rockdesign.cli import main; main()"]
    out = subprocess.run([*command, "--version"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == f"rockdesign {version('rockdesign')}"
    assert version("rockdesign") == PYPROJECT_VERSION


def test_package_version_matches_pyproject():
    assert rockdesign.__version__ == PYPROJECT_VERSION


def test_changelog_names_the_current_version():
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert re.search(rf"^## \[{re.escape(PYPROJECT_VERSION)}\] - \d{{4}}-\d{{2}}-\d{{2}}$", text, re.MULTILINE)
