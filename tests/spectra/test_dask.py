"""Distributed runs on dask.distributed give the local arrays bit for bit.

The session's LocalCluster of two worker processes (one thread each, tests/conftest.py) is reached
through its scheduler address — the path a real cluster takes (``--dask ADDRESS`` is exercised
through the CLI in test_cli_spectrum.py and tests/checks/test_check.py, ``local:N`` parsing below); runs must reproduce the in-process arrays exactly, also when an interrupted
distributed run is resumed.
"""
from __future__ import annotations

import numpy as np
import pytest

from support import reference_podium, table34_column
from rockdesign.planar.spectra import (ChunkStore, DaskExecutor, SpectrumRequest, compute_spectrum, make_executor,
                                parse_axis)
from rockdesign.planar.spectra.kernel import warm_up

distributed = pytest.importorskip("distributed")

REQ = SpectrumRequest("ricker-sym", parse_axis("omega_p/p:0.8:9:31", "x"), parse_axis("ap/up:0:9:19", "y"))


pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def cluster(dask_cluster):
    return dask_cluster   # the session's cluster (tests/conftest.py)


def test_scheduler_address_run_is_identical_to_local(cluster, tmp_path):
    system = table34_column("B2ec")
    local = compute_spectrum(system, REQ, chunk_rows=2)
    with DaskExecutor(cluster.scheduler_address, warm_up=warm_up) as ex:
        dist = compute_spectrum(system, REQ, executor=ex, chunk_rows=2, store_dir=tmp_path / "c", keep_chunks=True)
        info = ex.describe()
    assert info["workers"] == 2
    assert dist.execution["executor"] == "dask" and dist.execution["chunks_computed"] == 10
    np.testing.assert_array_equal(dist.out, local.out)
    # the chunk files written from the distributed run resume a local run
    again = compute_spectrum(system, REQ, store_dir=tmp_path / "c")
    assert again.execution["chunks_resumed"] == 10 and again.execution["chunks_computed"] == 0
    np.testing.assert_array_equal(again.out, local.out)


def test_2dof_podium_is_identical_to_local(cluster):
    # 4 states and superstructure damping: the podium-2dof model distributed like a block
    system = reference_podium(3.0)
    req = SpectrumRequest("ricker-anti", parse_axis("omega_p/p:1:6:4", "x"), parse_axis("ap/up:1.5:4.5:3", "y"),
                          structure="podium-2dof")
    local = compute_spectrum(system, req, chunk_rows=1)
    with DaskExecutor(cluster.scheduler_address, warm_up=warm_up) as ex:
        dist = compute_spectrum(system, req, executor=ex, chunk_rows=1)
    assert dist.overturned.any() and (dist.theta_max > 0).any()
    np.testing.assert_array_equal(dist.out, local.out)


def test_executor_specs():
    ex = make_executor("local:3")
    assert isinstance(ex, DaskExecutor) and ex.slots == 3 and ex.numba_threads >= 1
    assert make_executor(None).name == "local"
    for bad in ("local:0", "local:x", "nonsense"):
        with pytest.raises(Exception) as err:
            make_executor(bad)
        assert err.value.key == "executor"             # the library's parameter (the CLI says --dask)


def test_interrupted_distributed_run_resumes(cluster, tmp_path):
    system = table34_column("B1")
    local = compute_spectrum(system, REQ, chunk_rows=4)
    store = tmp_path / "c"
    with DaskExecutor(cluster.scheduler_address, warm_up=warm_up) as ex:
        compute_spectrum(system, REQ, executor=ex, chunk_rows=4, store_dir=store, keep_chunks=True)
    files = sorted(store.glob("chunk-*.npz"))
    for f in files[:3]:
        f.unlink()   # as if the run had been stopped before these chunks arrived
    with DaskExecutor(cluster.scheduler_address, warm_up=warm_up) as ex:
        resumed = compute_spectrum(system, REQ, executor=ex, store_dir=store)
    assert resumed.execution["chunks_computed"] == 3
    assert resumed.execution["chunks_resumed"] == len(files) - 3
    np.testing.assert_array_equal(resumed.out, local.out)
    assert ChunkStore(store, "").completed() == []


def test_suite_batches_on_the_cluster(cluster):
    # the same executor serves record suites: run_batch chunked over dask, identical arrays
    from rockdesign.planar.dynamics.batch import batch_options, run_batch
    from rockdesign.planar.dynamics.model import ModelChoice, system_parameters
    from rockdesign.motions.library import load_record
    from rockdesign.planar.dynamics.parallel import run_motions
    system = table34_column("B1")
    sp = system_parameters(system, ModelChoice("block", "exact"))
    rec = load_record("p695-ff/11a")
    scales = list(np.linspace(0.3, 4.0, 8))
    motions = [rec] * len(scales)
    t_ends = [rec.duration + 10.0] * len(scales)
    s_ref, d_ref = run_batch(sp, motions, scales, t_ends, batch_options())
    with DaskExecutor(cluster.scheduler_address, warm_up=warm_up) as ex:
        s, d = run_motions(sp, motions, scales, t_ends, batch_options(), executor=ex, chunk_jobs=3)
    np.testing.assert_array_equal(s, s_ref)
    np.testing.assert_array_equal(d, d_ref)
