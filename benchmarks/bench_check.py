"""Benchmark: the full design check of the podium example (44 records, PDF included).

Budget (issue "rockdesign check"): warm run under 15 s, first (JIT-compiling) run under 90 s on the
2-core machine.  The cold run uses an empty numba cache directory (NUMBA_CACHE_DIR), so nothing of
the repository's cache is reused; the warm run repeats it with that cache filled.  As a ratio
against a baseline measured in the same run, the suite-analysis stage (the nonlinear RHA of the
records) is also timed for a few records with the independent scipy implementation
(solve_ivp DOP853, same equations and events, restarted at impacts).

    .venv/bin/python benchmarks/bench_check.py [--project examples/podium_flat.toml] [--out benchmarks/results/check.json]
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def timed_check(project: str, out_dir: str, cache_dir: str) -> tuple[float, int]:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    exe = str(Path(sys.executable).with_name("rockdesign"))
    t0 = time.perf_counter()
    proc = subprocess.run([exe, "check", project, "-o", out_dir], env=env, cwd=ROOT, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if proc.returncode not in (0, 1):
        raise SystemExit(f"check failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
    return dt, proc.returncode


def suite_ratio(project: str, n_records: int = 3) -> dict:
    """Our engine vs the scipy reference on the first records of the project's suite (same model)."""
    from rockdesign.checks.check import _excitation
    from rockdesign.design.quantities import design_quantities
    from rockdesign.dynamics.simulate import simulate
    from rockdesign.motions.config import resolve_motions
    from rockdesign.project import load_project
    from rockdesign.reference.scipy_engine import simulate_scipy
    proj = load_project(ROOT / project)
    q = design_quantities(proj.system)
    suite = resolve_motions(_excitation(proj), gravity=proj.system.g,
                            uplift_acceleration=q["uplift_acceleration"].value)
    motions = [r.motion for r in suite.records[:n_records]]
    ours = 0.0
    for m in motions:   # warm-up then timed
        simulate(proj.system, m, structure="podium-2dof" if proj.system.has_elastic_superstructure else "auto",
                 record_history=False)
    rows = []
    for m in motions:
        t0 = time.perf_counter()
        r = simulate(proj.system, m, structure="podium-2dof" if proj.system.has_elastic_superstructure else "auto",
                     record_history=False, rtol=1e-10)
        t_ours = time.perf_counter() - t0
        t0 = time.perf_counter()
        ref = simulate_scipy(proj.system, m, method="DOP853", rtol=1e-10, atol=1e-12,
                             t_end=m.duration + proj.analysis.free_vibration)
        t_ref = time.perf_counter() - t0
        ours += t_ours
        rows.append({"record": m.name, "ours_s": t_ours, "scipy_s": t_ref, "ratio": t_ref / t_ours,
                     "theta_max_ours": r.theta_max, "theta_max_scipy": ref.theta_max})
    return {"records": rows, "median_ratio": sorted(x["ratio"] for x in rows)[len(rows) // 2]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default="examples/podium_flat.toml")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "check.json"))
    ap.add_argument("--skip-cold", action="store_true", help="only the warm run")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as work:
        cold = None
        if not args.skip_cold:
            cold, _ = timed_check(args.project, str(Path(work) / "cold"), cache)
            print(f"first run (empty numba cache): {cold:.1f} s  (budget 90 s)")
        else:
            timed_check(args.project, str(Path(work) / "fill"), cache)
        warm, code = timed_check(args.project, str(Path(work) / "warm"), cache)
        print(f"warm run: {warm:.1f} s  (budget 15 s), verdict exit code {code}")
    ratio = suite_ratio(args.project)
    print(f"suite RHA, ours vs scipy DOP853 (same equations/events, rtol 1e-10): median ratio "
          f"{ratio['median_ratio']:.0f}x")
    result = {"benchmark": "check", "project": args.project, "first_run_s": cold, "warm_run_s": warm,
              "budget_first_s": 90, "budget_warm_s": 15, "suite_rha_vs_scipy": ratio,
              "date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
              "machine": {"platform": platform.platform(), "processor": platform.processor(), "cpus": os.cpu_count(),
                          "python": platform.python_version()}}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(result, indent=2) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
