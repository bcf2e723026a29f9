"""Benchmark: the full 801 × 401 rocking spectrum of the Housner block (thesis Fig 3.19) in one command.

Goal (issue "rocking spectra at scale"): the 321 201 nonlinear analyses of one spectrum — days of
MATLAB work in the thesis — in under 60 s on this 2-core machine, and scaling over dask workers.

Measured, in one run:

1. ``rockdesign spectrum`` end to end (a subprocess: imports, kernel load, 321 201 analyses,
   Polyakov's line, lines, npz/json, PNG/SVG figures) for the thesis block B1 (2H = 3 m, 2B = 0.3 m,
   λ = 1/3, exact EOM, rtol 1e-10) under the antisymmetric Ricker wavelet on the thesis grid
   ω_p/p 0.5…12 (801) × a_p/(g tan α) 0…12 (401); wall time and time per analysis.
2. Baselines on random samples of the same grid, as ratios measured now: the same analyses without
   the early stop (full 10 s of free vibration), one ``simulate()`` call per analysis from Python,
   and the independent scipy implementation (solve_ivp DOP853, same equations and events).
3. dask.distributed scaling: a LocalCluster of 1 and of 2 single-threaded worker processes on a
   201 × 101 sub-grid (compute time without cluster start-up), checked bit for bit against the
   in-process result.

    .venv/bin/python benchmarks/bench_spectrum.py [OUT.json] [--quick] [--no-dask]

``--quick`` runs a 201 × 101 grid instead of the full one (for trying the script, not for numbers).
Results are printed and written as JSON (default ``benchmarks/results/spectrum.json``).
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

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
BLOCK_TOML = """
[project]
name = "Housner block B1 (thesis Table 3.4, Fig 3.19)"
[column]
height = "3.0 m"
width = "0.3 m"
mass = "1 t"
mass_distribution = 0.3333333333333333
[analysis]
rtol = 1e-10
"""


def _machine() -> dict:
    import numba
    return {"cpus": os.cpu_count(), "platform": platform.platform(), "python": platform.python_version(),
            "numba": numba.__version__, "numpy": np.__version__, "load_average": list(os.getloadavg())}


def cli_run(project: Path, out: Path, x: str, y: str) -> dict:
    """``rockdesign spectrum`` in a subprocess; returns wall time and the timings of summary.json."""
    exe = str(Path(sys.executable).with_name("rockdesign"))
    cmd = [exe, "spectrum", str(project), "--pulse", "ricker-anti", "--x", x, "--y", y, "-o", str(out), "-q"]
    import resource
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    if proc.returncode != 0:
        raise SystemExit(f"rockdesign spectrum failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
    s = json.loads((out / "summary.json").read_text())
    n = s["results"]["n_analyses"]
    return {"command": " ".join(cmd[1:]), "analyses": n, "wall_s": wall, "cpu_s": cpu,
            "cpu_per_analysis_ms": 1e3 * cpu / n, "cpu_utilisation": cpu / wall,
            "per_analysis_ms_wall": 1e3 * wall / n, "compute_s": s["timings"]["compute_s"],
            "per_analysis_ms_compute": s["timings"]["per_analysis_ms"], "warm_up_s": s["timings"]["warm_up_s"],
            "postprocess_s": s["timings"]["postprocess_s"], "figures_s": s["timings"]["figures_s"],
            "threads": s["execution"].get("threads"), "chunks": s["execution"]["chunks"],
            "n_overturned": s["results"]["n_overturned"], "status_counts": s["results"]["status_counts"],
            "mean_steps": s["results"]["mean_steps"], "goal_s": 60.0, "goal_met": wall < 60.0}


def baselines(n_sample: int, n_python: int, n_scipy: int, seed: int = 0) -> dict:
    """Cost per analysis of the spectrum kernel vs full-length runs, Python simulate() calls and scipy."""
    from rockdesign.planar.dynamics.batch import batch_options
    from rockdesign.planar.dynamics.simulate import simulate
    from rockdesign.motions.motion import pulse_motion
    from rockdesign.bench.baseline.scipy_engine import simulate_scipy
    from rockdesign.planar.spectra.kernel import OUT_STEPS, pulse_points, warm_up
    from rockdesign.planar.spectra.spectrum import SpectrumRequest, prepare
    from rockdesign.planar.system import Column, RockingSystem

    system = RockingSystem("B1", "column", Column(1.5, 0.15, 1000.0, 1 / 3))
    req = SpectrumRequest("ricker-anti")
    _, sp, kind, shape, periods, amplitudes, _, _ = prepare(system, req)
    rng = np.random.default_rng(seed)
    iy = rng.integers(0, amplitudes.size, n_sample)
    ix = rng.integers(0, periods.size, n_sample)
    warm_up()
    pulse_points(sp, kind, shape, periods[:2], amplitudes[-2:], batch_options(), req.t_free)  # compile
    out = {}

    def kernel_time(energy_stop):
        opts = batch_options(req.rtol, req.atol, energy_stop=energy_stop)
        t0 = time.perf_counter()
        res = pulse_points(sp, kind, shape, periods[ix], amplitudes[iy], opts, req.t_free)
        return time.perf_counter() - t0, int(res[:, OUT_STEPS].sum())
    t_stop, steps_stop = kernel_time(True)
    t_full, steps_full = kernel_time(False)
    out["sample_points"] = n_sample
    out["kernel_energy_stop_ms"] = 1e3 * t_stop / n_sample
    out["kernel_full_length_ms"] = 1e3 * t_full / n_sample
    out["early_stop_speedup"] = t_full / t_stop
    out["early_stop_steps_ratio"] = steps_full / max(steps_stop, 1)
    # Python loop over simulate() (energy stop on, no history): the cost without the batch kernel
    t0 = time.perf_counter()
    for k in range(n_python):
        simulate(system, pulse_motion("ricker-anti", float(amplitudes[iy[k]]), float(periods[ix[k]])),
                 model="exact", energy_stop=True, record_history=False)
    out["python_simulate_ms"] = 1e3 * (time.perf_counter() - t0) / n_python
    # scipy reference (solve_ivp DOP853 at the same tolerance, full length)
    t0 = time.perf_counter()
    for k in range(n_scipy):
        m = pulse_motion("ricker-anti", float(amplitudes[iy[k]]), float(periods[ix[k]]))
        simulate_scipy(system, m, rtol=req.rtol, atol=req.atol, t_end=m.duration + req.t_free)
    out["scipy_reference_ms"] = 1e3 * (time.perf_counter() - t0) / n_scipy
    out["python_simulate_points"] = n_python
    out["scipy_points"] = n_scipy
    return out




def _cpu_seconds() -> float:
    """CPU seconds used so far by this process (all threads) — run on each dask worker."""
    import resource
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def thread_scaling(x: str, y: str) -> dict:
    """In-process kernel with 1 and 2 numba threads: how much parallelism the machine offers now."""
    import numba

    from rockdesign.planar.spectra import SpectrumRequest, compute_spectrum, parse_axis
    from rockdesign.planar.system import Column, RockingSystem
    system = RockingSystem("B1", "column", Column(1.5, 0.15, 1000.0, 1 / 3))
    req = SpectrumRequest("ricker-anti", parse_axis(x, "x"), parse_axis(y, "y"))
    out = {}
    for n in (1, 2):
        numba.set_num_threads(n)
        c0 = time.process_time()
        spec = compute_spectrum(system, req)
        out[f"threads_{n}"] = {"compute_s": spec.execution["compute_s"], "cpu_s": time.process_time() - c0}
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    out["speedup_2_over_1"] = out["threads_1"]["compute_s"] / out["threads_2"]["compute_s"]
    return out


def dask_scaling(x: str, y: str) -> dict:
    from rockdesign.planar.spectra import SpectrumRequest, compute_spectrum, make_executor, parse_axis
    from rockdesign.planar.spectra.kernel import warm_up
    from rockdesign.planar.system import Column, RockingSystem
    system = RockingSystem("B1", "column", Column(1.5, 0.15, 1000.0, 1 / 3))
    req = SpectrumRequest("ricker-anti", parse_axis(x, "x"), parse_axis(y, "y"))
    local = compute_spectrum(system, req)
    out = {"grid": [x, y], "analyses": local.n_analyses, "local_in_process_s": local.execution["compute_s"],
           "local_threads": local.execution.get("threads")}
    for n in (1, 2):
        with make_executor(f"local:{n}", warm_up=warm_up, numba_threads=1) as ex:
            ex.start()
            c0 = ex.client.run(_cpu_seconds)
            spec = compute_spectrum(system, req, executor=ex)
            c1 = ex.client.run(_cpu_seconds)
        cpu = sum(c1[w] - c0[w] for w in c1)
        wall = spec.execution["compute_s"]
        out[f"workers_{n}"] = {"compute_s": wall, "startup_s": ex.warm_up_seconds,
                               "per_analysis_ms": spec.execution["per_analysis_ms"],
                               "worker_cpu_s": cpu, "cpu_utilisation": cpu / (n * wall),
                               "chunks": spec.execution["chunks"],
                               "identical_to_local": bool(np.array_equal(spec.out, local.out, equal_nan=True))}
    out["speedup_2_over_1"] = out["workers_1"]["compute_s"] / out["workers_2"]["compute_s"]
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", default=str(ROOT / "benchmarks" / "results" / "spectrum.json"))
    ap.add_argument("--quick", action="store_true", help="201 × 101 grid instead of 801 × 401")
    ap.add_argument("--no-dask", action="store_true", help="skip the dask scaling")
    args = ap.parse_args(argv)
    x, y = ("omega_p/p:0.5:12:201", "ap/up:0:12:101") if args.quick else ("omega_p/p:0.5:12:801", "ap/up:0:12:401")
    result = {"benchmark": "rocking spectrum, Housner block B1, antisymmetric Ricker",
              "date": datetime.now(timezone.utc).isoformat(timespec="seconds"), "machine": _machine(),
              "quick": args.quick}
    with tempfile.TemporaryDirectory() as tmp:
        proj = Path(tmp) / "b1.toml"
        proj.write_text(BLOCK_TOML)
        print(f"full spectrum {x} × {y} ...", flush=True)
        result["spectrum"] = cli_run(proj, Path(tmp) / "out", x, y)
    sp = result["spectrum"]
    print(f"  {sp['analyses']:,} analyses: {sp['wall_s']:.1f} s wall (goal 60 s: "
          f"{'met' if sp['goal_met'] else 'NOT met'}), computing {sp['compute_s']:.1f} s = "
          f"{sp['per_analysis_ms_compute']:.3f} ms per analysis on {sp['threads']} threads; "
          f"{sp['cpu_s']:.1f} CPU-s = {sp['cpu_per_analysis_ms']:.3f} CPU-ms per analysis, "
          f"{sp['cpu_utilisation']:.2f} cores busy on average", flush=True)
    print("baselines on random grid points ...", flush=True)
    result["baselines"] = b = baselines(4000, 300, 20)
    per = sp["per_analysis_ms_compute"]
    b["ratio_python_simulate_to_spectrum"] = b["python_simulate_ms"] / per
    b["ratio_scipy_to_spectrum"] = b["scipy_reference_ms"] / per
    b["scipy_projected_full_spectrum_h"] = b["scipy_reference_ms"] * sp["analyses"] / 3.6e6
    print(f"  early stop: {b['early_stop_speedup']:.2f}× faster than full-length runs "
          f"({b['kernel_energy_stop_ms']:.3f} vs {b['kernel_full_length_ms']:.3f} ms per analysis, "
          f"{b['early_stop_steps_ratio']:.2f}× fewer steps)")
    print(f"  Python simulate() loop: {b['python_simulate_ms']:.3f} ms per analysis "
          f"({b['ratio_python_simulate_to_spectrum']:.1f}× the spectrum command's compute)")
    print(f"  scipy reference: {b['scipy_reference_ms']:.1f} ms per analysis ({b['ratio_scipy_to_spectrum']:.0f}×; "
          f"the full spectrum would take {b['scipy_projected_full_spectrum_h']:.1f} h)", flush=True)
    if not args.no_dask:
        print("parallelism available now: in-process kernel on 1 and 2 threads ...", flush=True)
        result["threads"] = t = thread_scaling("omega_p/p:0.5:12:201", "ap/up:0:12:101")
        print(f"  1 thread {t['threads_1']['compute_s']:.2f} s, 2 threads {t['threads_2']['compute_s']:.2f} s "
              f"→ speedup {t['speedup_2_over_1']:.2f}", flush=True)
        print("dask LocalCluster, 1 and 2 single-threaded workers ...", flush=True)
        result["dask"] = d = dask_scaling("omega_p/p:0.5:12:201", "ap/up:0:12:101")
        print(f"  {d['analyses']:,} analyses: 1 worker {d['workers_1']['compute_s']:.2f} s, 2 workers "
              f"{d['workers_2']['compute_s']:.2f} s → speedup {d['speedup_2_over_1']:.2f} (workers busy "
              f"{100 * d['workers_1']['cpu_utilisation']:.0f} % / {100 * d['workers_2']['cpu_utilisation']:.0f} % "
              f"of their wall time); identical to local: "
              f"{d['workers_1']['identical_to_local'] and d['workers_2']['identical_to_local']}")
    result["machine"]["load_average_after"] = list(os.getloadavg())
    summary = {"full_spectrum_wall_s": sp["wall_s"], "per_analysis_ms": sp["per_analysis_ms_compute"],
               "cpu_per_analysis_ms": sp["cpu_per_analysis_ms"], "cores_busy": sp["cpu_utilisation"],
               "goal_60s_met": sp["goal_met"], "early_stop_speedup": b["early_stop_speedup"],
               "ratio_scipy_to_spectrum": b["ratio_scipy_to_spectrum"]}
    if "dask" in result:
        summary["dask_speedup_2_over_1"] = result["dask"]["speedup_2_over_1"]
        summary["threads_speedup_2_over_1"] = result["threads"]["speedup_2_over_1"]
        summary["dask_identical_to_local"] = (result["dask"]["workers_1"]["identical_to_local"]
                                              and result["dask"]["workers_2"]["identical_to_local"])
    result = {"benchmark": result.pop("benchmark"), "date": result.pop("date"), "summary": summary, **result}
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(result, indent=1) + "\n")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
