"""Benchmark: the full design check of the podium example (44 records, PDF included).

First (JIT-compiling) run < 45 s on the 2-core machine.  ``--pairs N`` (default 5) runs ``check`` and
``check --no-pdf`` alternately, warm, and reports the median ratio of the pairs (what the report adds),
and the report's stages are timed in this process (figures, HTML, PDF).  ``--baseline-root DIR`` also times another checkout's ``check`` (e.g. main) warm, runs
alternating with ours in this process (the machine is shared: best of ``--repeats``), and compares
verdict, counts and classes of the two results.json.  The cold run uses an empty numba cache directory (NUMBA_CACHE_DIR), so nothing of
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


CPU_SECONDS = {}
"""CPU seconds (user + system) of the last timed check: on a machine shared with other jobs the wall time
grows with the load, the CPU time much less; CPU/cores is the wall time of an idle machine at best."""


def timed_check(project: str, out_dir: str, cache_dir: str | None, root: Path = ROOT,
                extra: tuple[str, ...] = ()) -> tuple[float, int]:
    """Seconds and exit code of ``rockdesign check project -o out_dir [extra]`` run from the checkout ``root``
    (its CPU seconds in :data:`CPU_SECONDS`)."""
    import resource
    env = dict(os.environ, PYTHONPATH=str(root))
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = cache_dir
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "rockdesign.cli", "check", project, "-o", out_dir, *extra], env=env,
                          cwd=root, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    CPU_SECONDS["last"] = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"check failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
    announced = [ln.strip() for ln in proc.stderr.splitlines() if "compil" in ln]
    if announced:
        print("  " + " | ".join(announced))
    return dt, proc.returncode


def same_outcome(ours: Path, baseline: Path) -> dict:
    """Verdict, counts, classes and per-record overturning of two results.json files."""
    a = json.loads(ours.read_text())
    b = json.loads(baseline.read_text())
    keys = ("n_records", "n_overturned", "n_overturned_dynamic", "n_exceeded_capacity", "n_false_negative", "classes")
    out = {"verdict": [a["verdict"], b["verdict"]],
           "same_verdict": a["verdict"] == b["verdict"],
           "same_counts_and_classes": all(a["summary"][k] == b["summary"][k] for k in keys),
           "same_record_classes": [r["class"] for r in a["records"]] == [r["class"] for r in b["records"]],
           "same_checks": [(c.get("name"), c.get("passed")) for c in a["checks"]]
           == [(c.get("name"), c.get("passed")) for c in b["checks"]],
           "median_margin": [a["summary"].get("median_margin"), b["summary"].get("median_margin")],
           "max_theta_max_over_theta_c": [a["summary"]["max_theta_max_over_theta_c"],
                                          b["summary"]["max_theta_max_over_theta_c"]]}
    return out


def suite_ratio(project: str, n_records: int = 3) -> dict:
    """Our engine vs the scipy reference on the first records of the project's suite (same model)."""
    from rockdesign.planar.checks.check import _excitation
    from rockdesign.planar.design.quantities import design_quantities
    from rockdesign.planar.dynamics.simulate import simulate
    from rockdesign.motions.config import resolve_motions
    from rockdesign.library import load_project
    from rockdesign.bench.baseline.scipy_engine import simulate_scipy
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


def first_run(project: str, work: str, cache: str, skip: bool, budget: float) -> float | None:
    """Seconds of a check with an empty numba cache (``cache``), which it fills; None (cache filled
    untimed) with ``skip``."""
    if skip:
        timed_check(project, str(Path(work) / "fill"), cache)
        return None
    cold, _ = timed_check(project, str(Path(work) / "cold"), cache)
    print(f"first run (empty numba cache): {cold:.1f} s  (budget {budget:g} s)")
    return cold


def reported_suite_ratio(project: str) -> dict:
    """:func:`suite_ratio`, printed."""
    ratio = suite_ratio(project)
    print(f"suite RHA, ours vs scipy DOP853 (same equations/events, rtol 1e-10): median ratio "
          f"{ratio['median_ratio']:.0f}x")
    return ratio


def write_result(path, result: dict) -> None:
    """Write a benchmark's JSON with the load average, date and machine it was measured on."""
    result = dict(result, load_average=list(os.getloadavg()),
                  date=datetime.now(timezone.utc).isoformat(timespec="seconds"),
                  machine={"platform": platform.platform(), "processor": platform.processor(),
                           "cpus": os.cpu_count(), "python": platform.python_version()})
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(json.dumps(result, indent=2) + "\n")
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default="examples/podium_flat.toml")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "check.json"))
    ap.add_argument("--skip-cold", action="store_true", help="only the warm run")
    ap.add_argument("--baseline-root", default=None, help="another checkout (e.g. /work/main) timed alternately")
    ap.add_argument("--repeats", type=int, default=2, help="warm runs (best is reported)")
    ap.add_argument("--pairs", type=int, default=5, help="paired runs of check and check --no-pdf (0: none)")
    args = ap.parse_args()
    baseline = None
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as work:
        cold = first_run(args.project, work, cache, args.skip_cold, budget=45)
        warms, base_warms = [], []
        if args.baseline_root:   # fill the baseline's own cache first
            timed_check(args.project, str(Path(work) / "base-fill"), None, Path(args.baseline_root))
        for k in range(args.repeats):
            warm_k, code = timed_check(args.project, str(Path(work) / "warm"), cache)
            warms.append(warm_k)
            print(f"warm run {k + 1}: {warm_k:.1f} s, verdict exit code {code}")
            if args.baseline_root:
                b_k, _ = timed_check(args.project, str(Path(work) / "base"), None, Path(args.baseline_root))
                base_warms.append(b_k)
                print(f"baseline warm run {k + 1}: {b_k:.1f} s")
        warm = min(warms)
        print(f"warm run: {warm:.1f} s (best of {len(warms)})")
        cost = report_cost(args.project, work, cache, args.pairs) if args.pairs else None
        if args.baseline_root:
            baseline = {"root": args.baseline_root, "warm_run_s": min(base_warms), "runs_s": base_warms,
                        "ratio_baseline_over_ours": min(base_warms) / warm,
                        "outcome": same_outcome(Path(work) / "warm" / "results.json",
                                                Path(work) / "base" / "results.json")}
            print(f"baseline warm {min(base_warms):.1f} s → ours is {baseline['ratio_baseline_over_ours']:.2f}× "
                  f"faster; same verdict/counts/classes: {baseline['outcome']}")
    write_result(args.out, {"benchmark": "check", "project": args.project, "first_run_s": cold, "warm_run_s": warm,
                            "warm_runs_s": warms, "budget_first_s": 45, "baseline": baseline,
                            "report_cost": cost, "report_stages_in_process": report_stages(args.project),
                            "suite_rha_vs_scipy": reported_suite_ratio(args.project)})


def report_cost(project: str, work: str, cache: str, pairs: int) -> dict:
    """``check`` against ``check --no-pdf`` (warm), run alternately ``pairs`` times: the median over the
    pairs of the wall-time and CPU-time ratios (the goal: the report adds at most half, ratio ≤ 1.5)."""
    import statistics
    rows = []
    for k in range(pairs):
        a, _ = timed_check(project, str(Path(work) / "pdf"), cache)
        a_cpu = CPU_SECONDS["last"]
        b, _ = timed_check(project, str(Path(work) / "nopdf"), cache, extra=("--no-pdf",))
        b_cpu = CPU_SECONDS["last"]
        rows.append({"check_s": a, "no_pdf_s": b, "check_cpu_s": a_cpu, "no_pdf_cpu_s": b_cpu})
        print(f"pair {k + 1}: check {a:.1f} s ({a_cpu:.1f} CPU-s), --no-pdf {b:.1f} s ({b_cpu:.1f} CPU-s)")
    wall = statistics.median(r["check_s"] / r["no_pdf_s"] for r in rows)
    cpu = statistics.median(r["check_cpu_s"] / r["no_pdf_cpu_s"] for r in rows)
    print(f"check / --no-pdf: wall {wall:.2f}×, CPU {cpu:.2f}× (median of {pairs} pairs)")
    return {"pairs": rows, "wall_ratio_median": wall, "cpu_ratio_median": cpu}


def report_stages(project: str) -> dict:
    """The report's stages timed in this process after one check (process CPU seconds, after a warm-up
    render, so imports and fonts are not counted): making the figures, drawing them (SVG), the HTML and
    the PDF (WeasyPrint, figures included); and whether WeasyPrint subsets fonts with HarfBuzz (the
    system library libharfbuzz-subset0) or fontTools."""
    import time as _time

    import rockdesign.library as rd
    from rockdesign.report import render
    from rockdesign.planar.report import report as planar_report
    proj = rd.load_project(ROOT / project)
    result = rd.run_check(proj, progress=False)
    with tempfile.TemporaryDirectory() as tmp:       # (a first render: imports and fonts not counted)
        render.html_to_pdf("<p>warm-up</p>", Path(tmp) / "warm.pdf")
    times = {}

    def timed(name, call, *args):
        t = _time.process_time()
        value = call(*args)
        times[name] = _time.process_time() - t
        return value

    made = timed("make_figures_cpu_s", planar_report.make_figures, result)
    html_of = timed("context_cpu_s", planar_report.html_renderer, result)
    svgs = timed("draw_figures_cpu_s", planar_report.draw_figures, made)
    html = timed("html_cpu_s", html_of, svgs)
    with tempfile.TemporaryDirectory() as tmp:
        timed("pdf_cpu_s", render.html_to_pdf, html, Path(tmp) / "report.pdf")
    from ctypes.util import find_library    # (the library WeasyPrint subsets fonts with when it is installed)
    harfbuzz_subset = find_library("harfbuzz-subset")
    out = {**times, "figures": len(svgs), "font_subsetting": "harfbuzz" if harfbuzz_subset is not None else "fonttools"}
    print("report stages (CPU-s): " + ", ".join(f"{k.removesuffix('_cpu_s')} {v:.2f}" for k, v in times.items())
          + f" ({len(svgs)} figures; fonts subset by {out['font_subsetting']})")
    return out


if __name__ == "__main__":
    main()
