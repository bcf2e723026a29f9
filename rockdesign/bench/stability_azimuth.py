"""The stability case of the 3D cylinder on a planar motion along an azimuth (see :mod:`rockdesign.bench.stability`).

A record acting along one line is, by the cylinder's symmetry, the record along x turned by the line's
azimuth β: θ(t) is the same and the tilt stays on the line (Housner's cylinder, thesis Eq 5.26).  The 3D
equations (Eqs 5.22–5.23) cannot show it: the torque of Eq 5.23 vanishes on the line only in exact
arithmetic, so the spin ℓ = J φ̇ gathers round-off, and its first return to θ = 0 is a quasi-impact far below
what any step control resolves (:mod:`rockdesign.cylinder.motion_line`).  The case runs the record as two
components along a sweep of azimuths and amplitudes against the single component along x, and runs the 3D
equations alone on the diagonal — our integrator without the planar reduction, and scipy's integrators from
the same state.

Every case function has the signature ``case(quick=False, methods=ALL_METHODS) -> StabilityCase``.
"""
from __future__ import annotations

import math
import time

import numpy as np

from .. import mplfig as plt  # (pyplot-free Figures: importing never switches the backend)
from ..cylinder.engine import simulate_cylinder
from ..cylinder.eom import parameters, rhs_ground
from ..cylinder.simulation import COMPLETED
from ..cylinder.system import cylinder
from ..motions.library import load_record
from ..motions.motion import record_motion
from ..cylinder.pairs import pair_of_records
from ..plots import STYLE
from .figures import COLORS
from .stability_outcome import ALL_METHODS, Outcome, StabilityCase

RECORD = "p695-ff/11a"
AZIMUTHS_DEG = (0.0, 15.0, 30.0, 45.0, 60.0, 90.0, 135.0, 200.0)
AMPLITUDES = (0.9, 1.05, 1.2, 1.5, 2.0, 3.0)
"""Resultant PGA over the uplift acceleration g tan α: below uplift, micro-rocking, rocking, overturning."""
GRID = 0.01
"""[s] the dense-output grid on which θ(t) is compared."""
EPS = float(np.finfo(float).eps)


def along(record, beta: float):
    """The record along the azimuth β [rad] as two components (a cosβ, a sinβ), as two files give it."""
    a = record.samples * record.scale
    return pair_of_records(f"{record.name} along {math.degrees(beta):g}°",
                           record_motion("x", math.cos(beta) * a, record.dt),
                           record_motion("y", math.sin(beta) * a, record.dt))


def theta_bound(a, b, cyl) -> float:
    """(N_a + N_b) √n (atol + rtol θ_ot) [rad]: how far two runs of one equation may differ by what their step
    control lets through (each accepted step: error norm ≤ 1, so ≤ √n (atol + rtol θ_ot) on θ; N steps added
    up without amplification)."""
    n = 6 if cyl.damped else 4
    s = a.solver
    return (a.solver["steps"] + b.solver["steps"]) * math.sqrt(n) * (s["atol"] + s["rtol"] * cyl.theta_overturn)


def _on_grid(r) -> dict[int, float]:
    k = np.round(r.t / GRID)
    rows = np.isclose(r.t, k * GRID, rtol=0.0, atol=1e-9)
    return dict(zip(k[rows].astype(int), r.theta[rows]))


def theta_difference(a, b) -> float:
    """max |θ_a − θ_b| [rad] on the grid times both runs reached."""
    ga, gb = _on_grid(a), _on_grid(b)
    return max((abs(ga[k] - gb[k]) for k in set(ga) & set(gb)), default=0.0)


def off_line(r, beta: float) -> float:
    """max distance [rad] of φ from the line of β (β or β + π) from the first uplift on."""
    rows = r.t >= (r.uplift_time if r.uplift_time is not None else np.inf)
    if not rows.any():
        return 0.0
    return float(np.max(np.abs(np.angle(np.exp(2j * (r.phi[rows] - beta)))))) / 2.0


def phi_bound(r) -> float:
    """[rad] the rounding of φ + π added at every planar crossing: (crossings + 1) · 2ε · max(|φ|, π)."""
    return (r.times_of("planar-crossing").size + 1) * 2.0 * EPS * max(float(np.max(np.abs(r.phi))), math.pi)


def sweep(contact: str, azimuths=AZIMUTHS_DEG, amplitudes=AMPLITUDES, record_id: str = RECORD) -> list[dict]:
    """One row per amplitude and azimuth: the two-component run along β against the single component along x.

    ``chaotic``: the reference itself moves by more than the bound when its input changes by 4ε (the rotation's
    round-off is ≤ 1.05 ε), so θ(t) is not comparable there; the outcome and the line still are."""
    cyl = cylinder(3.0, 0.6, contact=contact)
    record = load_record(record_id)
    up = cyl.g * math.tan(cyl.alpha)
    x_only = pair_of_records(record.name, record, None)
    rows = []
    for amplitude in amplitudes:
        scale = amplitude * up / x_only.resultant_pga
        ref = simulate_cylinder(cyl, x_only.scaled(scale), output_dt=GRID)
        nudged = simulate_cylinder(cyl, x_only.scaled(scale * (1.0 + 4.0 * EPS)), output_dt=GRID)
        for deg in azimuths:
            t0 = time.perf_counter()
            run = simulate_cylinder(cyl, along(record, math.radians(deg)).scaled(scale), output_dt=GRID)
            seconds = time.perf_counter() - t0
            bound = theta_bound(run, ref, cyl)
            rows.append({"contact": contact, "amplitude": amplitude, "azimuth": deg, "status": run.status,
                         "failed": run.status not in COMPLETED, "planar": run.planar,
                         "same_outcome": (run.overturned == ref.overturned
                                          and (run.uplift_time is None) == (ref.uplift_time is None)),
                         "overturned": run.overturned, "uplifted": run.uplift_time is not None,
                         "d_theta": theta_difference(run, ref), "bound": bound,
                         "sensitivity": theta_difference(ref, nudged),
                         "chaotic": theta_difference(ref, nudged) > bound,
                         "off_line": off_line(run, math.radians(deg)), "phi_bound": phi_bound(run),
                         "crossings": int(run.times_of("planar-crossing").size), "steps": run.solver["steps"],
                         "theta_max_over_alpha": run.theta_max / run.alpha, "seconds": seconds})
    return rows


CROSS_FRACTIONS = (1e-15, 1e-14, 1e-12, 1e-10, 1e-9, 1e-8)
"""Cross components (× the PGA) added to the diagonal: where a spin too small for the step control begins."""


def cross_component(fractions=CROSS_FRACTIONS, amplitude: float = 1.5) -> list[dict]:
    """The diagonal (a, a) of :data:`RECORD` at ``amplitude`` × g tan α with a cross component ε·b (b: the record's
    other horizontal component scaled to its PGA): the status and overturning instant of each run, and of ε = 0.
    A real cross component gives the body a real spin, ∝ ε; below what the step control resolves at its first
    quasi-impact the run ends "step size collapsed" (a reported failure, never a result)."""
    cyl = cylinder(3.0, 0.6)
    record, other = load_record(RECORD), load_record(RECORD[:-1] + "b")
    a = record.samples * record.scale
    b = other.samples[:a.size] * other.scale
    b = np.concatenate([b, np.zeros(a.size - b.size)]) * np.max(np.abs(a)) / np.max(np.abs(b))
    scale = amplitude * cyl.g * math.tan(cyl.alpha) / record.pga
    rows = []
    for eps in (0.0,) + tuple(fractions):
        pair = pair_of_records(f"diagonal + {eps:g} cross", record_motion("x", a, record.dt),
                               record_motion("y", a + eps * b, record.dt)).scaled(scale)
        r = simulate_cylinder(cyl, pair)
        rows.append({"fraction": eps, "status": r.status, "t_end": float(r.t[-1]), "steps": r.solver["steps"],
                     "quasi_impacts": r.quasi_impacts})
    return rows


def _row_ok(r: dict) -> bool:
    return (not r["failed"] and r["planar"] and r["same_outcome"] and r["off_line"] <= r["phi_bound"]
            and (r["chaotic"] or r["d_theta"] <= r["bound"]))


def _scipy_3d(method: str, cyl, pair, start: tuple, t_stop: float, rtol: float, atol: float) -> dict:
    """Eqs 5.22–5.23 (rigid contact) with scipy's ``solve_ivp`` from the state ``start`` = (t, θ, θ̇, φ, φ̇) our
    integrator hands over at θ_seed after an uplift, restarted at every record sample, to ``t_stop`` [s]."""
    from scipy.integrate import solve_ivp
    par = parameters(cyl.R, cyl.alpha, cyl.g)
    out = np.zeros(4)
    dt, sx, sy, scale = pair.dt, pair.x, pair.y, pair.scale

    def f(t, y):
        i = min(int(t / dt), sx.size - 2)
        w = t / dt - i
        rhs_ground(y, out, par, scale * (sx[i] + w * (sx[i + 1] - sx[i])), scale * (sy[i] + w * (sy[i + 1] - sy[i])))
        return out.copy()

    t, y = start[0], np.array(start[1:], dtype=float)
    t0 = time.perf_counter()
    while t < t_stop - 1e-12:
        t_next = min(t_stop, (math.floor(t / dt + 1e-9) + 1) * dt)
        try:
            sol = solve_ivp(f, (t, t_next), y, method=method.split()[-1], rtol=rtol, atol=atol)
        except Exception as exc:  # a crash is the measurement
            return {"ok": False, "t": t, "theta": float(y[0]), "why": f"{type(exc).__name__}: {exc}"[:90],
                    "seconds": time.perf_counter() - t0}
        if sol.y.size and np.min(sol.y[0]) < 0.0:
            k = int(np.argmax(sol.y[0] < 0.0))
            return {"ok": False, "t": float(sol.t[k]), "theta": float(sol.y[0, k]),
                    "why": "θ < 0: stepped through the apex, out of the equations' domain θ ≥ 0",
                    "seconds": time.perf_counter() - t0}
        if sol.status != 0:
            return {"ok": False, "t": float(sol.t[-1]), "theta": float(sol.y[0, -1]), "why": sol.message,
                    "seconds": time.perf_counter() - t0}
        t, y = t_next, sol.y[:, -1]
    return {"ok": True, "t": t, "theta": float(y[0]), "phi": float(y[2]), "why": "",
            "seconds": time.perf_counter() - t0}


def planar_azimuth(quick: bool = False, methods=ALL_METHODS) -> StabilityCase:
    """A planar motion along any azimuth on the 3D cylinder: two components along β against one along x."""
    azimuths = (0.0, 45.0, 200.0) if quick else AZIMUTHS_DEG
    amplitudes = (0.9, 1.2, 2.0) if quick else AMPLITUDES
    rows = [r for contact in ("rigid", "spring-dashpot") for r in sweep(contact, azimuths, amplitudes)]
    # the 3D equations alone on the diagonal at 1.5 g tan α (rigid): ours without the reduction, and scipy's
    cyl = cylinder(3.0, 0.6)
    record = load_record(RECORD)
    scale = 1.5 * cyl.g * math.tan(cyl.alpha) / record.pga
    diagonal = along(record, math.radians(45.0)).scaled(scale)
    plain = simulate_cylinder(cyl, diagonal, planar_reduction=False)
    reduced = simulate_cylinder(cyl, diagonal, output_dt=GRID)
    x_ref = simulate_cylinder(cyl, pair_of_records(record.name, record, None).scaled(scale), output_dt=GRID)
    seed = plain.solver["theta_seed"]
    k = int(np.argmax(plain.theta >= seed))
    start = (plain.t[k], plain.theta[k], plain.thetadot[k], plain.phi[k], plain.phidot[k])
    crossing = float(reduced.times_of("planar-crossing")[0])
    cross = cross_component((1e-12, 1e-9) if quick else CROSS_FRACTIONS)
    collapsed = [c["fraction"] for c in cross if c["status"] not in COMPLETED]
    resolved = [c for c in cross if c["status"] in COMPLETED and c["fraction"] > max(collapsed, default=0.0)]
    k_stop = int(round((crossing + 1.0) / GRID))         # a second past the first crossing, on the grid
    theta_stop = _on_grid(x_ref)[k_stop]
    outcomes = []
    bad = [r for r in rows if not _row_ok(r)]
    compared = [r for r in rows if not r["chaotic"] and r["uplifted"]]
    chaotic = min((r["crossings"] for r in rows if r["chaotic"]), default=0)
    for m in methods:
        if m == "rockdesign":
            worst = max(compared, key=lambda r: r["d_theta"] / r["bound"])
            detail = (f"{len(rows) - len(bad)} of {len(rows)} runs agree with the rotated single component: the same "
                      f"outcome ({sum(r['overturned'] for r in rows)} overturned, "
                      f"{sum(r['uplifted'] and not r['overturned'] for r in rows)} rocked, "
                      f"{sum(not r['uplifted'] for r in rows)} never uplifted), φ on the line "
                      f"(≤ {max(r['off_line'] for r in rows):.1e} rad), max |Δθ| {max(r['d_theta'] for r in compared):.1e} rad "
                      f"(at most {worst['d_theta'] / worst['bound']:.2g} of the tolerance bound)"
                      + (f"; {sum(r['chaotic'] for r in rows)} micro-rocking runs ({chaotic:,} crossings and more) "
                         "chaotic at round-off level, θ(t) not comparable: their reference moves as much under a 4ε "
                         "change of its input" if chaotic else ""))
            outcomes.append(Outcome(m, "ok" if not bad else "fails", detail, {"rows": rows}))
        else:
            s = _scipy_3d(m, cyl, diagonal, start, k_stop * GRID, 1e-10, 1e-12)
            if s["ok"]:
                s["d_theta"] = abs(s["theta"] - theta_stop)
                s["off_line"] = abs(math.remainder(s["phi"] - math.pi / 4.0, math.pi))
                s["ok"] = s["d_theta"] <= 1e-6 and s["off_line"] <= 1e-6
                detail = (f"passes the apex at t = {crossing:.6f} s, but 1 s later θ is {s['d_theta']:.1e} rad off the "
                          f"planar motion and φ {s['off_line']:.1e} rad off its line (rtol 1e-10)")
            else:
                detail = (f"the 3D equations from the same state stop at t = {s['t']:.6f} s (θ = {s['theta']:.1e} "
                          f"rad): {s['why']}")
            outcomes.append(Outcome(m, "ok" if s["ok"] else "fails", detail, s))
    plain_end = (f"t = {plain.t[-1]:.6f} s, θ = {plain.theta[-1]:.1e} rad, φ̇ = {plain.phidot[-1]:.1e} rad/s")
    ratio = max((r["d_theta"] / r["bound"] for r in compared), default=0.0)
    behaviour = (f"Integrates a motion along one line as the planar cylinder it is (φ̇ ≡ 0, Eq 5.26), whatever its azimuth: "
                 f"{len(rows) - len(bad)} of {len(rows)} runs agree with the rotated single component (θ within "
                 f"{ratio:.2g} of the tolerance bound where comparable). The reduction holds from an uplift for as long "
                 "as every piece of the excitation lies on the line of the uplift force, however the motion is given "
                 "(one component, two equal or proportional ones, a rotated record, the tail of a pair whose other "
                 "component has ended); where a piece leaves the line the 3D equations take over. Without it the 3D "
                 "equations carry a round-off spin into the first return to θ = 0 and collapse the step size there "
                 f"({plain_end}, where the planar run crosses); scipy's integrators of the same equations collapse, "
                 "step through θ = 0, or pass it off the line (their rows). "
                 + (f"What remains is a cross component that is real but too small for the step control: added to the "
                    f"diagonal at {', '.join(f'{c:g}' for c in collapsed)} × the PGA it gives a spin whose first "
                    "quasi-impact collapses the step size (reported as a failure, exit 2)"
                    + (f"; from {resolved[0]['fraction']:g} on the quasi-impacts are resolved and the cylinder "
                       f"overturns at t = {resolved[0]['t_end']:.4f} s, against {cross[0]['t_end']:.4f} s on the line "
                       "— the limit of a vanishing spin is 3D, not planar (each quasi-impact turns φ by ±(2π − Δφ), "
                       "Eq 5.38)" if resolved else "")
                    if collapsed else "A cross component above round-off is resolved at every size tried"))
    data = {"rows": rows, "cross": cross, "x_t": x_ref.t, "x_theta": x_ref.theta, "d_t": reduced.t, "d_theta": reduced.theta,
            "plain_t": plain.t, "plain_theta": plain.theta, "scale": scale}
    engine = {"run": "45°, 1.5 × g tan α, rigid", "status": reduced.status, "quasi_impacts": reduced.quasi_impacts,
              "steps": reduced.solver["steps"], "rejected_steps": reduced.solver["rejected_steps"],
              "function_evaluations": reduced.solver["rhs_evaluations"], "rest_entries": reduced.solver["rest_entries"],
              "without_reduction": plain.status}
    return StabilityCase("planar-azimuth", "A planar motion along any azimuth (3D cylinder)",
                         f"the template cylinder (2H = 3 m, 2B = 0.6 m; rigid and spring–dashpot contacts) under FEMA "
                         f"P695 {RECORD} given as two components along β = {', '.join(f'{a:g}' for a in azimuths)}° "
                         f"(ü_gx = a cosβ, ü_gy = a sinβ), at resultant PGA / g tan α = "
                         f"{', '.join(f'{a:g}' for a in amplitudes)}, rtol 1e-10; reference: the record alone along x "
                         f"at the same amplitude. θ(t) compared on a {GRID:g}-s dense-output grid against the bound "
                         "(N_β + N_x) √n (atol + rtol θ_ot) of the two runs' step control; φ against the line β mod π. "
                         "scipy: Eqs 5.22–5.23 from our state at θ_seed after the uplift, on the diagonal at 1.5 g tan α.",
                         outcomes, engine, behaviour, _plot_azimuth, data)


def _plot_azimuth(case: StabilityCase):
    d = case.data
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(1, 2, figsize=(11.0, 3.6))
        ax = axes[0]
        ax.plot(d["x_t"], d["x_theta"], color="k", lw=1.6, label="record alone along x")
        ax.plot(d["d_t"], d["d_theta"], color=COLORS["rockdesign"], lw=0.8, ls="--", label="along 45° (two components)")
        ax.plot(d["plain_t"][-1], max(d["plain_theta"][-1], 1e-9), "x", color="0.3", ms=9,
                label="3D equations alone: step size collapsed")
        ax.set_xlim(d["x_t"][np.argmax(d["x_theta"] > 0)] - 0.5, d["x_t"][-1] + 0.2)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("θ [rad]")
        ax.set_title("1.5 × g tan α, rigid contact", fontsize=8, loc="left")
        ax.legend(fontsize=6.5)
        ax = axes[1]
        for contact, marker in (("rigid", "o"), ("spring-dashpot", "s")):
            rows = [r for r in d["rows"] if r["contact"] == contact and r["uplifted"] and not r["chaotic"]]
            ax.semilogy([r["amplitude"] + 0.004 * r["azimuth"] / 45.0 for r in rows],
                        [max(r["d_theta"] / r["bound"], 1e-12) for r in rows], marker, ms=3.5, ls="none",
                        color=COLORS["rockdesign"] if contact == "rigid" else "C0", label=f"{contact}: |Δθ| / bound")
        ax.axhline(1.0, color="k", ls=":", lw=0.8, label="tolerance bound")
        ax.set_xlabel("resultant PGA / g tan α (azimuths side by side)")
        ax.set_ylabel("max |Δθ| / bound (0 drawn at 1e-12)")
        ax.legend(fontsize=6.5)
        fig.tight_layout()
        return fig
