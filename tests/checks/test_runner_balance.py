"""The order the batch driver's threads take jobs in (checks.runner.balanced_order): longest predicted
cost first, which balances the threads of the shared job counter, and results that do not depend on it."""
from __future__ import annotations

import itertools
import math
import random

from rockdesign.planar.checks.runner import balanced_order, run_jobs
from rockdesign.planar.dynamics.model import ModelChoice
from rockdesign.motions.motion import pulse_motion
from support import G, block_from_p


def _makespan(order, costs, threads):
    """When the last thread finishes if each thread takes the next job of ``order`` as it becomes free (the
    batch driver's shared counter, rockdesign.execution.scheduling)."""
    free = [0.0] * threads
    for k in order:
        t = min(range(threads), key=lambda i: (free[i], i))
        free[t] += costs[k]
    return max(free)


def _best_two_way(costs):
    """Brute force: the smallest possible larger half over all splits into two sets."""
    n = len(costs)
    best = math.inf
    for size in range(n + 1):
        for first in itertools.combinations(range(n), size):
            a = sum(costs[k] for k in first)
            best = min(best, max(a, sum(costs) - a))
    return best


def test_the_order_is_a_permutation_that_balances_two_threads():
    rng = random.Random(5)
    for trial in range(40):
        n = rng.randint(2, 12)
        costs = [rng.choice([rng.uniform(0.5, 1.0), rng.uniform(5, 40)]) for _ in range(n)]
        order = balanced_order(costs, 2)
        assert sorted(order) == list(range(n))
        # longest first, each job to the first free thread: within 4/3 of the optimum (Graham's bound
        # 4/3 − 1/(3m) for m = 2 threads: 7/6)
        assert _makespan(order, costs, 2) <= _best_two_way(costs) * 7 / 6 + 1e-12
    assert balanced_order([5.0, 1.0, 2.0], 1) == [0, 1, 2]


def test_a_long_job_is_not_left_for_last():
    costs = [1.0] * 6 + [10.0]               # in their own order the long job starts when the short ones end
    assert _makespan(list(range(7)), costs, 2) == 13.0
    assert _makespan(balanced_order(costs, 2), costs, 2) == 10.0
    assert balanced_order([2.0, 2.0, 3.0], 2) == [2, 0, 1]       # ties keep the job order


def test_results_do_not_depend_on_the_predicted_costs():
    system = block_from_p(2.14, math.tan(0.25)).with_restitution(0.81)
    period = 2 * math.pi / (5 * 2.14)
    motions = [pulse_motion("sine", k * 0.25 * G, period) for k in (1.5, 2.0, 3.0186, 4.5, 6.0, 2.5)]
    kw = dict(rtol=1e-10, atol=1e-12, free_vibration=5.0, criterion="dynamic", rest_velocity=5e-4)
    choice = ModelChoice("block", "linear")
    plain = run_jobs(system, choice, motions, [1.0] * 6, **kw)
    shuffled = run_jobs(system, choice, motions, [1.0] * 6, costs=[6, 1, 5, 2, 4, 3], chunk=6, **kw)
    assert shuffled == plain
    assert any(r.overturned for r in plain) and not all(r.overturned for r in plain)
    assert all(0.0 < r.t_end <= m.duration + 5.0 + 1e-9 for r, m in zip(plain, motions))
    assert min(r.t_end for r in plain if r.overturned) < min(r.t_end for r in plain if not r.overturned)
