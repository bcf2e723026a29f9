"""Shared fixtures: validation cases (from the repository), ../shared (skip cleanly when absent), standard systems."""
from __future__ import annotations

import math

import pytest

from rockdesign.paths import shared_dir
from support import G, block_from_p, reference_podium, table34_column  # noqa: F401  (re-exported)



def pytest_configure(config):
    config.addinivalue_line("markers", "shared: needs ../shared (validation data, records)")


@pytest.fixture(scope="session")
def shared():
    d = shared_dir()
    if d is None:
        pytest.skip("../shared is not available")
    return d


@pytest.fixture(scope="session")
def cases():
    """The validation cases by id, from the repository's tests/validation/data/cases.json (no ../shared)."""
    from casedata import all_cases
    return all_cases()


