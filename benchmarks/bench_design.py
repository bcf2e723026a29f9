"""Benchmark: ``rockdesign design`` against the separate ``rockdesign check --no-pdf`` runs of its valid
variants, in the same run (the machine is shared: only the ratio is compared).  The grid runs as a user runs
it: coarse to fine, with the perturbation draws of every passing variant (robust cells).

Rows (``--grid``):

- ``3x3``: a 20-column podium with a rigid superstructure under 11 far-field ground motions (p695-ff/1a …
  11a at 0.4 g, the ASCE 7-22 minimum), varied in column width (0.5, 0.65, 0.8 m) and height (2, 2.5, 3 m);
- ``5x5``: examples/podium_asce7_22.toml (22 ground motions scaled per ASCE 7-22 §16.2, elastic
  superstructure) over podium.width = 0.40 … 0.56 m and podium.height = 2.6 … 3.4 m, five values each, every
  cell analysed (``--every-cell``): what a fully analysed chart costs against its separate checks (goal ≤ 0.5);
- ``10x10``: examples/podium_curved.toml (22 ground motions, elastic superstructure) over
  podium.width = 0.30 … 0.60 m and podium.curvature = 0.1 … 0.6, ten values each (long: some 100 separate
  checks of 10–15 s each on 2 cores), coarse to fine with the inference rule (goal ≤ 0.2).

Each row also checks the design answer: every analysed cell has a distance to the flip, no cell left out
touches an analysed cell of another category, and the recommendation's tolerance neighbours (each varied key ±
its tolerance, listed in design.json) pass in separate ``rockdesign check`` runs of their own project files.

Each valid variant is written out as its own project file and checked by a separate process, as an engineer
would; the grid is one ``design --no-pdf`` process.  Every analysed cell's verdict is compared with its check's
verdict, and a robust cell's check must say robust (the benchmark fails otherwise).  With ``--rounds N`` the
3 × 3 grid also runs in this process N times with its variants together (shared batches) and one after the
other, alternating: the ratio of the medians and the cells compared (they must be equal).

    .venv/bin/python benchmarks/bench_design.py [--grid 3x3|10x10|all] [--out benchmarks/results/design.json]
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


GRIDS = {"3x3": (None, [WIDTH, HEIGHT], 0.2, False),
         "5x5": (ROOT / "examples" / "podium_asce7_22.toml",
                 ["podium.width=0.40m:0.56m:5", "podium.height=2.6m:3.4m:5"], 0.5, True),
         "10x10": (ROOT / "examples" / "podium_curved.toml",
                   ["podium.width=0.30m:0.60m:10", "podium.curvature=0.1:0.6:10"], 0.2, False)}
"""name → (project file or None for :data:`PROJECT`, the variables, the goal for the wall-time ratio, every
cell)."""


def grid_row(name: str, tmp: Path) -> dict:
    """One row: the grid against the separate checks of its valid variants (seconds, ratio, verdicts)."""
    from rockdesign.design_space.variants import parse_vary, variant_toml, variants
    from rockdesign.planar.kind import Planar
    source, vary, goal, every = GRIDS[name]
    folder = tmp / name
    folder.mkdir()
    base = folder / "project.toml"
    text = PROJECT if source is None else source.read_text(encoding="utf-8")
    base.write_text(text, encoding="utf-8")
    raw = tomllib.loads(text)
    variables = [parse_vary(v, raw, alternatives=Planar.key_alternatives) for v in vary]   # as rockdesign design
    cells = variants(raw, variables, file=str(base))
    checks = {}
    for v in cells:
        if v.project is None:
            continue
        path = folder / ("variant_" + "_".join(map(str, v.index)) + ".toml")
        path.write_text(variant_toml(v.raw), encoding="utf-8")
        out = folder / ("check_" + "_".join(map(str, v.index)))
        dt, _, _ = run(["check", str(path), "--no-pdf", "-o", str(out)], folder)
        res = json.loads((out / "results.json").read_text())
        checks[tuple(v.index)] = {"seconds": dt, "verdict": res["verdict"], "robust": res.get("verdict_robust")}
        print(f"{name} check {v.index}: {dt:.1f} s {res['verdict']}")
    args = ["design", str(base), "--no-pdf", "-o", str(folder / "grid")] + (["--every-cell"] if every else [])
    for v in vary:
        args += ["--vary", v]
    dt, _, _ = run(args, folder)
    grid = json.loads((folder / "grid" / "design.json").read_text())
    answer = design_answer(grid, raw, variables, folder)
    analysed = [c for c in grid["cells"] if c.get("analysed", True) and tuple(c["index"]) in checks]
    mismatches = [c["index"] for c in analysed if c["verdict"] != checks[tuple(c["index"])]["verdict"]]
    not_robust = [c["index"] for c in analysed if c.get("robust") and not checks[tuple(c["index"])]["robust"]]
    total = sum(c["seconds"] for c in checks.values())
    rec = grid["recommended"]
    row = {"variables": vary, "seconds": dt, "separate_checks_seconds": total, "ratio": dt / total,
           "goal_ratio": goal, "goal_met": dt / total <= goal, "valid_variants": len(checks),
           "cells_analysed": len(analysed), "analyses_run": grid["analyses_run"],
           "analyses_saved_at_least": grid["analyses_saved"],
           "regions": {k: sum(1 for c in grid["cells"] if _region(c) == k)
                       for k in ("robust PASS", "fragile PASS", "FAIL", "not analysed", "other")},
           "recommended": rec and {"labels": rec["labels"], "robust": rec["robust"],
                                   "check_robust": checks.get(tuple(rec["index"]), {}).get("robust")},
           "verdicts_equal": not mismatches, "mismatches": mismatches, "robust_cells_not_robust_in_check": not_robust,
           **answer, "checks": [{"index": list(k), **v} for k, v in checks.items()]}
    print(f"{name}: {dt:.1f} s vs {total:.1f} s → ratio {dt / total:.3f} (goal ≤ {goal}); "
          f"{len(analysed)} cells analysed, verdicts equal: {not mismatches}; recommendation's neighbours pass in "
          f"separate checks: {answer['neighbours_pass_in_separate_checks']}")
    return row


def design_answer(grid: dict, raw: dict, variables, folder: Path) -> dict:
    """What the design answer must satisfy (SPEC §15): a flip margin in every analysed cell, no cell left out
    beside an analysed cell of another category, and the recommendation's tolerance neighbours passing in
    separate checks of their own project files."""
    from rockdesign.design_space.refine import category, neighbours
    from rockdesign.design_space.variants import neighbour_variant, variant_toml
    cells = {tuple(c["index"]): c for c in grid["cells"]}
    shape = tuple(len(v["values"]) for v in grid["variables"])
    analysed = [c for c in grid["cells"] if c.get("analysed", True) and c["verdict"] in ("PASS", "FAIL")]
    edges = [c["labels"] for i, c in cells.items() if not c.get("analysed", True)
             and any(category(cells[n]) != c["between"] for n in neighbours(i, shape) if n in cells)]
    rec = grid["recommended"]
    separate = []
    for n, hood in enumerate((rec or {}).get("neighbourhood") or []):
        variant = neighbour_variant(raw, variables, tuple(rec["index"]), hood["key"], hood["values"][hood["key"]],
                                    file=str(folder / "project.toml"))
        path = folder / f"neighbour_{n}.toml"
        path.write_text(variant_toml(variant.raw), encoding="utf-8")
        out = folder / f"neighbour_check_{n}"
        dt, _, _ = run(["check", str(path), "--no-pdf", "-o", str(out)], folder)
        res = json.loads((out / "results.json").read_text())
        separate.append({"labels": hood["labels"], "design": hood["verdict"], "check": res["verdict"],
                         "n_unacceptable": res["acceptance"]["n_unacceptable"], "acmr": res["acceptance"]["acmr"],
                         "flip_margin": res["acceptance"]["flip_margin"], "seconds": dt})
        print(f"neighbour {hood['labels']}: design {hood['verdict']}, separate check {res['verdict']} "
              f"({res['acceptance']['n_unacceptable']} unacceptable, ACMR {res['acceptance']['acmr']})")
    cell = cells.get(tuple(rec["index"])) if rec else None
    return {"flip_margin_in_every_analysed_cell": all(c.get("flip_margin") is not None for c in analysed),
            "recommended_flip_margin": cell and cell.get("flip_margin"),
            "recommended_tolerance_robust": rec and rec.get("tolerance_robust"),
            "cells_inferred": (grid.get("settings") or {}).get("cells_inferred"),
            "inference_audit": (grid.get("settings") or {}).get("inference_audit"),
            "inferred_beside_another_category": edges,
            "inference_study": inference_study(grid),
            "neighbours_in_separate_checks": separate,
            "neighbours_pass_in_separate_checks": bool(separate) and all(r["check"] == "PASS" for r in separate)}


def inference_study(grid: dict, thresholds=(1.0, 1.1, 1.2, 1.25, 1.3, 1.5)) -> list[dict]:
    """How the inference rule's threshold FAR would have done on this chart: for each threshold, the analysed cells
    whose coarser corners (all analysed) agree and are far from their flip — the cells the rule would have left
    out — and how many of them the analysis shows to be of another category (docs/design.md "Inference only where
    it is safe")."""
    from rockdesign.design_space.refine import category, corners, level_strides, levels
    cells = {tuple(c["index"]): c for c in grid["cells"]}
    shape = tuple(len(v["values"]) for v in grid["variables"])
    rows = []
    for far in thresholds:
        left, wrong = 0, []
        for level, indexes in enumerate(levels(shape)):
            for i in indexes if level else []:
                around = [cells[c] for c in corners(i, shape, level_strides(shape, level - 1))]
                found = {category(c) for c in around}
                if not all(c.get("analysed", True) for c in around) or len(found) != 1 or not cells[i].get(
                        "analysed", True):
                    continue
                (cat,) = found
                if cat not in ("robust PASS", "FAIL") or not all(
                        (c["flip_margin"] or 0.0) >= far if c["verdict"] == "PASS"
                        else c["flip_margin"] is not None and c["flip_margin"] <= 1 / far for c in around):
                    continue
                left += 1
                if category(cells[i]) != cat:
                    wrong.append({"labels": cells[i]["labels"], "is": category(cells[i]), "inferred": cat})
        rows.append({"far": far, "would_leave_out": left, "of_another_category": len(wrong), "cells": wrong})
    return rows


def _region(cell: dict) -> str:
    if not cell.get("analysed", True):
        return "not analysed"
    if cell["verdict"] == "PASS":
        return "robust PASS" if cell.get("robust") else "fragile PASS"
    return "FAIL" if cell["verdict"] == "FAIL" else "other"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "design.json"))
    ap.add_argument("--grid", choices=[*GRIDS, "all"], default="3x3", help="which rows to run")
    ap.add_argument("--rounds", type=int, default=0, help="rounds of the in-process shared/one-by-one comparison")
    opts = ap.parse_args()
    from rockdesign.bench.timing import machine_info
    from rockdesign.design_space.variants import parse_vary, variant_document, variant_toml
    from rockdesign.planar.kind import Planar
    names = list(GRIDS) if opts.grid == "all" else [opts.grid]
    rows = {}
    with tempfile.TemporaryDirectory(prefix="bench_design_") as tmp:
        tmp = Path(tmp)
        base = tmp / "podium.toml"
        base.write_text(PROJECT, encoding="utf-8")
        raw = tomllib.loads(PROJECT)
        variables = [parse_vary(v, raw, alternatives=Planar.key_alternatives) for v in (WIDTH, HEIGHT)]
        # warm the kernel cache once (not timed: both sides load the same compiled kernels)
        run(["check", str(_variant(tmp, raw, variables, (0, 0), variant_document, variant_toml)), "--no-pdf",
             "-o", str(tmp / "warm")], tmp)
        for name in names:
            rows[name] = grid_row(name, tmp)
        together = shared_vs_one_by_one(base, tmp, opts.rounds) if opts.rounds else None
    out = Path(opts.out)
    previous = json.loads(out.read_text()) if out.exists() else {}
    result = {
        "benchmark": "design", "date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "machine": machine_info(),
        "grids": {**(previous.get("grids") or {}), **rows},
        "grid_3x3_shared_vs_one_by_one": together or previous.get("grid_3x3_shared_vs_one_by_one"),
    }
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    bad = [n for n, r in rows.items() if r["mismatches"] or r["robust_cells_not_robust_in_check"]
           or r["inferred_beside_another_category"] or not r["flip_margin_in_every_analysed_cell"]
           or any(x["design"] != x["check"] for x in r["neighbours_in_separate_checks"])]
    if bad:
        raise SystemExit(f"cells differ from their checks in {bad}")
    if together is not None and not together["cells_equal"]:
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
            Planar.grid_batches = shared_batches if how == "together" else (lambda self, executor=None: None)
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
