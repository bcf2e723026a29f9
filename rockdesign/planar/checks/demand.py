"""What the rocking storey buys: the superstructure's force and drift demand against a fixed base (SPEC §13).

Per record (CONTRACT §6.2): the peak absolute acceleration of the superstructure |f_s| (= base shear /
m_T) from the elastic 2DOF podium model, its shear coefficient |f_s|/g, the peak drift |u_T − u_B|,
the same superstructure on a fixed base with the damping the user gave (ζ_s) under the same scaled record
(exact piecewise-linear SDOF, absolute acceleration) and their ratio — the force reduction rocking buys;
records whose ratio exceeds 1 are named.  Where the suite's target spectrum is known, its 5 % value at T_s
(the code's design acceleration) is shown beside the fixed base.  Over the suite: median,
84th percentile and maximum over the records that did not overturn, beside the base-shear coefficient
at which the columns uplift (tan α, Eq 3.34).

The demand always comes from the elastic 2DOF model when the superstructure has a period: if the
overturning statistics use the rigid-superstructure model, the suite is analysed once more with the
2DOF podium (and its overturning count is reported beside the rigid model's).  A rigid superstructure
has no elastic demand; frames (no superstructure) report the cap beam's peak acceleration between
impacts and its velocity jump per impact instead.
"""
from __future__ import annotations

import math

import numpy as np

from ..dynamics.eom import P_ZETA
from ..dynamics.model import ModelChoice, system_parameters
from ...motions.spectra import fixed_base_acceleration, motion_samples
from .runner import analysis_failed
from .runner import run_jobs

DEMAND_RTOL = 1e-8
"""Largest rtol of the analyses the demand is read from: the suite statistics (median, 84th percentile,
maximum) of the peak superstructure acceleration converge there on the example podiums (docs/tolerances.md,
"Superstructure demand"); a check run at a looser ``[analysis] rtol`` analyses the 2DOF suite again at this
tolerance for the demand."""


def stats_of(values) -> dict:
    """{median, p84, max} of ``values`` (numpy's linear-interpolation percentile), None entries for none."""
    v = np.asarray([x for x in values if x is not None and math.isfinite(x)], dtype=float)
    if v.size == 0:
        return {"median": None, "p84": None, "max": None}
    return {"median": float(np.median(v)), "p84": float(np.percentile(v, 84.0)), "max": float(v.max())}


def fixed_base_damping(system) -> float:
    """The damping ratio of the fixed-base reference: the damping the user gave the superstructure, ζ_s
    (SPEC §13) — the building as described, on a rigid base.  Not the 2DOF model's pre-uplift ζ_s/S_r under
    the damping correction (Eq 4.27), which is a device of the model to keep ζ_s after uplift; with it a
    record that never uplifts the storey has a force ratio slightly above 1 (the model's building is less
    damped before uplift than the one given)."""
    return float(system.superstructure.damping)


def model_damping(system) -> float:
    """The damping ratio the 2DOF podium gives the superstructure before uplift (Eq 4.3): ζ_s, or ζ_s/S_r with
    the damping correction (Eq 4.27)."""
    return float(system_parameters(system, ModelChoice("podium-2dof", "exact"))[P_ZETA])


def record_demand(run, motion, system, zeta: float | None = None) -> dict | None:
    """The per-record ``superstructure`` dict of CONTRACT §6.2 from a 2DOF run (a :class:`RunSummary`) and
    the scaled record (fixed base: damping ``zeta``, default :func:`fixed_base_damping`); None when the run
    carries no superstructure demand."""
    if run is None or run.superstructure_acceleration_max is None:
        return None
    s = system.superstructure
    accel, dt = motion_samples(motion)
    zeta = fixed_base_damping(system) if zeta is None else zeta
    fixed = fixed_base_acceleration(accel, dt, 2.0 * math.pi / s.omega_s, zeta)
    a = run.superstructure_acceleration_max
    return {"acceleration_max": a, "shear_coefficient_max": a / system.g, "drift_max": run.drift_max,
            "fixed_base_acceleration_max": fixed, "force_ratio": a / fixed if fixed > 0.0 else None,
            "model": "podium-2dof"}


def cap_beam_demand(run) -> dict | None:
    """Per-record cap-beam demand of a rigid-mass model: peak absolute acceleration between impacts [m/s²]
    and the largest velocity jump at an impact [m/s] (SPEC §13); None without one."""
    if run is None or run.cap_acceleration_max is None:
        return None
    return {"acceleration_max": run.cap_acceleration_max, "velocity_jump_max": run.cap_velocity_jump_max}


def superstructure_demand(system, chosen: ModelChoice, motions, runs, run_kw, uplift_acceleration: float,
                          stage=None, *, names=None, target=None):
    """(per-record ``superstructure`` dicts or None, per-record ``cap_beam`` dicts or None, the
    ``summary.superstructure`` dict of CONTRACT §6.2 and §7.2, the 2DOF runs used or None) of a planar check.

    ``runs`` are the suite's analyses with the ``chosen`` model; ``run_kw`` the keyword arguments of
    :func:`~rockdesign.planar.checks.runner.run_jobs` the check used; ``stage(name, total)`` a progress-stage
    factory (the check's), called only when analyses run.  The 2DOF suite is analysed again when the
    chosen model is not the 2DOF podium or ran at an rtol looser than :data:`DEMAND_RTOL`.
    ``names``: (record id, ground motion) of each motion — the records whose force ratio exceeds 1 are
    named.  ``target``: the suite's target spectrum (5 % damping, ``psa(periods)`` [m/s²] and ``describe``),
    when one is known: its value at T_s is the design acceleration shown beside the fixed base.
    """
    n = len(motions)
    g = system.g
    tan_alpha = uplift_acceleration / g
    summary = {"n_records": 0, "shear_coefficient": stats_of([]), "drift": stats_of([]), "force_ratio": stats_of([]),
               "uplift_base_shear_coefficient": tan_alpha, "fixed_base_damping": None, "note": ""}
    if system.kind != "podium":
        summary["note"] = "a solitary column carries no superstructure"
        return [None] * n, [None] * n, summary, None
    if system.superstructure is None or system.superstructure.rigid:
        what = ("no superstructure: the rocking frame's cap beam is a rigid mass" if system.superstructure is None
                else "the superstructure is declared rigid (no period): it moves with the cap beam as one rigid mass")
        caps = [cap_beam_demand(r) for r in runs]
        ok = [i for i in range(n) if not analysis_failed(runs[i].status) and not runs[i].overturned]
        summary.update({
            "n_records": len(ok),
            "note": (f"{what}, so no elastic demand exists. In the rigid-body model θ̇ jumps at an impact "
                     "(Eq 3.14/3.80), so the cap beam's acceleration is impulsive there: reported are its peak "
                     "absolute acceleration between impacts and its largest velocity jump per impact (an impulse "
                     "per unit mass), never a step-size-dependent peak; an elastic superstructure has no such "
                     "jump (its velocity is continuous at an impact, Eq 4.21)."),
            "cap_beam": {"acceleration": stats_of([caps[i]["acceleration_max"] for i in ok if caps[i]]),
                         "velocity_jump": stats_of([caps[i]["velocity_jump_max"] for i in ok if caps[i]])}})
        return [None] * n, caps, summary, None
    notes = []
    two_dof = ModelChoice("podium-2dof", chosen.equations)
    demand_runs = runs
    if chosen.structure != "podium-2dof" or run_kw["rtol"] > DEMAND_RTOL:
        kw = dict(run_kw, rtol=min(run_kw["rtol"], DEMAND_RTOL))
        progress = stage("superstructure demand (2DOF podium)", n) if stage else None
        demand_runs = run_jobs(system, two_dof, motions, [1.0] * n, progress=progress, **kw)
        if chosen.structure != "podium-2dof":
            notes.append(f"The overturning statistics use the {chosen.label} model (rigid superstructure); the "
                         f"demand comes from the elastic 2DOF podium ({two_dof.label}) run on the same records.")
        if run_kw["rtol"] > DEMAND_RTOL:
            notes.append(f"The demand analyses ran at rtol {kw['rtol']:g} (the demand's statistics converge there; "
                         f"the check's rtol is {run_kw['rtol']:g}).")
    zeta = fixed_base_damping(system)
    zeta_model = model_damping(system)
    per = [record_demand(r, m, system, zeta) for r, m in zip(demand_runs, motions)]
    ok = [i for i in range(n) if per[i] is not None and not analysis_failed(demand_runs[i].status)
          and not demand_runs[i].overturned and not analysis_failed(runs[i].status) and not runs[i].overturned]
    n_ot_2dof = sum(r.overturned for r in demand_runs if not analysis_failed(r.status))
    n_ot_chosen = sum(r.overturned for r in runs if not analysis_failed(r.status))
    if chosen.structure != "podium-2dof":
        summary["n_overturned_2dof"] = n_ot_2dof
        summary["n_overturned_model"] = n_ot_chosen
        if n_ot_2dof != n_ot_chosen:
            notes.append(f"The 2DOF podium overturns under {n_ot_2dof} record{'' if n_ot_2dof == 1 else 's'}, the "
                         f"{chosen.label} model under "
                         f"{n_ot_chosen}.")
    s = system.superstructure
    period = 2.0 * math.pi / s.omega_s
    notes.append(f"Statistics over the {len(ok)} of {n} records that overturned in neither analysis. Shear "
                 "coefficient = peak |f_s|/g, f_s = ω_s²(u_T − u_B) + 2ζ_s ω_s(u̇_T − u̇_B) (the superstructure's "
                 "absolute acceleration, Eq 4.9), sampled at every record sample and on both sides of every impact; "
                 f"fixed base: the building as given (T_s = {period:.3g} s, ζ_s = {100 * zeta:.3g} %) on a rigid base, "
                 "exact for the piecewise-linear record. "
                 f"The columns uplift at a quasi-static base-shear coefficient tan α = {tan_alpha:.4g} (Eq 3.34); the "
                 "superstructure's dynamic response can exceed it.")
    if s.damping_correction:
        notes.append(f"Damping correction (Eq 4.27): the 2DOF model gives the superstructure ζ_s/S_r = "
                     f"{100 * zeta_model:.3g} % before uplift so that it keeps ζ_s = {100 * zeta:.3g} % while the "
                     "storey rocks (ζ_su = S_r ζ_in); the fixed base keeps the damping given, so a record too weak "
                     "to uplift the storey gives a force ratio slightly above 1.")
    ratios = [per[i]["force_ratio"] for i in ok]
    above = [i for i in ok if per[i]["force_ratio"] is not None and per[i]["force_ratio"] > 1.0]
    ids = [names[i] if names else (f"record {i + 1}", f"record {i + 1}") for i in range(n)]
    above_gm = list(dict.fromkeys(ids[i][1] for i in above))
    if above:
        notes.append(f"The rocking storey raises the superstructure's force above the fixed base's under "
                     f"{len(above)} of {len(ok)} records ({len(above_gm)} ground motion"
                     f"{'s' if len(above_gm) != 1 else ''}: {', '.join(above_gm)}).")
    summary.update({
        "n_records": len(ok),
        "shear_coefficient": stats_of([per[i]["shear_coefficient_max"] for i in ok]),
        "drift": stats_of([per[i]["drift_max"] for i in ok]),
        "force_ratio": stats_of(ratios),
        "fixed_base_shear_coefficient": stats_of([per[i]["fixed_base_acceleration_max"] / g for i in ok]),
        "fixed_base_damping": zeta,
        "model_damping_before_uplift": zeta_model,
        "force_ratio_above_one": {"n_records": len(above), "records": [ids[i][0] for i in above],
                                  "ground_motions": above_gm,
                                  "force_ratio": {ids[i][0]: per[i]["force_ratio"] for i in above}},
    })
    if target is not None:
        design = float(np.asarray(target.psa(np.array([period])), dtype=float)[0])
        summary.update({
            "design_spectrum_acceleration": design,
            "design_spectrum_shear_coefficient": design / g,
            "design_spectrum_force_ratio": stats_of([per[i]["acceleration_max"] / design for i in ok]),
        })
        notes.append(f"Design spectrum: the suite's 5 % target at T_s = {period:.3g} s is {design / g:.3g} g "
                     "(the spectrum the records were scaled against), what a code design with 5 % damping would use.")
    summary["note"] = " ".join(notes)
    return per, [None] * n, summary, demand_runs


def governing_demand_history(system, outcomes, chosen: ModelChoice, a):
    """(record id, 2DOF :class:`~rockdesign.planar.dynamics.response.Response`) of the record with the largest
    superstructure shear coefficient among those that did not overturn — the time history of a_T and the
    drift the report draws; None without an elastic superstructure."""
    rows = [o for o in outcomes if o.superstructure is not None and not o.run.overturned
            and not analysis_failed(o.run.status)]
    if not rows:
        return None
    o = max(rows, key=lambda o: o.superstructure["acceleration_max"])
    from ..dynamics.simulate import simulate
    response = simulate(system, o.motion, model=chosen.equations, structure="podium-2dof",
                        rtol=min(a.rtol, DEMAND_RTOL), atol=a.atol, t_end=o.motion.duration + a.free_vibration,
                        overturn=a.overturn, rest_velocity=a.rest_velocity)
    return o.id, response
