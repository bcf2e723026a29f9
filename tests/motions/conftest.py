"""Shared fixtures of the ground-motion tests.

Tests that read ../shared (staged real records, reference tables) skip cleanly when
``rockdesign.paths.shared_dir()`` finds no shared folder.
"""
from __future__ import annotations

import pytest

from rockdesign.paths import shared_dir

G_REFERENCE = 9.80665
"""g [m/s²] used by ../shared/ground_motions/MANIFEST.md and fema_p695_pga_sdmax.csv."""


@pytest.fixture(scope="session")
def shared():
    folder = shared_dir()
    if folder is None:
        pytest.skip("../shared (validation data) not available")
    return folder


@pytest.fixture(scope="session")
def shared_records(shared):
    folder = shared / "ground_motions" / "records"
    if not folder.is_dir():
        pytest.skip("../shared/ground_motions/records not available")
    return folder
