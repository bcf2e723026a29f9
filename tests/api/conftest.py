"""Session fixtures of the library tests: the small project as a file and its check (computed once)."""
from __future__ import annotations

import pytest

from api_support import SMALL_PODIUM


@pytest.fixture(scope="session")
def small_project_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("project") / "small.toml"
    path.write_text(SMALL_PODIUM, encoding="utf-8")
    return path


@pytest.fixture(scope="session")
def small_check(small_project_file):
    """rd.check of the small project without margins (computed once per session)."""
    import rockdesign as rd
    return rd.check(rd.load_project(small_project_file), margins=False)
