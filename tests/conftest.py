"""Shared fixtures: validation cases from ../shared (skip cleanly when absent), standard systems."""
from __future__ import annotations

import json
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
def cases(shared):
    data = json.loads((shared / "validation" / "cases.json").read_text())
    return {c["id"]: c for c in data}


