"""A cylinder checked at its uplift threshold (issue 43) against the same cylinder 10 % more slender.

Usage::

    .venv/bin/python benchmarks/bench_cylinder_threshold.py [--repeat 3] [--out benchmarks/results/cylinder_threshold.json]

The project of ``rockdesign init cylinder`` (rigid contact, FEMA P695 far-field pairs, resultant PGA 0.3 g,
risk category II) with 2H = 2.5 m and 2B = 0.75 m: tan α = 0.30, so the design level is the uplift
acceleration g tan α and half of the perturbation ensemble's runs (amplitude × 1.001) barely uplift.  The
yardstick is 2B = 0.675 m (tan α = 0.27: 0.3 g is 1.11 g tan α, ordinary rocking).  Both full checks (design
suite, incremental margins, 8-run perturbation ensemble; no report) run in this process, alternately
(threshold, yardstick, threshold, ...) after a warm-up, and the ratio is taken pair by pair (robust to the
load of a shared machine).  Then the threshold check is repeated with the seed tilt × 0.1 and × 10 (two
decades): the verdict and the counts must not change.

Second part: the cost of one suite of 3D analyses of the threshold cylinder against the resultant PGA over
g tan α (1.001 … 1.3, rigid and spring–dashpot contact): just above 1.00 the cylinder rests after its first
quasi-impact; around 1.01–1.03 the rigid contact keeps micro-rocking (energy above the rest energy, which it
cannot dissipate) — the cost that remains, and which the planar engine's c_r = 1 block shares
(docs/cylinder.md, "Rest, uplift and the seed").  Writes ``benchmarks/results/cylinder_threshold.json``.
"""
from __future__ import annotations

import argparse
import json
import math
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import rockdesign.cylinder.engine as engine  # noqa: E402
from rockdesign.cylinder.check import run_cylinder_check  # noqa: E402
from rockdesign.cylinder.system import cylinder  # noqa: E402
from rockdesign.kinds import parse_document  # noqa: E402
from rockdesign.cylinder.pairs import suite_pairs  # noqa: E402

THRESHOLD, YARDSTICK = 0.75, 0.675          # diameters [m], height 2.5 m
AMPLITUDES = (1.001, 1.003, 1.01, 1.03, 1.1, 1.3)


def project(diameter: float):
    return parse_document({
        "project": {"name": f"cylinder 2.5 m x {diameter} m"},
        "cylinder": {"height": "2.5 m", "diameter": f"{diameter} m", "density": "2.6 t/m^3", "contact": "rigid"},
        "excitation": {"suites": ["p695-farfield-pairs"], "scale": {"method": "resultant_pga", "target": "0.3 g"}},
        "analysis": {"overturn_tilt": 1.5, "risk_category": "II", "acceptance": "asce7", "rtol": 1e-10,
                     "free_vibration": "10 s"}})


def timed_check(proj) -> tuple[float, object]:
    t0 = time.perf_counter()
    result = run_cylinder_check(proj)
    return time.perf_counter() - t0, result


def summary(result) -> dict:
    return {"verdict": result.verdict, "n_overturned": result.summary["n_overturned"],
            "total_quasi_impacts": result.summary["total_quasi_impacts"],
            "ensemble_p_overturn": result.ensemble["p_overturn"] if result.ensemble else None}


def with_seed_factor(factor: float):
    """simulate_cylinder's default seed × factor (the check takes the default)."""
    original = engine.seed_tilt

    def scaled(R, alpha, g, rest_velocity):
        return factor * original(R, alpha, g, rest_velocity)
    return original, scaled


def suite_cost(contact: str, amplitude: float) -> dict:
    cyl = cylinder(2.5, THRESHOLD, contact=contact)
    out = {"seconds": 0.0, "steps": 0, "quasi_impacts": 0, "rest_entries": 0, "overturned": 0}
    for pair in suite_pairs("p695-farfield-pairs", gravity=cyl.g):
        scaled = pair.scaled(amplitude * cyl.g * cyl.tan_alpha / pair.resultant_pga)
        t0 = time.perf_counter()
        r = engine.simulate_cylinder(cyl, scaled)
        out["seconds"] += time.perf_counter() - t0
        out["steps"] += r.solver["steps"]
        out["quasi_impacts"] += r.quasi_impacts
        out["rest_entries"] += r.solver["rest_entries"]
        out["overturned"] += r.overturned
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "cylinder_threshold.json"))
    args = ap.parse_args()
    thr, yard = project(THRESHOLD), project(YARDSTICK)
    timed_check(thr)                                     # warm-up: kernels loaded or compiled
    pairs = []
    for _ in range(args.repeat):
        a, ra = timed_check(thr)
        b, rb = timed_check(yard)
        pairs.append((a, b))
        print(f"threshold {a:.2f} s ({ra.verdict}), 10 % more slender {b:.2f} s ({rb.verdict}), ratio {a / b:.3f}",
              flush=True)
    seeds = {}
    for factor in (0.1, 1.0, 10.0):
        original, scaled = with_seed_factor(factor)
        engine.seed_tilt = scaled
        try:
            _, r = timed_check(thr)
        finally:
            engine.seed_tilt = original
        seeds[str(factor)] = summary(r)
        print(f"seed × {factor}: {seeds[str(factor)]}", flush=True)
    costs = {}
    for contact in ("rigid", "spring-dashpot"):
        for amp in AMPLITUDES:
            costs[f"{contact} {amp}"] = c = suite_cost(contact, amp)
            print(f"{contact:14s} PGA = {amp} g tan α: 22 pairs in {c['seconds']:.2f} s, {c['steps']:,} steps, "
                  f"{c['quasi_impacts']:,} quasi-impacts, {c['rest_entries']} rests, {c['overturned']} overturned",
                  flush=True)
    ratios = [a / b for a, b in pairs]
    doc = {"machine": platform.platform(), "python": platform.python_version(),
           "threshold_project": "2H = 2.5 m, 2B = 0.75 m (tan α = 0.30), rigid, 0.3 g resultant PGA",
           "yardstick_project": "2H = 2.5 m, 2B = 0.675 m (tan α = 0.27)",
           "check_seconds": [{"threshold": a, "yardstick": b} for a, b in pairs],
           "median_ratio_threshold_over_yardstick": statistics.median(ratios),
           "verdict_by_seed_factor": seeds, "suite_cost_by_amplitude": costs,
           "seed_default_rad": engine.seed_tilt(math.hypot(0.375, 1.25), math.atan2(0.375, 1.25), 9.81, 5e-4)}
    Path(args.out).write_text(json.dumps(doc, indent=1) + "\n")
    print(f"median ratio {doc['median_ratio_threshold_over_yardstick']:.3f}; wrote {args.out}")


if __name__ == "__main__":
    main()
