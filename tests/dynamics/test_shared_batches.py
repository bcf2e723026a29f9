"""Shared batches of the design grid (rockdesign.execution.batch_pool served by the planar kind's
rockdesign.planar.dynamics.shared_batches): the batches of member threads run together, and every thread gets
exactly what its batch gives alone.  A member is passed down as an executor; nothing is kept per thread."""
from __future__ import annotations

import threading
import time

import numpy as np
import pytest

from support import G, reference_podium, table34_column
from rockdesign.planar.dynamics.batch import batch_options, run_batch
from rockdesign.execution.batch_pool import BatchPool, PoolCancelled, PoolMember
from rockdesign.execution.executor import is_executor
from rockdesign.planar.dynamics.shared_batches import BatchRequest, SharedBatches, batch_rows
from rockdesign.planar.dynamics.model import ModelChoice, system_parameters
from rockdesign.motions.motion import pulse_motion


def _systems():
    return [system_parameters(table34_column("B1"), ModelChoice("block", "exact")),
            system_parameters(table34_column("B4ec"), ModelChoice("block", "exact")),
            system_parameters(reference_podium(), ModelChoice("podium-2dof", "exact"))]


def _members(pool, work, threads=None):
    """Run ``work[k](member)`` as members in ``threads`` threads (default one each; the next starts when one
    ends) while this thread serves the pool; returns their results (re-raises the first error)."""
    results, errors = [None] * len(work), []

    def body(k):
        try:
            with pool.member() as member:
                assert isinstance(member, PoolMember) and member.pool is pool and is_executor(member)
                results[k] = work[k](member)
        except BaseException as exc:      # noqa: BLE001 — re-raised in the test's thread
            errors.append(exc)
    queue = list(range(len(work)))
    lock = threading.Lock()

    def worker():
        while True:
            with lock:
                if not queue:
                    return
                k = queue.pop(0)
            body(k)
    threads = [threading.Thread(target=worker) for _ in range(threads or len(work))]
    for t in threads:
        t.start()
    try:
        pool.serve()
    finally:
        pool.cancel()           # (a no-op once every member has ended)
    for t in threads:
        t.join(timeout=120)
        assert not t.is_alive(), "a member thread is stuck"
    if errors:
        raise errors[0]
    return results


def _batch(member, sp, motions, opts):
    """One batch through the executor protocol (as a planar check hands it out): (summaries, diagnostics)."""
    n = len(motions)
    (_, rows), = member.map(batch_rows, (sp, opts), {0: (motions, [1.0] * n, [5.0] * n, [5.0] * n)})
    return rows


def test_members_batches_run_together_and_each_gets_its_own_result():
    sps = _systems()
    motions = [pulse_motion("ricker-anti", a * G, 0.95) for a in (0.25, 0.3, 0.38, 0.5)]
    loose, tight = batch_options(1e-6, 1e-8), batch_options(1e-8, 1e-10)
    # three variants with different numbers of batches, options and Python work between them
    plans = [[(0, [0, 1], loose), (0, [2, 3], loose), (0, [1], tight)],
             [(1, [3, 2, 1, 0], loose)],
             [(2, [0], loose), (2, [1, 2], tight)]]
    shared, shared_queued = SharedBatches(), SharedBatches()
    pool = BatchPool(len(plans), shared)

    def variant(plan):
        def work(member):
            out = []
            for k, (system, picks, opts) in enumerate(plan):
                time.sleep(0.01 * k)
                out.append(_batch(member, sps[system], [motions[i] for i in picks], opts))
            return out
        return work

    got = _members(pool, [variant(p) for p in plans])
    queued = BatchPool(len(plans), shared_queued)   # two threads for three members: the third waits for a thread
    got_queued = _members(queued, [variant(p) for p in plans], threads=2)
    for results_of in (got, got_queued):
        for plan, results in zip(plans, results_of):
            for (system, picks, opts), (s, d) in zip(plan, results):
                s_alone, d_alone = run_batch(sps[system], [motions[i] for i in picks], [1.0] * len(picks),
                                             [5.0] * len(picks), opts, threads=False)
                np.testing.assert_array_equal(s, s_alone)
                np.testing.assert_array_equal(d, d_alone)
    assert queued.requests == 6 and shared_queued.jobs == 12
    assert pool.requests == 6 and shared.jobs == 12
    assert shared.calls < pool.requests          # batches of different variants shared calls


def test_a_lone_member_runs_at_once():
    sp = _systems()[0]
    motion = pulse_motion("ricker-anti", 0.38 * G, 0.95)
    shared = SharedBatches()
    pool = BatchPool(1, shared)
    (s, _), = _members(pool, [lambda m: _batch(m, sp, [motion], batch_options())])
    assert shared.calls == 1 and pool.rounds == 1
    np.testing.assert_array_equal(s, run_batch(sp, [motion], [1.0], [5.0], batch_options())[0])


def test_cancel_wakes_a_waiting_member():
    shared = SharedBatches()
    pool = BatchPool(2, shared)
    sp = _systems()[0]
    motion = pulse_motion("ricker-anti", 0.38 * G, 0.95)
    busy = threading.Event()
    release = threading.Event()

    def waiting(member):
        busy.wait(timeout=60)           # the other member is in: this batch waits for it
        return _batch(member, sp, [motion], batch_options())

    def other(member):        # a member that never asks for a batch keeps the first one waiting
        busy.set()
        release.wait(timeout=60)

    def cancel_later():     # as the grid does on Ctrl-C
        busy.wait(timeout=60)
        time.sleep(0.2)
        pool.cancel()
        release.set()
    threading.Thread(target=cancel_later).start()
    with pytest.raises(PoolCancelled):
        _members(pool, [other, waiting])
    assert shared.calls == 0


def test_shared_calls_on_an_executor_equal_the_calls_in_this_process():
    """On an executor (here the chunked local one; a dask cluster in tests/design_space/test_robust_runs.py)
    a shared call runs in chunks and gives each request the rows ``run_batch`` gives it alone."""
    from rockdesign.execution.executor import LocalExecutor
    sps = _systems()
    motions = [pulse_motion("ricker-anti", a * G, 0.95) for a in (0.25, 0.3, 0.38, 0.5)]
    opts = batch_options(1e-6, 1e-8)
    requests = [BatchRequest(sps[k], motions[k:], [1.0] * (4 - k), [5.0] * (4 - k), opts, [5.0] * (4 - k))
                for k in range(3)]
    chunked = SharedBatches(LocalExecutor())
    for req, (s, d) in zip(requests, chunked.requests(requests)):
        s_alone, d_alone = run_batch(req.sp, req.motions, req.scales, req.t_ends, opts, threads=False)
        np.testing.assert_array_equal(s, s_alone)
        np.testing.assert_array_equal(d, d_alone)
    assert chunked.calls == 1 and chunked.jobs == 4 + 3 + 2


def test_a_call_the_kind_cannot_merge_runs_as_given():
    """A member is an executor for any batch function: a call SharedBatches does not merge runs as given."""
    shared = SharedBatches()
    pool = BatchPool(1, shared)
    got, = _members(pool, [lambda m: dict(m.map(divmod, (17,), {0: (5,), 1: (3,)}))])
    assert got == {0: (3, 2), 1: (5, 2)} and shared.calls == 0 and pool.rounds == 1
