"""The order the batch kernel runs jobs in (checks.runner.balanced_order): blocks of equal counts and
near-equal predicted cost, and results that do not depend on it."""
from __future__ import annotations

import itertools
import math
import random

from rockdesign.checks.runner import balanced_order, run_jobs
from rockdesign.dynamics.model import ModelChoice
from rockdesign.motions.motion import pulse_motion
from support import G, block_from_p


def _blocks(order, threads):
    n = len(order)
    size = [n // threads + (1 if b < n % threads else 0) for b in range(threads)]
    out, start = [], 0
    for s in size:
        out.append(order[start:start + s])
        start += s
    return out


def _best_two_way(costs):
    """Brute force: the smallest possible larger half over all equal-count splits."""
    n = len(costs)
    best = math.inf
    for first in itertools.combinations(range(n), n // 2 + n % 2):
        a = sum(costs[k] for k in first)
        best = min(best, max(a, sum(costs) - a))
    return best


def test_the_order_is_a_permutation_with_balanced_blocks():
    rng = random.Random(5)
    for trial in range(40):
        n = rng.randint(2, 12)
        costs = [rng.choice([rng.uniform(0.5, 1.0), rng.uniform(5, 40)]) for _ in range(n)]
        order = balanced_order(costs, 2)
        assert sorted(order) == list(range(n))
        heavier = max(sum(costs[k] for k in block) for block in _blocks(order, 2))
        # greedy longest-first with equal counts: within 1/3 of the optimum (and usually at it)
        assert heavier <= _best_two_way(costs) * 4 / 3 + 1e-12
    assert balanced_order([5.0, 1.0, 2.0], 1) == [0, 1, 2]


def test_a_sorted_list_is_no_longer_split_into_short_and_long_halves():
    costs = [1.0] * 8 + [10.0] * 8           # the kernel's two threads would get 8 and 80
    blocks = _blocks(balanced_order(costs, 2), 2)
    assert [sum(costs[k] for k in b) for b in blocks] == [44.0, 44.0]


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
