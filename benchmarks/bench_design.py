"""Benchmark: ``rockdesign design`` over a 3 × 3 grid against the nine separate ``rockdesign check --no-pdf``
runs of the same variants, in the same run (the machine is shared: only the ratio is compared).

The project is a 20-column podium with a rigid superstructure under 11 far-field ground motions
(p695-ff/1a … 11a at 0.4 g, the ASCE 7-22 minimum), varied in column width (0.5, 0.65, 0.8 m) and height
(2, 2.5, 3 m).  Each variant is written out as its own project file and checked by a separate process,
as an engineer would; the grid is one ``design --no-pdf`` process.  A 1 × 3 grid (the widths at the
first height) against the three matching checks shows how the saving grows with the grid.  Every
cell's verdict is compared with its check's verdict (the benchmark fails if one differs).

In one process, the 3 × 3 grid with its variants checked together (their batches merged into shared
calls of the batch driver, the default) against the same grid checked one variant after the other,
alternating, ``--rounds`` times each: the ratio of the medians, and the cells compared (they must be
equal).

    .venv/bin/python benchmarks/bench_design.py [--out benchmarks/results/design.json]
"""
from __future__ import annotations

import argparse
import itertools
import json
import os
import subprocess
import sys
import tempfile
import time
import tomllib
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

RECORDS = ", ".join(f'"p695-ff/{k}a"' for k in range(1, 12))
PROJECT = f"""\
[project]
name = "20-column podium, 11 far-field ground motions"

[podium]
columns = 20
cap_beam_mass = "200 t"
height = "2 m"
width = "0.6 m"
mass = "2.7 t"
mass_distribution = 0.3333

[superstructure]
mass = "600 t"
period = "rigid"

[excitation]
records = [{RECORDS}]
scale = {{ method = "pga", target = "0.4 g" }}

[analysis]
overturn = "static"
"""
WIDTH = "podium.width=0.5m:0.8m:3"
HEIGHT = "podium.height=2m:3m:3"


def run(args: list[str], cwd: Path) -> tuple[float, int, str]:
    """Wall seconds, exit code and stderr of ``python -m rockdesign.cli ARGS``."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "rockdesign.cli", *args], env=env, cwd=cwd, capture_output=True,
                          text=True)
    dt = time.perf_counter() - t0
    if proc.returncode not in (0, 1):
        raise SystemExit(f"{args[0]} failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
    return dt, proc.returncode, proc.stderr


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "design.json"))
    ap.add_argument("--rounds", type=int, default=2, help="rounds of the in-process shared/one-by-one comparison")
    opts = ap.parse_args()
    from rockdesign.bench.timing import machine_info
    from rockdesign.design_space.variants import parse_vary, variant_document, variant_toml
    with tempfile.TemporaryDirectory(prefix="bench_design_") as tmp:
        tmp = Path(tmp)
        base = tmp / "podium.toml"
        base.write_text(PROJECT, encoding="utf-8")
        raw = tomllib.loads(PROJECT)
        variables = [parse_vary(WIDTH, raw), parse_vary(HEIGHT, raw)]
        # warm the kernel cache once (not timed: both sides load the same compiled kernels)
        run(["check", str(_variant(tmp, raw, variables, (0, 0), variant_document, variant_toml)), "--no-pdf",
             "-o", str(tmp / "warm")], tmp)
        checks = {}
        for index in itertools.product(range(3), range(3)):
            path = _variant(tmp, raw, variables, index, variant_document, variant_toml)
            dt, code, _ = run(["check", str(path), "--no-pdf", "-o", str(tmp / f"check_{index[0]}{index[1]}")], tmp)
            verdict = json.loads((tmp / f"check_{index[0]}{index[1]}" / "results.json").read_text())["verdict"]
            checks[index] = {"seconds": dt, "verdict": verdict}
            print(f"check {index}: {dt:.1f} s {verdict}")
        dt9, code9, _ = run(["design", str(base), "--vary", WIDTH, "--vary", HEIGHT, "--no-pdf", "-o",
                             str(tmp / "grid3x3")], tmp)
        grid = json.loads((tmp / "grid3x3" / "design.json").read_text())
        print(f"design 3 × 3: {dt9:.1f} s")
        dt3, code3, _ = run(["design", str(base), "--vary", WIDTH, "--no-pdf", "-o", str(tmp / "grid1x3")], tmp)
        row = json.loads((tmp / "grid1x3" / "design.json").read_text())
        print(f"design 1 × 3: {dt3:.1f} s")
        together = shared_vs_one_by_one(base, tmp, opts.rounds)
    mismatches = [c["index"] for c in grid["cells"] if c["verdict"] != checks[tuple(c["index"])]["verdict"]]
    mismatches += [c["index"] for c in row["cells"] if c["verdict"] != checks[(c["index"][0], 0)]["verdict"]]
    sum9 = sum(c["seconds"] for c in checks.values())
    sum3 = sum(checks[(i, 0)]["seconds"] for i in range(3))
    result = {
        "benchmark": "design", "date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "machine": machine_info(),
        "project": "20-column podium, rigid superstructure, 11 ground motions (p695-ff/1a…11a at 0.4 g)",
        "variables": [WIDTH, HEIGHT],
        "checks": [{"index": list(k), **v} for k, v in checks.items()],
        "grid_3x3": {"seconds": dt9, "separate_checks_seconds": sum9, "ratio": dt9 / sum9,
                     "analyses_run": grid["analyses_run"], "analyses_saved_at_least": grid["analyses_saved"],
                     "verdicts": {"PASS": sum(c["verdict"] == "PASS" for c in grid["cells"]),
                                  "FAIL": sum(c["verdict"] == "FAIL" for c in grid["cells"])}},
        "grid_1x3": {"seconds": dt3, "separate_checks_seconds": sum3, "ratio": dt3 / sum3,
                     "analyses_run": row["analyses_run"], "analyses_saved_at_least": row["analyses_saved"]},
        "grid_3x3_shared_vs_one_by_one": together,
        "verdicts_equal": not mismatches, "mismatches": mismatches,
        "goal_ratio_3x3_at_most_0.6": dt9 / sum9 <= 0.6,
    }
    Path(opts.out).parent.mkdir(parents=True, exist_ok=True)
    Path(opts.out).write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    print(f"3 × 3: {dt9:.1f} s vs {sum9:.1f} s → ratio {dt9 / sum9:.2f}; 1 × 3: {dt3:.1f} s vs {sum3:.1f} s → "
          f"ratio {dt3 / sum3:.2f}; verdicts equal: {not mismatches}")
    if mismatches:
        raise SystemExit(f"verdicts differ from the checks at {mismatches}")
    if not together["cells_equal"]:
        raise SystemExit("the grid's cells differ between shared batches and one variant after the other")


def shared_vs_one_by_one(base: Path, tmp: Path, rounds: int) -> dict:
    """The 3 × 3 grid in this process, variants together (shared batches) and one after the other,
    alternating: seconds of each run, the ratio of the medians, the shared batches' counts."""
    import statistics

    from rockdesign.design_space.run import design
    from rockdesign.planar.kind import Planar
    shared_batches = Planar.grid_batches
    times = {"together": [], "one_by_one": []}
    cells = {}
    shared = None
    for k in range(rounds):
        for how in ("together", "one_by_one"):
            Planar.grid_batches = shared_batches if how == "together" else (lambda self: None)
            t0 = time.perf_counter()
            res = design(base, [WIDTH, HEIGHT])
            times[how].append(time.perf_counter() - t0)
            cells[how] = [{key: v for key, v in c.items() if key != "resumed"} for c in res.as_json()["cells"]]
            shared = res.grid.shared_batches or shared
            print(f"in-process 3 × 3, {how.replace('_', ' ')}: {times[how][-1]:.1f} s")
    Planar.grid_batches = shared_batches
    med = {how: statistics.median(v) for how, v in times.items()}
    return {"seconds": times, "ratio_together_over_one_by_one": med["together"] / med["one_by_one"],
            "shared_batches": shared, "cells_equal": cells["together"] == cells["one_by_one"]}


def _variant(tmp: Path, raw: dict, variables, index, variant_document, variant_toml) -> Path:
    doc, _ = variant_document(raw, variables, index)
    path = tmp / f"variant_{index[0]}{index[1]}.toml"
    path.write_text(variant_toml(doc), encoding="utf-8")
    return path


if __name__ == "__main__":
    main()
