"""Robust design charts, run: coarse-to-fine leaves out only cells between agreeing neighbours and every
analysed cell equals the grid analysed cell by cell; a dask cluster of two worker processes gives the local
run's cells (the variants submitted together)."""
from __future__ import annotations

import pytest

from support import stocky_podium_toml
from rockdesign.design_space.refine import category
from rockdesign.design_space.run import design

# two built-in ground motions under the binomial rule (the smallest suite the rule accepts), 2 draws each
SMALL = stocky_podium_toml(analysis='acceptance = "binomial"\noverturn_probability_limit = 0.8\nensemble_size = 2')
KEEP = ("verdict", "robust", "draws", "n_unacceptable", "acmr", "median_theta_max_over_theta_c", "reason",
        "robustness", "analysed")


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    path = tmp_path_factory.mktemp("robust") / "small.toml"
    path.write_text(SMALL, encoding="utf-8")
    return path


def _cells(result):
    return [{k: c.get(k) for k in KEEP} for c in result.grid.cells]


def test_coarse_to_fine_cells_equal_every_cell(small):
    vary = ["podium.width=0.30m:0.70m:5"]
    coarse = design(small, vary)
    every = design(small, vary, every_cell=True)
    assert all(c["analysed"] for c in every.grid.cells)
    left = [c for c in coarse.grid.cells if not c["analysed"]]
    assert left                                 # 0.4 m and 0.6 m lie between robust PASS cells
    for c, e in zip(coarse.grid.cells, every.grid.cells):
        if c["analysed"]:
            assert {k: c.get(k) for k in KEEP} == {k: e.get(k) for k in KEEP}
        else:                                   # no verdict word; the category its neighbours agree on
            assert c["verdict"] is None and c["robust"] is None and c["between"] in ("robust PASS", "FAIL")
    analysed = {tuple(c["index"]): category(c) for c in coarse.grid.cells if c["analysed"]}
    for c in left:                              # left out only between two analysed cells that agree
        (i,) = c["index"]
        below = max(j for (j,) in analysed if j < i)
        above = min(j for (j,) in analysed if j > i)
        assert analysed[(below,)] == analysed[(above,)] == c["between"]
    assert coarse.as_json()["settings"]["cells_not_analysed"] == len(left)
    assert coarse.as_json()["settings"]["cells_inferred"] == len(left)
    # inference only where it is safe (SPEC §15): between corners far from their flip, never beside an analysed
    # cell of another category; an audited sample analysed (and, here, agreeing)
    from rockdesign.acceptance.flip import far_from_flip
    for c in left:
        (i,) = c["index"]
        for j in (i - 1, i + 1):
            other = coarse.grid.cells[j]
            assert category(other) == c["between"]
            assert not other["analysed"] or far_from_flip(other)
    audit = coarse.as_json()["settings"]["inference_audit"]
    audited = [c for c in coarse.grid.cells if c.get("audit")]
    assert audit["n"] == len(audited) >= 1 and audit["agreed"] == audit["n"]
    assert all(c["analysed"] and c["audit"]["agreed"] for c in audited)
    assert coarse.grid.analyses_run <= every.grid.analyses_run


@pytest.mark.slow
def test_a_dask_cluster_of_two_worker_processes_equals_the_local_run(small, tmp_path):
    """3 × 3 grid on a real LocalCluster (2 separate worker processes): the same cells as the local run."""
    import logging
    import warnings

    distributed = pytest.importorskip("distributed")
    from rockdesign.execution.executor import make_executor
    vary = ["podium.width=0.35m:0.65m:3", "podium.height=2.5m:3.5m:3"]
    local = design(small, vary)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           dashboard_address=None, silence_logs=logging.ERROR)
    try:
        with make_executor(cluster.scheduler_address) as ex:
            ex.start()
            remote = design(small, vary, executor=ex)
            workers = ex.client.scheduler_info()["workers"]
    finally:
        cluster.close()
    assert len(workers) == 2
    assert _cells(remote) == _cells(local)
    shared = remote.grid.shared_batches          # the variants ran together: shared calls on the cluster
    assert shared is not None and shared["variants"] >= 2 and shared["driver_calls"] < shared["batches"]
