"""Benchmark: the full design check of the podium example with the overturning fragility and the perturbation
ensembles (issue 13), stage by stage (the engine speed and first-run budgets are in bench_check.py).


Budget (issue "rockdesign check"): warm run under 15 s, first (JIT-compiling) run under 90 s on the
2-core machine; with the overturning fragility and the perturbation ensembles (issue 13, default
``ensemble_size = 8``) the warm run stays under 30 s.  The stages of one in-process check are timed
too (ensembles against the nominal suite analysis of the same process, fragility fits + bootstrap).
Cold run (empty numba cache), warm run and the suite-analysis ratio against scipy are measured as in
bench_check.py (its ``timed_check`` and ``suite_ratio``).

    .venv/bin/python benchmarks/bench_check_fragility.py [--project examples/podium_flat.toml] [--out benchmarks/results/check_fragility.json]
"""
from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

from bench_check import CPU_SECONDS, first_run, reported_suite_ratio, timed_check, write_result  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[1]


def without_ensembles(text: str) -> str:
    """The project text with ``[analysis] ensemble_size = 0``."""
    lines = text.splitlines()
    if "[analysis]" in (line.strip() for line in lines):
        k = next(i for i, line in enumerate(lines) if line.strip() == "[analysis]")
        lines.insert(k + 1, "ensemble_size = 0")
    else:
        lines += ["", "[analysis]", "ensemble_size = 0"]
    return "\n".join(lines) + "\n"


def stage_times(project: str) -> dict:
    """Seconds per stage of one in-process check (kernels warm), from the progress callback."""
    from rockdesign.planar.checks.check import run_check
    from rockdesign.acceptance.fragility import check_fragility
    from rockdesign.acceptance.scans import SCAN_RATIO
    from rockdesign.library import load_project
    proj = load_project(ROOT / project)
    starts = {}
    t0 = time.perf_counter()
    result = run_check(proj, progress=lambda stage, done, total: starts.setdefault(stage, time.perf_counter()))
    end = time.perf_counter()
    names = list(starts)
    stages = {name: (starts[names[k + 1]] if k + 1 < len(names) else end) - starts[name]
              for k, name in enumerate(names)}
    t1 = time.perf_counter()
    check_fragility(result.records, proj.analysis, empirical=(result.statistics["n_overturned"], len(result.records)),
                    stripe_ratio=SCAN_RATIO)
    fits = time.perf_counter() - t1
    suite = next(v for k, v in stages.items() if k.startswith("suite analysis"))
    ens = next((v for k, v in stages.items() if k.startswith("perturbation ensembles")), None)
    return {"total_s": end - t0, "stages_s": stages, "fragility_fits_and_bootstrap_s": fits,
            "ensemble_size": proj.analysis.ensemble_size,
            "ensemble_over_suite_analysis": None if ens is None else ens / suite,
            "fragility": {k: (result.fragility or {}).get(k) for k in ("median", "beta", "median_ci90", "beta_ci90",
                                                                     "method", "n_censored", "p_overturn_design")},
            "collapse_margin": {k: (result.collapse_margin or {}).get(k) for k in ("CMR", "ACMR", "beta_tot",
                                                                               "ACMR10", "ACMR20",
                                                                               "p_collapse_design", "passed")},
            "ensemble": {k: (result.ensemble or {}).get(k) for k in ("p_overturn", "n_not_robust",
                                                                    "records_not_robust")}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default="examples/podium_flat.toml")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "check_fragility.json"))
    ap.add_argument("--skip-cold", action="store_true", help="only the warm run")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as work:
        cold = first_run(args.project, work, cache, args.skip_cold, budget=90)
        warm, code = timed_check(args.project, str(Path(work) / "warm"), cache)
        warm_cpu = CPU_SECONDS["last"]
        print(f"warm run: {warm:.1f} s  (budget 30 s with fragility and ensembles), verdict exit code {code}; "
              f"CPU {warm_cpu:.1f} s (÷ {os.cpu_count()} cores = {warm_cpu / os.cpu_count():.1f} s; load average "
              f"{os.getloadavg()[0]:.1f})")
        # the same warm check without the perturbation ensembles, under the same load
        plain = Path(work) / "no_ensembles.toml"
        plain.write_text(without_ensembles((ROOT / args.project).read_text()))
        warm_plain, _ = timed_check(str(plain), str(Path(work) / "plain"), cache)
        plain_cpu = CPU_SECONDS["last"]
        print(f"warm run without ensembles: {warm_plain:.1f} s, CPU {plain_cpu:.1f} s")
    stages = stage_times(args.project)
    for name, sec in stages["stages_s"].items():
        print(f"  {sec:6.1f} s  {name}")
    print(f"  fragility fits + bootstrap: {stages['fragility_fits_and_bootstrap_s']:.2f} s; ensembles / suite "
          f"analysis: {stages['ensemble_over_suite_analysis'] or 0:.1f}x")
    write_result(args.out, {"benchmark": "check", "project": args.project, "first_run_s": cold, "warm_run_s": warm,
                            "warm_run_cpu_s": warm_cpu, "warm_run_without_ensembles_s": warm_plain,
                            "warm_run_without_ensembles_cpu_s": plain_cpu, "budget_first_s": 90,
                            "budget_warm_s": 30, "stages": stages,
                            "suite_rha_vs_scipy": reported_suite_ratio(args.project)})


if __name__ == "__main__":
    main()
