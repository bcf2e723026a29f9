"""How the parallel batch driver shares out its jobs: the shared counter against static schedules (same-run ratios).

Usage::

    .venv/bin/python benchmarks/bench_scheduling.py [--rounds N] [--factors 0.5,1,2,3]
        [--baseline-scheduling FILE] [--out benchmarks/results/scheduling.json]

The batch is a check's: ``examples/podium_curved.toml`` (2DOF podium, exact equations, the check's rtol)
under the 44 records of its FEMA P695 far-field suite, scaled as the check scales them, times each of
``--factors`` (default 0.5, 1, 2, 3: 176 jobs, some overturning early, most running to the end).  It runs
in two ways: in batches of 8 jobs, longest predicted first (as ``checks.runner.run_jobs`` hands them to the
driver on 2 cores), and as one batch of all jobs.  Every driver has the body of
``rockdesign.planar.dynamics.batch._run_batch`` and is compiled here (not cached):

* ``counter`` — workers take the next job from the shared counter of :mod:`rockdesign.execution.scheduling`;
* ``counter, baseline`` (with ``--baseline-scheduling FILE``: another version of that module, e.g.
  ``git show <commit>:rockdesign/execution/scheduling.py > FILE``) — the same driver on its ``take``;
* ``static, cost-balanced`` — no counter: the jobs dealt out in Python before the call, longest predicted
  first to the least-loaded worker (LPT list scheduling on the predicted costs, the end times), each
  worker running its own list;
* ``static, numba blocks`` — ``prange`` over the jobs: numba's schedule, one contiguous block per thread.

On the machine as it is, and with a CPU-bound competitor pinned to the last core.  The drivers are timed
in interleaved rounds (order reversed every other round); reported: min, median and the median over the
rounds of each driver's time over the ``counter`` driver's (paired).  Every driver's results are checked
bit for bit against the serial driver.  Writes ``benchmarks/results/scheduling.json``.
"""
from __future__ import annotations

import argparse
import heapq
import importlib.util
import json
import os
import statistics
import sys
import time
from pathlib import Path

import numba
import numpy as np
from numba import njit, prange

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import rockdesign as rd  # noqa: E402
from bench_threads import Competitors  # noqa: E402
from rockdesign.bench.timing import machine_info  # noqa: E402
from rockdesign.execution import scheduling  # noqa: E402
from rockdesign.jsonable import json_ready  # noqa: E402
from rockdesign.planar.checks.check import suite_records  # noqa: E402
from rockdesign.planar.checks.runner import balanced_order  # noqa: E402
from rockdesign.planar.dynamics import batch  # noqa: E402
from rockdesign.planar.dynamics.batch import _job, batch_options, pack_motions  # noqa: E402
from rockdesign.planar.dynamics.model import ModelChoice, default_structure, system_parameters  # noqa: E402

CHECK_BATCH = 8
"""Jobs per call of the driver in a check on 2 cores (``run_jobs``: max(4 × usable cores, 8))."""


def counter_driver(take):
    """``batch._run_batch`` with the given ``take``."""
    @njit(parallel=True)
    def run(sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t, ev_k,
            ev_y, workers):
        n = kinds.shape[0]
        summaries = np.zeros((n, batch.N_SUMMARY))
        diags = np.zeros((n, batch.N_DIAG), dtype=np.int64)
        written = np.zeros(n, dtype=np.int64)
        counter = np.zeros(1, dtype=np.int64)
        for _ in prange(workers):
            j = take(counter)
            while j < n:
                _job(j, sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y,
                     ev_t, ev_k, ev_y, summaries, diags, written)
                j = take(counter)
        return summaries, diags, written
    return run


@njit(parallel=True)
def planned_driver(sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t,
                   ev_k, ev_y, plan):
    """Worker ``w`` runs the jobs ``plan[w, :]`` (−1: no more), dealt out before the call."""
    n = kinds.shape[0]
    summaries = np.zeros((n, batch.N_SUMMARY))
    diags = np.zeros((n, batch.N_DIAG), dtype=np.int64)
    written = np.zeros(n, dtype=np.int64)
    for w in prange(plan.shape[0]):
        for k in range(plan.shape[1]):
            j = plan[w, k]
            if j < 0:
                break
            _job(j, sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t,
                 ev_k, ev_y, summaries, diags, written)
    return summaries, diags, written


@njit(parallel=True)
def block_driver(sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t,
                 ev_k, ev_y):
    """numba's own schedule: ``prange`` over the jobs."""
    n = kinds.shape[0]
    summaries = np.zeros((n, batch.N_SUMMARY))
    diags = np.zeros((n, batch.N_DIAG), dtype=np.int64)
    written = np.zeros(n, dtype=np.int64)
    for j in prange(n):
        _job(j, sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t, ev_k,
             ev_y, summaries, diags, written)
    return summaries, diags, written


def lpt_plan(costs, workers: int) -> np.ndarray:
    """Jobs dealt out longest first to the least-loaded worker (ties: lower worker); workers × longest list."""
    lists = [[] for _ in range(workers)]
    heap = [(0.0, w) for w in range(workers)]
    for j in sorted(range(len(costs)), key=lambda k: (-costs[k], k)):
        load, w = heapq.heappop(heap)
        lists[w].append(j)
        heapq.heappush(heap, (load + costs[j], w))
    plan = np.full((workers, max(1, max(len(x) for x in lists))), -1, dtype=np.int64)
    for w, x in enumerate(lists):
        plan[w, :len(x)] = x
    return plan


def check_jobs(factors):
    """(sp, motions, scales, t_ends, opts) of the podium_curved check's suite at ``factors``."""
    project = rd.load_project(ROOT / "examples" / "podium_curved.toml")
    a = project.analysis
    _, resolved = suite_records(project)
    motions = [r.motion for r in resolved.records]
    choice = ModelChoice(default_structure(project.system, a.rigid_superstructure_ratio)[0], "exact")
    sp = system_parameters(project.system, choice, rest_velocity=a.rest_velocity)
    jobs = [(m, f) for f in factors for m in motions]
    t_ends = [m.duration + a.free_vibration for m, _ in jobs]
    opts = batch_options(a.rtol, a.atol)
    return sp, [m for m, _ in jobs], [f for _, f in jobs], t_ends, opts, choice.label, len(motions)


def packed_args(sp, motions, scales, t_ends, opts):
    kinds, xps, samples, offsets, lengths = pack_motions(motions, scales)
    n = kinds.size
    y0s = np.zeros((n, 4))
    sides = np.ones(n)
    empty, rows = np.zeros(0), np.zeros((0, 4))
    return (np.ascontiguousarray(sp).reshape(1, -1), np.zeros(n, dtype=np.int64), kinds, xps, samples, offsets,
            lengths, np.asarray(t_ends, dtype=np.float64), opts, y0s, sides, empty, rows, empty,
            np.zeros(0, dtype=np.int64), rows)


def batches(sp, motions, scales, t_ends, opts, size, threads):
    """[(packed arguments, predicted costs)] of consecutive batches of ``size`` jobs, each longest first."""
    out = []
    for start in range(0, len(motions), size):
        sl = slice(start, start + size)
        costs = t_ends[sl]
        order = balanced_order(costs, threads)
        out.append((packed_args(sp, [motions[sl][k] for k in order], [scales[sl][k] for k in order],
                                [costs[k] for k in order], opts), [costs[k] for k in order]))
    return out


def drivers(calls, counters: dict, threads: int) -> dict:
    """name → fn running every call (packed args, costs) with that driver."""
    out = {}
    for name, run in counters.items():
        out[name] = lambda run=run: [run(*args, scheduling.worker_count(args[2].size)) for args, _ in calls]
    plans = [lpt_plan(costs, min(threads, len(costs))) for _, costs in calls]
    out["static, cost-balanced"] = lambda: [planned_driver(*args, plan) for (args, _), plan in zip(calls, plans)]
    out["static, numba blocks"] = lambda: [block_driver(*args) for args, _ in calls]
    return out


def timed_rounds(configs: dict, rounds: int) -> dict:
    samples = {name: [] for name in configs}
    for r in range(rounds):
        for name in (list(configs) if r % 2 == 0 else list(configs)[::-1]):
            t0 = time.perf_counter()
            configs[name]()
            samples[name].append(time.perf_counter() - t0)
    res = {name: {"min_s": min(v), "median_s": statistics.median(v), "samples_s": v} for name, v in samples.items()}
    for name, v in samples.items():
        res[name]["over_counter_paired"] = statistics.median(
            x / y for x, y in zip(v, samples["counter"]))
    return res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--factors", default="0.5,1,2,3")
    ap.add_argument("--baseline-scheduling", default=None, help="another scheduling.py to compare (its take)")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "scheduling.json"))
    a = ap.parse_args(argv)
    t_start = time.perf_counter()
    threads = numba.get_num_threads()
    sp, motions, scales, t_ends, opts, model, n_records = check_jobs([float(f) for f in a.factors.split(",")])
    counters = {"counter": counter_driver(scheduling.take)}
    if a.baseline_scheduling:
        spec = importlib.util.spec_from_file_location("baseline_scheduling", a.baseline_scheduling)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        counters["counter, baseline"] = counter_driver(module.take)
    whole = batches(sp, motions, scales, t_ends, opts, len(motions), threads)
    check = batches(sp, motions, scales, t_ends, opts, CHECK_BATCH, threads)
    # compile, and check every driver against the serial one, bit for bit
    reference = batch._run_serial(*whole[0][0])
    identical = {}
    for name, fn in drivers(whole, counters, threads).items():
        got = fn()[0]
        identical[name] = all(np.array_equal(x, y, equal_nan=True) for x, y in zip(got, reference))
    result = {"machine": machine_info(), "threading_layer": numba.threading_layer(), "threads": threads,
              "project": "examples/podium_curved.toml", "model": model, "records": n_records,
              "factors": a.factors, "jobs": len(motions), "rtol": float(opts[batch.O_RTOL]),
              "serial_seconds_once": None, "bit_identical_to_serial": identical, "conditions": {}}
    t0 = time.perf_counter()
    batch._run_serial(*whole[0][0])
    result["serial_seconds_once"] = time.perf_counter() - t0
    for label, cpus in (("as is", []), ("one core busy", [(os.cpu_count() or 2) - 1])):
        cond = {"load_before": os.getloadavg()}
        with Competitors(cpus):
            for mode, calls in (("batches of 8, longest first", check), ("one batch, longest first", whole)):
                cond[mode] = timed_rounds(drivers(calls, counters, threads), a.rounds)
        cond["load_after"] = os.getloadavg()
        result["conditions"][label] = cond
    result["seconds"] = time.perf_counter() - t_start
    result["summary"] = {"bit_identical": all(identical.values())}
    for label, cond in result["conditions"].items():
        for mode, short in (("batches of 8, longest first", "batches_of_8"), ("one batch, longest first", "one_batch")):
            for name, v in cond[mode].items():
                if name != "counter":
                    key = f"{label}_{short}_{name}_over_counter_ratio"
                    result["summary"][key.replace(", ", "_").replace(" ", "_").replace("-", "_")] = \
                        v["over_counter_paired"]
    Path(a.out).parent.mkdir(parents=True, exist_ok=True)
    Path(a.out).write_text(json.dumps(json_ready(result), indent=1) + "\n")
    _print(result)
    return 0


def _print(r: dict) -> None:
    print(f"{r['jobs']} jobs ({r['records']} records × {r['factors']}), {r['model']}, rtol {r['rtol']:g}; "
          f"{r['threading_layer']}, {r['threads']} threads; serial {r['serial_seconds_once']:.2f} s once")
    print("bit-identical to the serial driver:", r["bit_identical_to_serial"])
    for label, cond in r["conditions"].items():
        print(f"{label} (load {cond['load_before'][0]:.1f} → {cond['load_after'][0]:.1f}):")
        for mode in ("batches of 8, longest first", "one batch, longest first"):
            print(f"  {mode}:")
            for name, v in cond[mode].items():
                print(f"    {name:24s} min {v['min_s']:.3f} s  median {v['median_s']:.3f} s  "
                      f"{v['over_counter_paired']:.3f}× counter (paired median)")
    print(f"({r['seconds']:.0f} s)")


if __name__ == "__main__":
    sys.exit(main())
