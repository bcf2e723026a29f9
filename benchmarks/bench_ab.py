"""Engine A/B: this checkout against another (e.g. the previous commit), interleaved, on one 30-s record.

The shared machine's speed drifts by ±30 % within minutes, so two `bench_engine.py` runs an hour apart
cannot show a 10 % change.  This script alternates the two checkouts in child processes (round 1: A, B;
round 2: A, B; …), each child timing every system of :data:`rockdesign.bench.problems.SYSTEMS` under
the benchmark record (best of ``--repeats`` calls after a warm-up): ``simulate`` with the history and
the batch kernel's summary-only run (the check's path).  It reports the best time of each checkout
over all rounds and the ratio B/A (> 1: this checkout is faster), and writes ``--out`` if given.

    .venv/bin/python benchmarks/bench_ab.py --baseline-root /path/to/old-checkout [--rounds 3] [--repeats 15]

The baseline checkout needs no virtualenv of its own (its package is imported from its folder with
this interpreter); its first round compiles its kernels into its own ``__pycache__``.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

CHILD = r"""
import json, sys, time
sys.path.insert(0, sys.argv[1])
from rockdesign.bench.problems import SYSTEMS, bench_record
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.planar.dynamics.batch import batch_options, run_batch
from rockdesign.planar.dynamics.model import ModelChoice, system_parameters
repeats = int(sys.argv[2])
record = bench_record()
out = {}
for name, (make, structure) in SYSTEMS.items():
    system = make()
    simulate(system, record, structure=structure, t_end=30.0)
    best = min(_timed(lambda: simulate(system, record, structure=structure, t_end=30.0)) for _ in range(repeats))
    sp = system_parameters(system, ModelChoice(structure, "exact"))
    opts = batch_options(1e-10, 1e-12, energy_stop=False)
    run_batch(sp, [record], [1.0], [30.0], opts)
    summary = min(_timed(lambda: run_batch(sp, [record], [1.0], [30.0], opts)) for _ in range(repeats))
    out[name] = {"ms": 1e3 * best, "ms_summary_only": 1e3 * summary}
print(json.dumps(out))
"""
TIMER = "import time\ndef _timed(f):\n    t = time.perf_counter(); f(); return time.perf_counter() - t\n"


def run_child(root: Path, repeats: int) -> dict:
    """Times of every system, measured by a child process importing rockdesign from ``root``."""
    proc = subprocess.run([sys.executable, "-c", TIMER + CHILD, str(root), str(repeats)], capture_output=True,
                          text=True, cwd=root)
    if proc.returncode != 0:
        raise SystemExit(f"timing {root} failed:\n{proc.stderr[-3000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _commit(root: Path) -> str | None:
    proc = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    return proc.stdout.strip() or None


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline-root", required=True, type=Path, help="the other checkout (A)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    roots = {"A (baseline)": args.baseline_root.resolve(), "B (this checkout)": ROOT}
    best: dict[str, dict] = {k: {} for k in roots}
    for r in range(args.rounds):
        for label, root in roots.items():
            for system, times in run_child(root, args.repeats).items():
                slot = best[label].setdefault(system, {"ms": float("inf"), "ms_summary_only": float("inf")})
                for key, value in times.items():
                    slot[key] = min(slot[key], value)
            print(f"round {r + 1}: {label} done", flush=True)
    a, b = best["A (baseline)"], best["B (this checkout)"]
    print(f"{'system':15s} {'A ms':>8s} {'B ms':>8s} {'A/B':>6s}   {'A summary':>9s} {'B summary':>9s} {'A/B':>6s}")
    sys.path.insert(0, str(ROOT))
    from rockdesign.bench.timing import machine_info
    info = machine_info()
    result = {"benchmark": "ab", "date": info["date"], "machine": info, "record": "p695-ff/1a x 0.6, 30 s, rtol 1e-10",
              "baseline_commit": _commit(roots["A (baseline)"]), "commit": _commit(ROOT), "rounds": args.rounds,
              "repeats": args.repeats, "systems": {}}
    for system in a:
        ra = a[system]["ms"] / b[system]["ms"]
        rs = a[system]["ms_summary_only"] / b[system]["ms_summary_only"]
        print(f"{system:15s} {a[system]['ms']:8.2f} {b[system]['ms']:8.2f} {ra:6.2f}   "
              f"{a[system]['ms_summary_only']:9.2f} {b[system]['ms_summary_only']:9.2f} {rs:6.2f}")
        result["systems"][system] = {"baseline": a[system], "ours": b[system], "ratio": ra, "ratio_summary_only": rs}
    if args.out:
        args.out.write_text(json.dumps(result, indent=2) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
