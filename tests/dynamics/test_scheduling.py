"""The shared job counter of the parallel drivers (rockdesign.execution.scheduling): every job is taken
exactly once, whichever worker takes it."""
from __future__ import annotations

import numba
import numpy as np
from numba import njit, prange

from rockdesign.execution.scheduling import take, worker_count


@njit
def _serial_takes(counter, times):
    out = np.empty(times, dtype=np.int64)
    for i in range(times):
        out[i] = take(counter)
    return out


@njit(parallel=True)
def _workers_take(n, workers, spin):
    """Each of ``workers`` workers takes jobs until none is left; job j records how often it was taken and
    burns ``spin × (j % 5)`` loop iterations, so the workers' jobs interleave."""
    counts = np.zeros(n, dtype=np.int64)
    sums = np.zeros(n)
    counter = np.zeros(1, dtype=np.int64)
    for _ in prange(workers):
        j = take(counter)
        while j < n:
            s = 0.0
            for k in range(spin * (j % 5)):
                s += np.sin(k * 1e-3 + j)
            sums[j] = s
            counts[j] += 1
            j = take(counter)
    return counts, sums, counter


def test_take_returns_the_counter_before_incrementing_it():
    counter = np.zeros(1, dtype=np.int64)
    assert list(_serial_takes(counter, 4)) == [0, 1, 2, 3]
    assert counter[0] == 4


def test_every_job_is_taken_exactly_once_by_concurrent_workers():
    n = 20_000
    workers = max(2, numba.get_num_threads())
    counts, sums, counter = _workers_take(n, workers, 50)
    assert np.all(counts == 1)
    assert counter[0] == n + workers                 # each worker's last take found the queue empty
    expected = np.array([sum(np.sin(k * 1e-3 + j) for k in range(50 * (j % 5))) for j in range(0, n, 997)])
    assert np.allclose(sums[::997], expected, rtol=1e-12, atol=1e-12)


def test_worker_count():
    assert worker_count(0) == 1
    assert worker_count(1) == 1
    assert worker_count(10 ** 6) == numba.get_num_threads()
