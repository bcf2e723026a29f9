"""Spot check of a design chart: every cell's verdict against ``rockdesign check --no-pdf`` of that
variant written out as its own project file (a separate process per variant, as an engineer would run it).

    .venv/bin/python benchmarks/spot_check_design.py examples/podium_curved.toml DIR \\
        --vary podium.width=0.36m:0.52m:3 --vary podium.curvature=0.1:0.5:3 [--out results/x.json]

(a cylinder project likewise, e.g. ``--vary cylinder.diameter=0.7m:0.95m:6``).

DIR is the ``rockdesign design -o DIR`` folder of the same project and variables (its design.json is read).
Exit code 1 when a verdict differs.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("project")
    ap.add_argument("design_dir")
    ap.add_argument("--vary", action="append", required=True)
    ap.add_argument("--out", default=None)
    opts = ap.parse_args()
    from rockdesign.design_space.variants import parse_vary, variant_document, variant_toml
    from rockdesign.kinds import kind_of
    from rockdesign.library import load_project
    raw = tomllib.loads(Path(opts.project).read_text(encoding="utf-8"))
    alternatives = kind_of(load_project(opts.project)).key_alternatives    # as rockdesign design reads them
    variables = [parse_vary(v, raw, alternatives=alternatives) for v in opts.vary]
    grid = json.loads((Path(opts.design_dir) / "design.json").read_text(encoding="utf-8"))
    rows = []
    with tempfile.TemporaryDirectory(prefix="spot_check_") as tmp:
        tmp = Path(tmp)
        for cell in grid["cells"]:
            idx = tuple(cell["index"])
            if cell["verdict"] == "INVALID":
                rows.append({"index": list(idx), "design": "INVALID", "check": None, "equal": True})
                continue
            doc, _ = variant_document(raw, variables, idx)
            path = tmp / f"variant_{'_'.join(map(str, idx))}.toml"
            path.write_text(variant_toml(doc), encoding="utf-8")
            out = tmp / f"check_{'_'.join(map(str, idx))}"
            t0 = time.perf_counter()
            proc = subprocess.run([sys.executable, "-m", "rockdesign.cli", "check", str(path), "--no-pdf", "-o",
                                   str(out)], env=dict(os.environ, PYTHONPATH=str(ROOT)), capture_output=True,
                                  text=True)
            dt = time.perf_counter() - t0
            if not (out / "results.json").is_file():
                raise SystemExit(f"check of {cell['labels']} failed ({proc.returncode}): {proc.stderr[-2000:]}")
            res = json.loads((out / "results.json").read_text())
            row = {"index": list(idx), "labels": cell["labels"], "design": cell["verdict"], "check": res["verdict"],
                   "equal": res["verdict"] == cell["verdict"], "check_seconds": dt,
                   "n_unacceptable": [cell["n_unacceptable"], res["acceptance"]["n_unacceptable"]],
                   "acmr": [cell["acmr"], res["acceptance"]["acmr"]]}
            rows.append(row)
            print(f"{cell['labels']}: design {cell['verdict']}, check {res['verdict']} ({dt:.0f} s)", flush=True)
    bad = [r for r in rows if not r["equal"]]
    summary = {"project": opts.project, "variables": opts.vary, "cells": rows, "all_equal": not bad}
    if opts.out:
        Path(opts.out).write_text(json.dumps(summary, indent=1) + "\n", encoding="utf-8")
    print(f"{len(rows)} cells, {len(bad)} differ")
    raise SystemExit(1 if bad else 0)


if __name__ == "__main__":
    main()
