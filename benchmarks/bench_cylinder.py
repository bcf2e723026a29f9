"""Cylinder engine benchmark: rockdesign's numba DOP853 against scipy solve_ivp(DOP853), equal accuracy.

Usage::

    .venv/bin/python benchmarks/bench_cylinder.py [--out benchmarks/results/cylinder.json]

The 3D cylinder of thesis Ch. 5 (2H = 3 m, tan α = 0.2; undamped and damped models) under a 30-s record
pair: FEMA P695 far-field record 1 (Northridge 1994, Beverly Hills – Mulholland, components a along x
and b along y, 0.01 s), scaled to a resultant PGA of 0.3 g (the thesis's Table 5.4 scaling), analysed
for 30 s.  Our engine runs at its default rtol = 1e-10; its error is max |Δθ| at the record samples
against a converged reference (our engine at rtol = 1e-13, atol = 1e-15, cross-checked with scipy at
rtol = 1e-11).  The baseline is scipy's DOP853 on the same equations (Eqs 5.22, 5.23 corrected, 5.36,
5.37, written here in plain Python), with the same uplift (Eq 5.24, located by brentq) and restarted
at every record sample (the kinks of the piecewise-linear record), over rtol = 1e-6 … 1e-11; the ratio
uses the *cheapest* scipy tolerance whose error is no larger than ours.  Times are the fastest of repeated runs (ours 15,
scipy's baseline 3; the machine is shared by other jobs) after a warm-up run, measured in this process.

Second part: a 60 × 51 size–amplitude spectrum (R = 0.5 … 30 m, max|ü_g|/(g tan α) = 1 … 6) of record
pair FEMA P695 far-field 11 (Landers, Yermo), damped model, on all cores (goal: < 60 s on 2 cores),
timed after a warm-up on a 2 × 2 grid.  Writes ``benchmarks/results/cylinder.json``.
"""
from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from rockdesign.cylinder.engine import simulate_cylinder  # noqa: E402
from rockdesign.cylinder.system import cylinder  # noqa: E402
from rockdesign.cylinder.pairs import parse_pair  # noqa: E402

MOTION = "record:p695-ff/1,resultant_pga=0.3g"
T_END = 30.0
OUR_RTOL, OUR_ATOL = 1e-10, 1e-12
SCIPY_TOLERANCES = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)
GOAL_RATIO = 100.0


def spec_rhs(t, y, cyl, ground):
    """Eqs 5.22/5.23 (corrected) or 5.23/5.36/5.37, in plain Python (the scipy baseline), with the same
    cancellation-free forms as the kernel: 1 − cosθ = 2 sin²(θ/2), cos2θ − cosθ = −2 sin(3θ/2) sin(θ/2),
    sinα − sin(α−θ) = 2 cos(α − θ/2) sin(θ/2) (the naive forms lose ~1e-7 relative at a quasi-impact)."""
    R, a, g = cyl.R, cyl.alpha, cyl.g
    s2, c2 = math.sin(a) ** 2, math.cos(a) ** 2
    th, thd, ph, phd = y[0], y[1], y[2], y[3]
    ax, ay = ground(t)
    st, ct, sh = math.sin(th), math.cos(th), math.sin(th / 2)
    omc = 2 * sh * sh
    X = st * ct * (1.25 * s2 - 4 / 3 * c2) - 1.5 * st * s2 - math.cos(a) * math.sin(a) * 2 * math.sin(1.5 * th) * sh
    F = ax * math.cos(ph) + ay * math.sin(ph)
    M = (15 + c2) / 12
    if cyl.damped:
        om, ze = cyl.contact_frequency, cyl.contact_damping
        Q = thd ** 2 * R * math.cos(a - th) - 2 * ze * om * y[5] - om * om * y[4]
        thdd = (-phd ** 2 * R * X - (g + Q) * math.sin(a - th) - math.cos(a - th) * F) / (R * (M - math.sin(a - th) ** 2))
    else:
        thdd = (-phd ** 2 * R * X - g * math.sin(a - th) - math.cos(a - th) * F) / (R * M)
    J = (16 + 5 * s2) / 12 * st * st + omc * (math.sin(2 * a) * st - 3 * s2 * ct)
    K = math.sin(2 * a) * (ct * omc + st * st) + st * (3 * s2 + (8 / 3 * c2 - 2.5 * s2) * ct)
    lever = 2 * math.cos(a - th / 2) * sh
    phdd = (lever * (ax * math.sin(ph) - ay * math.cos(ph)) / R - K * phd * thd) / J
    out = [thd, thdd, phd, phdd]
    if cyl.damped:
        out += [y[5], Q - thdd * R * math.sin(a - th)]
    return out


def scipy_run(cyl, t_s, ax, ay, rtol, atol, seed=1e-7, t_end=T_END):
    """Uplift (brentq on |ü_g| = g tan α), then DOP853 sample interval by sample interval; θ at the samples."""
    def ground(t):
        if t > t_s[-1]:
            return 0.0, 0.0
        return float(np.interp(t, t_s, ax)), float(np.interp(t, t_s, ay))
    up = cyl.g * math.tan(cyl.alpha)
    i = int(np.argmax(np.hypot(ax, ay) >= up))
    t_up = brentq(lambda t: math.hypot(*ground(t)) - up, t_s[i - 1], t_s[i], xtol=1e-15)
    gx, gy = ground(t_up)
    y = np.zeros(6 if cyl.damped else 4)
    y[0], y[2] = seed, math.atan2(-gy, -gx)
    knots = [t_up] + [t for t in t_s if t_up < t <= t_end]
    theta, nfev = [], 0
    for t0, t1 in zip(knots[:-1], knots[1:]):
        sol = solve_ivp(spec_rhs, (t0, t1), y, method="DOP853", rtol=rtol, atol=atol, args=(cyl, ground))
        nfev += sol.nfev
        y = sol.y[:, -1]
        theta.append(y[0])
        if y[0] >= cyl.theta_overturn:
            break
    return np.array(knots[1:len(theta) + 1]), np.array(theta), nfev


def ours_theta_at(r, times):
    idx = np.minimum(np.searchsorted(r.t, times), r.t.size - 1)
    assert np.allclose(r.t[idx], times, atol=1e-9)
    return r.theta[idx]


def timed(fn, repeats):
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.min(times))


def bench_model(contact: str, say) -> dict:
    cyl = cylinder(3.0, 0.6, contact=contact)
    pair = parse_pair(MOTION, gravity=cyl.g).pair
    t_s, ax, ay = pair.sampled()
    run = lambda rtol, atol: simulate_cylinder(cyl, pair, t_end=T_END, rtol=rtol, atol=atol)  # noqa: E731
    ref = run(1e-13, 1e-15)
    ours = run(OUR_RTOL, OUR_ATOL)
    seconds_ours = timed(lambda: run(OUR_RTOL, OUR_ATOL), 15)
    last = min(ours.t[-1], ref.t[-1])
    sample_t = t_s[(t_s > ours.uplift_time) & (t_s <= last)]
    err_ours = float(np.max(np.abs(ours_theta_at(ours, sample_t) - ours_theta_at(ref, sample_t))))
    say(f"[{contact}] ours: {seconds_ours * 1e3:.1f} ms, {ours.solver['steps']} steps, max|Δθ| = {err_ours:.2e} rad, "
        f"{ours.quasi_impacts} quasi-impacts, status {ours.status}")
    scipy_points = []
    for rtol in SCIPY_TOLERANCES:
        t0 = time.perf_counter()
        times, theta, nfev = scipy_run(cyl, t_s, ax, ay, rtol, rtol * 1e-2)
        secs = time.perf_counter() - t0
        keep = times <= last
        err = float(np.max(np.abs(theta[keep] - ours_theta_at(ref, times[keep]))))
        scipy_points.append({"rtol": rtol, "seconds": secs, "error_theta": err, "nfev": nfev})
        say(f"[{contact}] scipy DOP853 rtol {rtol:g}: {secs:.2f} s, max|Δθ| = {err:.2e} rad")
    # cross-check of the reference: scipy at its tightest tolerance
    cross = scipy_points[-1]["error_theta"]
    equal = [p for p in scipy_points if p["error_theta"] <= err_ours]
    baseline = dict(min(equal, key=lambda p: p["seconds"]) if equal else scipy_points[-1])
    # the baseline's time: the fastest of three runs (the machine is shared; ours: the fastest of 15)
    runs = [baseline["seconds"]]
    for _ in range(2):
        t0 = time.perf_counter()
        scipy_run(cyl, t_s, ax, ay, baseline["rtol"], baseline["rtol"] * 1e-2)
        runs.append(time.perf_counter() - t0)
    baseline["seconds"] = float(np.min(runs))
    baseline["seconds_runs"] = runs
    return {"model": "damped" if cyl.damped else "undamped", "motion": MOTION, "t_end": T_END,
            "ours": {"rtol": OUR_RTOL, "atol": OUR_ATOL, "seconds": seconds_ours, "error_theta": err_ours,
                     "steps": ours.solver["steps"], "rhs_evaluations": ours.solver["rhs_evaluations"],
                     "quasi_impacts": ours.quasi_impacts, "theta_max": ours.theta_max, "status": ours.status},
            "reference_cross_check_scipy_rtol_1e-11": cross,
            "scipy": scipy_points, "baseline": baseline,
            "equal_accuracy": bool(equal), "ratio": baseline["seconds"] / seconds_ours}


def bench_spectrum(say) -> dict:
    from rockdesign.cylinder.spectrum import cylinder_spectrum
    cyl = cylinder(3.0, 0.6, contact="spring-dashpot")
    pair = parse_pair("record:p695-ff/11").pair
    cylinder_spectrum(cyl, pair, [1.0, 2.0], [2.0, 3.0])               # warm-up (compilation)
    R, levels = np.linspace(0.5, 30.0, 60), np.linspace(1.0, 6.0, 51)
    spec = cylinder_spectrum(cyl, pair, R, levels)
    say(f"spectrum 60 x 51 of p695-ff/11 (damped): {spec.seconds:.1f} s, {int(spec.overturned.sum())} overturned")
    import os
    return {"record": "p695-ff/11", "model": "damped", "grid": [51, 60], "seconds": spec.seconds,
            "cores": os.cpu_count(), "n_overturned": int(spec.overturned.sum()), "goal_seconds": 60.0,
            "goal_met": spec.seconds < 60.0}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "cylinder.json"))
    args = parser.parse_args(argv)
    t0 = time.time()
    results = [bench_model(c, print) for c in ("rigid", "spring-dashpot")]
    spectrum = bench_spectrum(print)
    ratios = [r["ratio"] for r in results]
    out = {"benchmark": "cylinder", "date": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
           "machine": {"platform": platform.platform(), "python": platform.python_version()},
           "load_average_at_end": list(__import__("os").getloadavg()),
           "method": __doc__.strip(), "records": results, "spectrum": spectrum,
           "summary": {"ratio_min": min(ratios), "ratio_max": max(ratios), "goal_ratio": GOAL_RATIO,
                       "goal_ratio_met": min(ratios) >= GOAL_RATIO},
           "seconds": time.time() - t0}
    Path(args.out).write_text(json.dumps(out, indent=2) + "\n")
    for r in results:
        print(f"{r['model']}: ours {r['ours']['seconds'] * 1e3:.1f} ms vs scipy {r['baseline']['seconds']:.2f} s "
              f"(rtol {r['baseline']['rtol']:g}) → {r['ratio']:.0f}×")


if __name__ == "__main__":
    main()
