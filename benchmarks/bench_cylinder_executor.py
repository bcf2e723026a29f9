"""The cylinder check on an executor: its 3D analyses in batches on worker processes, against the same check in
this process (the baseline, same process, same project).

Usage::

    .venv/bin/python benchmarks/bench_cylinder_executor.py [--repeats 3] [--processes 2] [--dask]
                                                           [--out benchmarks/results/cylinder_executor.json]

The check of ``examples/cylinder.toml`` (2H = 3 m, D = 0.6 m, damped model; 22 record pairs of
``p695-farfield-pairs``; design level, incremental scans and the perturbation ensemble of 8 runs per pair),
:func:`rockdesign.cylinder.check.run_cylinder_check`: the baseline in this process one analysis after the other
(as before the analyses ran in threads), then the default (``executor=None``: in this process, one analysis per
core in threads, :func:`~rockdesign.execution.executor.one_core`), a
:class:`~rockdesign.execution.executor.LocalExecutor` of ``--processes`` spawned workers (started once before the
timed runs; its start-up is reported apart), and with ``--dask`` a local dask cluster of as many workers.
Every run's results.json sections (records, acceptance, summary, ensemble) must equal the in-process run's.
Times are the median of ``--repeats`` runs after a warm-up run that loads the kernels; the ratio is the baseline
over the executor (above 1: the executor is faster).  The planar runs along the components (2 per pair) stay in
this process, one after the other, so the ratio is below the core count.
"""
from __future__ import annotations

import argparse
import json
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from rockdesign.cylinder.check import run_cylinder_check  # noqa: E402
from rockdesign.execution.executor import LocalExecutor, make_executor, usable_cores  # noqa: E402
from rockdesign.library import load_project  # noqa: E402

SECTIONS = ("records", "acceptance", "summary", "ensemble", "verdict", "verdict_reason")


def essence(result) -> dict:
    data = result.as_json()
    return {k: data[k] for k in SECTIONS}


class OneAfterAnother(LocalExecutor):
    """The baseline: this process, every task in the caller's thread, one after the other."""

    def map(self, func, common, tasks):
        for i, args in tasks.items():
            yield i, func(*common, *args)


def timed(project, executor, repeats: int) -> tuple[list[float], dict, int]:
    times, out, analyses = [], None, 0
    for _ in range(repeats):
        counter = executor if executor is not None else LocalExecutor()    # None: this process
        before = counter.analyses
        t0 = time.perf_counter()
        result = run_cylinder_check(project, executor=counter)
        times.append(time.perf_counter() - t0)
        analyses = counter.analyses - before
        out = essence(result)
    return times, out, analyses


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--processes", type=int, default=2)
    parser.add_argument("--dask", action="store_true", help="also a local dask cluster of --processes workers")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "cylinder_executor.json"))
    args = parser.parse_args(argv)
    project = load_project(ROOT / "examples" / "cylinder.toml")
    run_cylinder_check(project)                                   # warm-up: kernels loaded, records read
    base, reference, analyses = timed(project, OneAfterAnother(), args.repeats)
    print(f"in this process, one analysis after the other: median {statistics.median(base):.2f} s ({analyses} analyses)")
    rows = {"in_process": {"seconds": base, "median": statistics.median(base), "analyses": analyses}}
    executors = [("threads", LocalExecutor), ("processes", lambda: LocalExecutor(processes=args.processes))]
    if args.dask:
        executors.append(("dask", lambda: make_executor(f"local:{args.processes}", numba_threads=1)))
    for name, make in executors:
        t0 = time.perf_counter()
        executor = make()
        executor.start()
        start = time.perf_counter() - t0
        try:
            run_cylinder_check(project, executor=executor)        # warm-up: the workers load the kernels
            times, got, n = timed(project, executor, args.repeats)
        finally:
            executor.close()
        same = got == reference
        ratio = statistics.median(base) / statistics.median(times)
        print(f"{name}: start {start:.2f} s, median {statistics.median(times):.2f} s, "
              f"one after the other / {name} = {ratio:.2f}, results equal: {same}")
        rows[name] = {"seconds": times, "median": statistics.median(times), "start_seconds": start,
                      "ratio_one_after_the_other_over_executor": ratio, "results_equal": same, "analyses": n}
        if not same:
            print(f"{name}: results differ from the in-process check", file=sys.stderr)
            return 1
    out = {"machine": {"platform": platform.platform(), "python": platform.python_version(),
                       "processor": platform.processor()},
           "project": "examples/cylinder.toml", "processes": args.processes, "repeats": args.repeats,
           "cores": usable_cores(), **rows}
    Path(args.out).write_text(json.dumps(out, indent=1) + "\n")
    print(f"written {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
