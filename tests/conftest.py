"""Shared fixtures: validation cases (from the repository), ../shared (skip cleanly when absent), standard systems."""
from __future__ import annotations

import math
import os

import pytest
from hypothesis import settings

from rockdesign.paths import shared_dir
from support import G, block_from_p, reference_podium, table34_column  # noqa: F401  (re-exported)

# Property tests draw the same examples on every run (deterministic CI; a failure reproduces);
# HYPOTHESIS_PROFILE=explore draws new random examples each run (to search for failures by hand).
settings.register_profile("deterministic", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "deterministic"))


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


@pytest.fixture(scope="session")
def dask_cluster():
    """One dask.distributed LocalCluster (2 worker processes, 1 thread each) for the whole session;
    tests reach it through ``dask_cluster.scheduler_address`` (as ``--dask ADDRESS``)."""
    distributed = pytest.importorskip("distributed")
    import logging
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           dashboard_address=None, silence_logs=logging.ERROR)
    yield cluster
    cluster.close()
