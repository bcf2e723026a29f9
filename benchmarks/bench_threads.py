"""Threads: one analysis in the calling thread, batches balanced over busy cores (same-run ratios).

Usage::

    .venv/bin/python benchmarks/bench_threads.py [--quick] [--out benchmarks/results/threads.json]

1. **One analysis** (``simulate``): ``rd.simulate`` of the ``podium_flat`` example under the built-in 30-s
   record p695-ff/1a, at numba's default thread count and with ``numba.set_num_threads(1)``, interleaved
   call by call.  The same job through the parallel batch driver (a ``prange`` region of one job, the
   way ``simulate`` ran before) is timed in the same rounds at both settings: the region's cost.  Done
   twice: on the machine as it is ("quiet") and with one CPU-bound competitor per core ("loaded",
   ``python -c 'while True: pass'`` processes).  Ratios: of the mins, of the medians, and the median of the
   ratios of the two times in each round (paired; the most robust on a shared machine).
2. **A batch with a busy core** (``batch``): the Housner block under the same record at
   ``--jobs`` scale factors 0.05 … 1.0 (summaries only), on one thread (the serial driver), and on all
   threads with the dynamic driver (:mod:`rockdesign.execution.scheduling`: each thread takes the next job
   from a shared counter) and with a static driver (numba's own ``prange`` over the jobs, each thread a
   fixed contiguous block — the scheme the batch driver replaced; compiled here, not cached), each with
   and without a competitor pinned to the last core.  The goal: the batch on all cores with one core busy
   takes ≤ 1.3× the one-thread time.
3. **Break-even** (``break_even``): batches of 1 … 8 jobs of the same block (scale factors 0.6 … 1.0, every
   job rocks), serial driver against the parallel driver: the smallest batch for which threads pay
   (``rockdesign.planar.dynamics.batch.SERIAL_BELOW_JOBS``).
4. **Job order** (``order``): the batch's jobs in their own order, longest first (by each job's measured
   one-thread time) and in the equal-count blocks of ``checks.runner``'s earlier ``balanced_order``, on the
   dynamic driver with a busy core.

The machine is shared: every configuration is timed in interleaved rounds and reported as min and
median; ``os.getloadavg()`` is recorded before and after each part.  Every result also checks that the
drivers agree bit for bit.  Writes ``benchmarks/results/threads.json`` and prints a table.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numba
import numpy as np
from numba import njit, prange

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import rockdesign as rd  # noqa: E402
from rockdesign.bench.problems import G, RECORD_ID, housner_block  # noqa: E402
from rockdesign.bench.timing import machine_info  # noqa: E402
from rockdesign.planar.dynamics import batch  # noqa: E402
from rockdesign.planar.dynamics.batch import _job, batch_options, pack_motions, run_packed  # noqa: E402
from rockdesign.planar.dynamics.model import ModelChoice, system_parameters  # noqa: E402
from rockdesign.jsonable import json_ready  # noqa: E402
from rockdesign.motions.library import load_record  # noqa: E402


@njit(parallel=True)
def static_batch(sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t, ev_k,
                 ev_y):
    """numba's own schedule: ``prange`` over the jobs, each thread one fixed contiguous block of them."""
    n = kinds.shape[0]
    summaries = np.zeros((n, batch.N_SUMMARY))
    diags = np.zeros((n, batch.N_DIAG), dtype=np.int64)
    written = np.zeros(n, dtype=np.int64)
    for j in prange(n):
        _job(j, sps, systems, kinds, xps, samples, offsets, lengths, t_ends, opts, y0s, sides, t_out, out_y, ev_t, ev_k,
             ev_y, summaries, diags, written)
    return summaries, diags, written


class Competitors:
    """CPU-bound ``while True: pass`` processes (one per entry of ``cpus``; None = not pinned), stopped on exit."""

    def __init__(self, cpus):
        self.cpus = list(cpus)
        self.procs: list[subprocess.Popen] = []

    def __enter__(self):
        for cpu in self.cpus:
            p = subprocess.Popen([sys.executable, "-c", "while True: pass"])
            if cpu is not None:
                os.sched_setaffinity(p.pid, {cpu})
            self.procs.append(p)
        time.sleep(0.3)                      # let them start spinning
        return self

    def __exit__(self, *exc):
        for p in self.procs:
            p.kill()
            p.wait()
        self.procs.clear()


def _stats(samples) -> dict:
    return {"min_s": min(samples), "median_s": statistics.median(samples), "n": len(samples)}


def _timed(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def _rounds(configs: dict, rounds: int) -> dict:
    """Time every ``configs[name] = (numba threads, fn)`` once per round, interleaved (order reversed every
    other round)."""
    samples = {name: [] for name in configs}
    for r in range(rounds):
        names = list(configs) if r % 2 == 0 else list(configs)[::-1]     # no configuration always first
        for name in names:
            threads, fn = configs[name]
            previous = numba.get_num_threads()
            numba.set_num_threads(threads)
            try:
                samples[name].append(_timed(fn))
            finally:
                numba.set_num_threads(previous)
    out = {name: _stats(v) for name, v in samples.items()}
    for name, v in samples.items():
        out[name]["samples_s"] = v
    return out


def _paired(res: dict, a: str, b: str) -> float:
    """Median over the rounds of a's time over b's in the same round (robust to the machine's slow drift)."""
    return statistics.median(x / y for x, y in zip(res[a]["samples_s"], res[b]["samples_s"]))


def bench_simulate(rounds: int) -> dict:
    """``rd.simulate`` (the serial path) and the one-job parallel region, default threads vs one thread."""
    project = rd.load_project(ROOT / "examples" / "podium_flat.toml")
    spec = f"record:{RECORD_ID}"
    threads = numba.get_num_threads()
    captured = {}

    def capture(*args):                       # the arguments simulate passes to its driver
        captured["args"] = args
        return real(*args)
    real = batch._run_serial
    batch._run_serial = capture
    try:
        reference = rd.simulate(project, spec)
    finally:
        batch._run_serial = real
    args = captured["args"]
    one_region = args + (1,)
    same = all(np.array_equal(a, b, equal_nan=True)
               for a, b in zip(batch._run_batch(*one_region), batch._run_serial(*args)))
    pairs = {"simulate, default threads": (threads, lambda: rd.simulate(project, spec)),
             "simulate, one thread": (1, lambda: rd.simulate(project, spec))}
    regions = {"one job in a parallel region, default threads": (threads, lambda: batch._run_batch(*one_region)),
               "one job in a parallel region, one thread": (1, lambda: batch._run_batch(*one_region)),
               "one job, serial driver": (threads, lambda: batch._run_serial(*args))}
    out = {"threads": threads, "drivers_bit_identical": bool(same), "theta_max_rad": float(reference.theta_max)}
    for label, cpus in (("quiet", []), ("loaded", [None] * (os.cpu_count() or 2))):
        load0 = os.getloadavg()
        with Competitors(cpus):
            res = _rounds(pairs, rounds)
            res.update(_rounds(regions, rounds))
        res["load_before"], res["load_after"], res["competitors"] = load0, os.getloadavg(), len(cpus)
        res["ratio_default_over_one_thread_paired"] = _paired(res, "simulate, default threads", "simulate, one thread")
        res["ratio_region_over_serial_paired"] = _paired(res, "one job in a parallel region, default threads",
                                                         "one job, serial driver")
        for stat in ("min_s", "median_s"):
            res[f"ratio_default_over_one_thread_{stat[:-2]}"] = (res["simulate, default threads"][stat]
                                                                 / res["simulate, one thread"][stat])
            res[f"ratio_region_over_serial_{stat[:-2]}"] = (res["one job in a parallel region, default threads"][stat]
                                                           / res["one job, serial driver"][stat])
        out[label] = res
    return out


def _block_batch(n_jobs: int, lowest: float = 0.05):
    sp = system_parameters(housner_block(), ModelChoice("block", "exact"))
    record = load_record(RECORD_ID, gravity=G)
    scales = np.linspace(lowest, 1.0, n_jobs)
    kinds, xps, samples, offsets, lengths = pack_motions([record] * n_jobs, scales)
    t_ends = np.full(n_jobs, record.duration)
    return sp, (kinds, xps, samples, offsets, lengths, t_ends), batch_options()


def _packed_args(sp, packed, opts, order=None):
    kinds, xps, samples, offsets, lengths, t_ends = packed
    if order is not None:
        kinds, xps, offsets, lengths, t_ends = (a[order] for a in (kinds, xps, offsets, lengths, t_ends))
    n = kinds.size
    y0s = np.zeros((n, 4))
    sides = np.ones(n)
    empty, rows = np.zeros(0), np.zeros((0, 4))
    return (np.ascontiguousarray(sp).reshape(1, -1), np.zeros(n, dtype=np.int64), kinds, xps, samples, offsets,
            lengths, t_ends, opts, y0s, sides, empty, rows, empty, np.zeros(0, dtype=np.int64), rows)


def bench_batch(n_jobs: int, rounds: int) -> dict:
    """The batch on one thread, and on all threads (dynamic and static drivers) with and without a busy core."""
    sp, packed, opts = _block_batch(n_jobs)
    args = _packed_args(sp, packed, opts)
    threads = numba.get_num_threads()
    t0 = time.perf_counter()
    static = static_batch(*args)
    compile_static = time.perf_counter() - t0
    serial = batch._run_serial(*args)
    dynamic = batch._run_batch(*args, threads)
    same = all(np.array_equal(a, b, equal_nan=True) and np.array_equal(a, c, equal_nan=True)
               for a, b, c in zip(serial, dynamic, static))
    quiet = {"one thread (serial driver)": (threads, lambda: batch._run_serial(*args)),
             "all threads, dynamic": (threads, lambda: batch._run_batch(*args, threads)),
             "all threads, static": (threads, lambda: static_batch(*args))}
    busy = {"all threads, dynamic, one core busy": quiet["all threads, dynamic"],
            "all threads, static, one core busy": quiet["all threads, static"]}
    samples = {name: [] for name in list(quiet) + list(busy)}
    load0 = os.getloadavg()
    last_cpu = max(os.sched_getaffinity(0))
    for _ in range(rounds):                    # quiet and busy rounds alternate
        for name, (_, fn) in quiet.items():
            samples[name].append(_timed(fn))
        with Competitors([last_cpu]):
            for name, (_, fn) in busy.items():
                samples[name].append(_timed(fn))
    res = {name: _stats(v) for name, v in samples.items()}
    base = res["one thread (serial driver)"]
    for name in list(res):
        for stat in ("min_s", "median_s"):
            res[name][f"ratio_to_one_thread_{stat[:-2]}"] = res[name][stat] / base[stat]
    return {"jobs": n_jobs, "threads": threads, "bit_identical": bool(same), "static_compile_s": compile_static,
            "load_before": load0, "load_after": os.getloadavg(), "competitor_cpu": last_cpu, "results": res,
            "goal_busy_core_ratio_le_1_3":
                res["all threads, dynamic, one core busy"]["ratio_to_one_thread_median"] <= 1.3}


def bench_break_even(rounds: int, sizes=(1, 2, 3, 4, 6, 8)) -> dict:
    """Serial driver against the parallel driver for small batches of the block (30-s record jobs, scale
    factors 0.6 … 1.0: every job rocks, ≈ 2 ms each on one core)."""
    sp, packed, opts = _block_batch(8, lowest=0.6)
    out = {"load_before": os.getloadavg(), "sizes": {}}
    threads = numba.get_num_threads()
    for n in sizes:
        order = np.arange(n) * (8 // n if n <= 8 else 1)
        args = _packed_args(sp, packed, opts, order=order)
        w = min(n, threads)
        ser, par = [], []
        for _ in range(rounds):
            ser.append(_timed(lambda: batch._run_serial(*args)))
            par.append(_timed(lambda: batch._run_batch(*args, w)))
        out["sizes"][n] = {"serial": _stats(ser), "parallel": _stats(par),
                           "parallel_over_serial_median": statistics.median(par) / statistics.median(ser),
                           "parallel_over_serial_min": min(par) / min(ser)}
    out["load_after"] = os.getloadavg()
    out["serial_below_jobs"] = batch.SERIAL_BELOW_JOBS
    return out


def bench_order(n_jobs: int, rounds: int) -> dict:
    """The dynamic driver with a busy core: jobs in their own order, longest first, or in balanced blocks."""
    from rockdesign.planar.checks.runner import balanced_order
    sp, packed, opts = _block_batch(n_jobs)
    threads = numba.get_num_threads()
    costs = []
    for j in range(n_jobs):                   # each job's one-thread time: the ideal predicted cost
        one = _packed_args(sp, packed, opts, order=np.array([j]))
        costs.append(min(_timed(lambda: batch._run_serial(*one)) for _ in range(2)))
    orders = {"own order": np.arange(n_jobs),
              "longest first": np.array(sorted(range(n_jobs), key=lambda k: (-costs[k], k))),
              "balanced equal-count blocks": np.array(balanced_order(costs, threads))}
    arg_sets = {name: _packed_args(sp, packed, opts, order=o) for name, o in orders.items()}
    samples = {name: [] for name in orders}
    with Competitors([max(os.sched_getaffinity(0))]):
        for _ in range(rounds):
            for name, a in arg_sets.items():
                samples[name].append(_timed(lambda: batch._run_batch(*a, threads)))
    return {"jobs": n_jobs, "sum_of_job_times_s": sum(costs), "longest_job_s": max(costs),
            "results": {name: _stats(v) for name, v in samples.items()}}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer rounds and jobs")
    ap.add_argument("--jobs", type=int, default=None, help="jobs in the batch (default 200, quick 64)")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "threads.json"))
    a = ap.parse_args(argv)
    jobs = a.jobs or (64 if a.quick else 200)
    rounds = 5 if a.quick else 9
    t0 = time.perf_counter()
    rd.simulate(rd.load_project(ROOT / "examples" / "podium_flat.toml"), f"record:{RECORD_ID}")   # warm
    result = {"machine": machine_info(), "threading_layer": None}
    result["simulate"] = bench_simulate(rounds * 8)
    result["threading_layer"] = numba.threading_layer()
    result["batch"] = bench_batch(jobs, rounds)
    result["break_even"] = bench_break_even(rounds * 3)
    result["order"] = bench_order(jobs, max(3, rounds // 2))
    result["seconds"] = time.perf_counter() - t0
    sim, bres = result["simulate"], result["batch"]["results"]
    result["summary"] = {
        "simulate_default_over_one_thread_quiet": sim["quiet"]["ratio_default_over_one_thread_paired"],
        "simulate_default_over_one_thread_loaded": sim["loaded"]["ratio_default_over_one_thread_paired"],
        "one_job_region_over_serial_quiet": sim["quiet"]["ratio_region_over_serial_paired"],
        "one_job_region_over_serial_loaded": sim["loaded"]["ratio_region_over_serial_paired"],
        "batch_busy_core_over_one_thread_dynamic":
            bres["all threads, dynamic, one core busy"]["ratio_to_one_thread_median"],
        "batch_busy_core_over_one_thread_static":
            bres["all threads, static, one core busy"]["ratio_to_one_thread_median"],
        "goal_simulate_le_1_3": max(sim["quiet"]["ratio_default_over_one_thread_paired"],
                                    sim["loaded"]["ratio_default_over_one_thread_paired"]) <= 1.3,
        "goal_busy_core_le_1_3": result["batch"]["goal_busy_core_ratio_le_1_3"],
        "load_average": result["machine"]["load_average"]}
    Path(a.out).parent.mkdir(parents=True, exist_ok=True)
    Path(a.out).write_text(json.dumps(json_ready(result), indent=1) + "\n")
    _print(result)
    return 0


def _print(r: dict) -> None:
    s = r["simulate"]
    print(f"threading layer {r['threading_layer']}, {s['threads']} threads, load {r['machine']['load_average']}")
    for label in ("quiet", "loaded"):
        q = s[label]
        print(f"simulate ({label}, load {q['load_before'][0]:.1f}): default/one thread "
              f"{q['ratio_default_over_one_thread_paired']:.2f}× paired median, "
              f"{q['ratio_default_over_one_thread_median']:.2f}× of medians, "
              f"{q['ratio_default_over_one_thread_min']:.2f}× min;"
              f" a one-job parallel region / serial driver {q['ratio_region_over_serial_paired']:.1f}× paired median")
        for name in ("simulate, default threads", "simulate, one thread",
                     "one job in a parallel region, default threads"):
            print(f"    {name:48s} min {q[name]['min_s'] * 1e3:7.2f} ms  median {q[name]['median_s'] * 1e3:7.2f} ms")
    b = r["batch"]
    print(f"batch of {b['jobs']} jobs (load {b['load_before'][0]:.1f}), bit-identical {b['bit_identical']}:")
    for name, v in b["results"].items():
        print(f"    {name:40s} min {v['min_s']:.3f} s  median {v['median_s']:.3f} s  "
              f"({v['ratio_to_one_thread_median']:.2f}× one thread, median)")
    print("break-even (parallel / serial, median):",
          ", ".join(f"{n} jobs {v['parallel_over_serial_median']:.2f}×" for n, v in r["break_even"]["sizes"].items()))
    o = r["order"]
    print("job order, one core busy:", ", ".join(f"{k} {v['median_s']:.3f} s" for k, v in o["results"].items()))
    print(f"({r['seconds']:.0f} s)")


if __name__ == "__main__":
    sys.exit(main())
