"""The same rigid block in OpenSees (a contact-spring model) and in rockdesign, timed in the same run.

Usage::

    .venv/bin/pip install openseespy    # not a rockdesign dependency; needs libblas3, liblapack3, libgfortran5
    .venv/bin/python benchmarks/bench_opensees.py [--quick] [--out benchmarks/results/opensees.json]

The block is the work-precision benchmark's ``housner-block`` (thesis Appendix B: R = 1.50 m,
tan α = 0.15, λ = 0.33, c_r = 0.90, exact equations).  The OpenSees model is the usual contact-spring
idealisation of a rocking block: a node at the centre of mass (mass m, rotational inertia λ m R²) joined
to the two base corners by very stiff elastic beams with a corotational transformation (large rotations;
OpenSees' rigid links are small-rotation constraints and would turn the restoring moment mgR sin(α − θ)
into the constant mgB).  Each corner stands on a zero-length ``flatSliderBearing`` (Coulomb friction,
μ = 1: no sliding, and no horizontal restraint once the corner lifts) and a vertical zero-length spring,
each with half of the no-tension contact stiffness K_V (``ENT``).  Impacts lose energy through
stiffness-proportional damping of the vertical springs on their committed stiffness (a lifted corner is
undamped); β_K is calibrated at Δt = 1e-4 s so that free rocking rebounds after its first impact to the
amplitude rockdesign gives with c_r = 0.90 — the same restitution in both models.  Newmark's average
acceleration method with Newton iterations, at a fixed time step.

Measured in one run:

1. **Free rocking** (released upright at the rate that lifts the block to 0.4 α): the first peak, the
   time of the first impact and the first rebound of OpenSees at every time step, against rockdesign
   (rtol 1e-10; the first impact of the rigid block is exact to ≤ 1e-9 s).
2. **One record** — FEMA P695 far-field record 1a (Northridge 1994, Mulholland, 0.01 s, 30 s) at
   several scale factors around the first one that overturns the block: θ_max/α and the overturning
   verdict (θ_max ≥ θc = α, the check's static criterion) of OpenSees at Δt = 0.01, 0.005 and 0.001 s
   against rockdesign, and the wall time of one analysis of each, run back to back (the
   machine is shared; a ratio of two neighbouring runs is what counts).

Writes ``benchmarks/results/opensees.json`` and prints a table.  Without openseespy it says so and exits
with 0; the tests never import it.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from rockdesign.bench.problems import G, RECORD_ID, bench_record, housner_block  # noqa: E402
from rockdesign.bench.timing import machine_info  # noqa: E402
from rockdesign.planar.dynamics.simulate import simulate  # noqa: E402

T_FREE = 2.0
T_RECORD = 30.0
PEAK_OVER_ALPHA = 0.4
MASS = 1000.0          # kg (rocking does not depend on it)
K_V = 1.0e9            # N/m per corner: contact frequency √(2 K_V / m) ≈ 1,400 rad/s
K_BEAM = 1.0e11        # N/m axial stiffness of the "rigid" beams (100 K_V)
MU = 1.0               # Coulomb friction at the corners: no sliding (tan α = 0.15)
K_H = 1.0e9            # N/m initial shear stiffness of the friction elements
TIME_STEPS = (0.01, 0.005, 0.001)
SCALES = (0.5, 0.6, 0.7, 0.8, 0.9)   # rockdesign: 0.7 and 0.9 overturn, 0.8 does not
CALIBRATION_DT = 1e-4


def _opensees():
    """The openseespy module, or None when it is not installed or its libraries are missing."""
    try:
        import openseespy.opensees as ops
    except (ImportError, RuntimeError) as exc:  # openseespy raises RuntimeError when BLAS/LAPACK are absent
        print(f"openseespy is not available ({exc}); skipping the OpenSees benchmark.")
        return None
    return ops


def _geometry():
    system = housner_block()
    col = system.column
    H, B = col.half_height, col.half_width
    return system, H, B, math.hypot(H, B), math.atan2(B, H)


def run_opensees(ops, accel: np.ndarray | None, dt_record: float, dt: float, t_end: float, beta_k: float,
                 thetadot0: float = 0.0) -> dict:
    """One OpenSees analysis of the contact-spring block, from rest or rocking about its left corner at
    θ̇ = ``thetadot0`` [rad/s]: θ [rad] at every step, θ_max/α, status and wall time [s] of the transient."""
    system, H, B, R, alpha = _geometry()
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, -B, 0.0)          # ground under the left corner
    ops.node(2, B, 0.0)           # ground under the right corner
    ops.node(3, -B, 0.0)          # the block's corners and its centre of mass
    ops.node(4, B, 0.0)
    ops.node(5, 0.0, H)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 1, 1)
    ops.mass(3, 1e-9 * MASS, 1e-9 * MASS, 1e-9 * MASS)
    ops.mass(4, 1e-9 * MASS, 1e-9 * MASS, 1e-9 * MASS)
    ops.mass(5, MASS, MASS, system.column.mass_distribution * MASS * R * R)   # I_C = λ m R² (Eq 3.6)
    ops.geomTransf("Corotational", 1)
    area, inertia = 1.0, 1.0
    young = K_BEAM * R                                  # E A / L ≈ K_BEAM for the ≈ R-long beams
    ops.element("elasticBeamColumn", 10, 5, 3, area, young, inertia, 1)
    ops.element("elasticBeamColumn", 11, 5, 4, area, young, inertia, 1)
    ops.element("elasticBeamColumn", 12, 3, 4, area, young, inertia, 1)
    # each corner: half of the contact stiffness in the friction element (its normal force sets the friction),
    # half in a vertical zero-length spring that carries the damping (so the friction element is undamped)
    ops.uniaxialMaterial("ENT", 1, 0.5 * K_V)
    ops.uniaxialMaterial("Elastic", 2, 1e-6)
    ops.frictionModel("Coulomb", 1, MU)
    for tag, (i, j) in ((1, (1, 3)), (2, (2, 4))):
        ops.element("flatSliderBearing", tag, i, j, 1, K_H, "-P", 1, "-Mz", 2, "-orient", 0, 1, 0, -1, 0, 0)
        ops.element("zeroLength", tag + 2, i, j, "-mat", 1, "-dir", 2, "-doRayleigh", 1)
    if beta_k:   # stiffness-proportional on the committed stiffness: zero once a corner has lifted
        ops.region(1, "-ele", 3, 4, "-rayleigh", 0.0, 0.0, 0.0, beta_k)
    ops.timeSeries("Constant", 1)                     # gravity, settled by one static step and held
    ops.pattern("Plain", 1, 1)
    ops.load(5, 0.0, -MASS * G, 0.0)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    ops.analyze(1)
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()
    if thetadot0:  # rigid rotation about the left corner (-B, 0): v = θ̇ ẑ × (x + B, y)
        for node, (x, y) in ((5, (0.0, H)), (3, (-B, 0.0)), (4, (B, 0.0))):
            for dof, v in ((1, -thetadot0 * y), (2, thetadot0 * (x + B)), (3, thetadot0)):
                ops.setNodeVel(node, dof, v, "-commit")
    if accel is not None:
        ops.timeSeries("Path", 2, "-dt", dt_record, "-values", *accel.tolist())
        ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-10, 100)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    n = int(round(t_end / dt))
    theta = np.empty(n + 1)
    theta[0] = ops.nodeDisp(5, 3)
    status = "completed"
    t0 = time.perf_counter()
    for k in range(1, n + 1):
        if ops.analyze(1, dt) != 0 and ops.analyze(10, dt / 10.0) != 0:   # retry a failed step in 10 substeps
            status = f"no convergence at t = {k * dt:.3f} s"
            theta = theta[:k]
            break
        theta[k] = ops.nodeDisp(5, 3)
        if abs(theta[k]) > 2.0 * alpha:     # far past θc: overturned by the check's criterion
            status = "overturned"
            theta = theta[:k + 1]
            break
    seconds = time.perf_counter() - t0
    ops.wipe()
    return {"theta": theta, "theta_max_over_alpha": float(np.max(np.abs(theta)) / alpha), "status": status,
            "seconds": seconds}


def _first_impact(theta: np.ndarray, dt: float) -> float:
    """Time [s] at which θ, after rising to its first peak, first returns to 0 (linear interpolation)."""
    top = int(np.argmax(theta))
    k = top + int(np.argmax(theta[top:] <= 0.0)) - 1
    return float(dt * (k + theta[k] / (theta[k] - theta[k + 1])))


def _first_rebound(theta: np.ndarray) -> float:
    """The peak |θ| [rad] of the half-cycle after the first impact (θ < 0 after the first rise θ > 0)."""
    start = int(np.argmax(theta))
    start += int(np.argmax(theta[start:] < 0.0))
    rest = theta[start:]
    end = start + int(np.argmax(rest >= 0.0)) if np.any(rest >= 0.0) else len(theta)
    return float(-np.min(theta[start:end]))


def calibrate_beta_k(ops, target_rebound: float, thetadot0: float) -> float:
    """β_K [s] of the contacts whose free-rocking rebound equals ``target_rebound`` [rad] (bisection on log β_K)."""
    lo, hi = 1e-5, 1e-1
    for _ in range(12):
        mid = math.sqrt(lo * hi)
        run = run_opensees(ops, None, 0.01, CALIBRATION_DT, T_FREE, mid, thetadot0=thetadot0)
        lo, hi = (mid, hi) if _first_rebound(run["theta"]) > target_rebound else (lo, mid)
    return math.sqrt(lo * hi)


def _best_ms(fn, repeats: int) -> float:
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return 1e3 * best


def free_rocking(ops, system, R: float, alpha: float, steps) -> dict:
    """Part 1: rockdesign's first peak, impact and rebound; OpenSees calibrated to the rebound, at every Δt."""
    lam = system.column.mass_distribution
    peak = PEAK_OVER_ALPHA * alpha   # energy: ½ (1 + λ) m R² θ̇0² = m g R (cos(α − θ0) − cos α)
    thetadot0 = math.sqrt(2.0 * G * (math.cos(alpha - peak) - math.cos(alpha)) / ((1.0 + lam) * R))
    ours = simulate(system, None, model="exact", thetadot0=thetadot0, t_end=T_FREE, rtol=1e-10)
    impacts = ours.impact_times
    window = (ours.t > impacts[0]) & (ours.t < (impacts[1] if len(impacts) > 1 else T_FREE))
    rebound = float(np.max(np.abs(ours.theta[window])))
    beta_k = calibrate_beta_k(ops, rebound, thetadot0)
    rows = []
    for dt in (CALIBRATION_DT, *steps):
        run = run_opensees(ops, None, 0.01, dt, T_FREE, beta_k, thetadot0=thetadot0)
        rows.append({"dt": dt, "first_peak_over_alpha": float(np.max(run["theta"])) / alpha,
                     "first_impact_s": _first_impact(run["theta"], dt),
                     "first_rebound_over_alpha": _first_rebound(run["theta"]) / alpha, "status": run["status"]})
    print(f"free rocking, rockdesign: peak {ours.theta_max / alpha:.4f} α, first impact {impacts[0]:.5f} s, "
          f"rebound {rebound / alpha:.4f} α; OpenSees β_K = {beta_k:.3e} s")
    for row in rows:
        print(f"  OpenSees Δt {row['dt']:g} s: peak {row['first_peak_over_alpha']:.4f} α, first impact "
              f"{row['first_impact_s']:.5f} s, rebound {row['first_rebound_over_alpha']:.4f} α")
    return {"thetadot0_rad_s": thetadot0, "rockdesign": {"peak_over_alpha": ours.theta_max / alpha,
                                                         "first_impact_s": float(impacts[0]),
                                                         "first_rebound_over_alpha": rebound / alpha},
            "beta_k_s": beta_k, "opensees": rows}


def record_runs(ops, system, alpha: float, beta_k: float, steps, scales) -> list[dict]:
    """Part 2: the record at each scale factor, rockdesign against OpenSees at every Δt."""
    record = bench_record()
    record = record.scaled(1.0 / record.scale)           # the record as published [m/s²]
    accel = record.samples * record.scale
    rows = []
    for scale in scales:
        motion = record.scaled(scale)
        ours = simulate(system, motion, model="exact", t_end=T_RECORD, rtol=1e-10)   # also the warm-up
        row = {"scale": scale, "rockdesign": {"theta_max_over_alpha": ours.theta_max / alpha,
                                              "overturned": bool(ours.theta_max >= alpha), "ms": []},
               "opensees": []}
        for dt in steps:
            # one run of each, back to back: the shared machine's load changes by the minute
            ours_ms = _best_ms(lambda: simulate(system, motion, model="exact", t_end=T_RECORD, rtol=1e-10), 1)
            run = run_opensees(ops, accel * scale, record.dt, dt, T_RECORD, beta_k)
            row["rockdesign"]["ms"].append(ours_ms)
            row["opensees"].append({"dt": dt, "theta_max_over_alpha": min(run["theta_max_over_alpha"], 2.0),
                                    "overturned": run["theta_max_over_alpha"] >= 1.0, "status": run["status"],
                                    "ms": 1e3 * run["seconds"], "over_rockdesign": 1e3 * run["seconds"] / ours_ms})
        rows.append(row)
        mark = {True: " OT", False: ""}
        cells = "  ".join(f"Δt {o['dt']:g}: {o['theta_max_over_alpha']:.3f}{mark[o['overturned']]} {o['ms']:.0f} ms"
                          for o in row["opensees"])
        print(f"× {scale:.2f}: rockdesign {row['rockdesign']['theta_max_over_alpha']:.3f}"
              f"{mark[row['rockdesign']['overturned']]} {min(row['rockdesign']['ms']):.2f} ms | OpenSees {cells}",
              flush=True)
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="two time steps and three scale factors")
    parser.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "opensees.json")
    args = parser.parse_args(argv)
    ops = _opensees()
    if ops is None:
        return 0
    system, H, B, R, alpha = _geometry()
    steps = TIME_STEPS[::2] if args.quick else TIME_STEPS
    scales = SCALES[1:4] if args.quick else SCALES
    free = free_rocking(ops, system, R, alpha, steps)
    rows = record_runs(ops, system, alpha, free["beta_k_s"], steps, scales)
    agree = {f"{dt:g}": sum(r["opensees"][i]["overturned"] == r["rockdesign"]["overturned"] for r in rows)
             for i, dt in enumerate(steps)}
    cost = {f"{dt:g}": [r["opensees"][i]["over_rockdesign"] for r in rows if r["opensees"][i]["status"] == "completed"]
            for i, dt in enumerate(steps)}   # analyses of the whole record (an overturned run stops early)
    summary = {"cases": len(rows), "verdicts_equal_to_rockdesign_per_dt": agree,
               "opensees_time_over_rockdesign_per_dt": {k: [min(v), max(v)] if v else None for k, v in cost.items()}}
    print(f"verdicts equal to rockdesign's (of {len(rows)} scale factors), per Δt: {agree}")
    print(f"OpenSees time / rockdesign time (whole record), per Δt: {summary['opensees_time_over_rockdesign_per_dt']}")
    from importlib.metadata import version
    out = {"benchmark": "opensees", "date": machine_info()["date"], "machine": machine_info(),
           "openseespy": version("openseespy"), "record": RECORD_ID,
           "model": {"mass_kg": MASS, "k_v_n_per_m": K_V, "k_beam_n_per_m": K_BEAM, "mu": MU, "k_h_n_per_m": K_H,
                     "integrator": "Newmark average acceleration, Newton, NormDispIncr 1e-12"},
           "free_rocking": free, "record_runs": rows, "summary": summary, "method": __doc__}
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
