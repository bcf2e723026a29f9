"""The energy bound that stops spectrum analyses early (docs/early_termination.md).

Claim: after the excitation ends, if the mechanical energy E is below the potential energy at the
current θ_max (with θ_max < θc), neither θ_max nor the overturning verdict can change. Tested
(1) against full-length runs of the same analyses — θ_max, exceedance, dynamic overturning and the
impacts before overturning must be identical — on random pulses and a record, for blocks (exact
and linearized), curved and flat extensions, frames/rigid superstructures and 2DOF podia; and
(2) on the premise of the proof: without ground motion E(t) never increases.
"""
from __future__ import annotations

import math
import zlib

import numpy as np
import pytest

from support import reference_podium, table34_column
from rockdesign.planar.dynamics.batch import batch_options, run_batch
from rockdesign.planar.dynamics.engine import integrate
from rockdesign.planar.dynamics.layout import (D_STATUS, D_STEPS, N_OPTIONS, O_ATOL, O_H_MAX, O_MAX_EVENTS, O_MAX_STEPS,
                                        O_RTOL, O_SCAN, O_T_END, ST_ENERGY_BOUND, S_DYNAMIC, S_EXCEEDED,
                                        S_IMPACTS_BEFORE_EXCEEDED, S_IMPACTS_BEFORE_OVERTURN, S_THETA_MAX, S_T_END)
from rockdesign.planar.dynamics.eom import P_BETA, P_RADIUS, P_TWO_DOF, total_energy
from rockdesign.planar.dynamics.model import ModelChoice, system_parameters
from rockdesign.motions.library import load_record
from rockdesign.motions.motion import PULSE_KINDS, no_motion, pulse_motion
from rockdesign.planar.system import Column, RockingSystem

SYSTEMS = {
    "block-exact": (lambda: table34_column("B1"), "block", "exact"),
    "block-linear": (lambda: table34_column("B1"), "block", "linear"),
    "curved-rho<rho_c": (lambda: table34_column("B2ec"), "block", "exact"),
    "curved-rho>rho_c": (lambda: table34_column("B4ec"), "block", "exact"),
    "curved-linear": (lambda: table34_column("B2ec"), "block", "linear"),
    # ρ = ½ linearized: zero rolling stiffness, θ(t) is a parabola that DP5 integrates exactly, steps grow
    # until every step ends on an impact, and the engine checks the bound only after event-free steps
    # (engine issue reported): the stop rarely triggers, results must still be identical
    "curved-linear-rho=1/2": (lambda: table34_column("B3ec"), "block", "linear"),
    "flat-extensions": (lambda: table34_column("B5ef"), "block", "exact"),
    "rigid-superstructure": (lambda: reference_podium(30.0), "rigid-superstructure", "exact"),
    "podium-2dof-ws/p=6": (lambda: reference_podium(6.0), "podium-2dof", "exact"),
    "podium-2dof-ws/p=3": (lambda: reference_podium(3.0), "podium-2dof", "exact"),
}


def _random_jobs(system, n_pulses, seed):
    rng = np.random.default_rng(seed)
    c = system.column
    p = math.sqrt(system.g / (math.hypot(c.half_height, c.half_width) * (1 + c.mass_distribution)))
    up = system.g * c.tan_alpha
    kinds = list(PULSE_KINDS)
    motions, scales = [], []
    for k in range(n_pulses):
        motions.append(pulse_motion(kinds[k % len(kinds)], rng.uniform(0.8, 10.0) * up,
                                    2 * math.pi / (rng.uniform(0.5, 12.0) * p)))
        scales.append(1.0)
    record = load_record("p695-ff/11a")
    for f in rng.uniform(0.5, 6.0, 4):
        motions.append(record)
        scales.append(f * up / record.pga)
    return motions, scales


@pytest.mark.parametrize("name", list(SYSTEMS))
def test_energy_stopped_runs_equal_full_length_runs(name):
    make, structure, equations = SYSTEMS[name]
    system = make()
    sp = system_parameters(system, ModelChoice(structure, equations))
    motions, scales = _random_jobs(system, 40 if "2dof" in name else 120, seed=zlib.crc32(name.encode()))
    t_ends = [m.duration + 10.0 for m in motions]
    s_stop, d_stop = run_batch(sp, motions, scales, t_ends, batch_options(energy_stop=True))
    s_full, d_full = run_batch(sp, motions, scales, t_ends, batch_options(energy_stop=False))
    for k in (S_THETA_MAX, S_EXCEEDED, S_DYNAMIC, S_IMPACTS_BEFORE_OVERTURN, S_IMPACTS_BEFORE_EXCEEDED):
        np.testing.assert_array_equal(s_stop[:, k], s_full[:, k])
    stopped = d_stop[:, D_STATUS] == ST_ENERGY_BOUND
    durations = np.array([m.duration for m in motions])
    # a stop never happens during the excitation or after the capacity was exceeded
    assert np.all(s_stop[stopped, S_T_END] >= durations[stopped])
    assert not np.any(s_stop[stopped, S_EXCEEDED])
    if name == "curved-linear-rho=1/2":
        return
    # the bound is not vacuous: it stops a good share of the analyses, earlier and cheaper
    assert stopped.mean() > 0.25
    assert np.mean(s_stop[stopped, S_T_END] < np.asarray(t_ends)[stopped] - 1.0) > 0.9
    assert d_stop[:, D_STEPS].sum() < 0.8 * d_full[:, D_STEPS].sum()


def _energy_history(system, structure, theta0, t_end=8.0):
    sp = system_parameters(system, ModelChoice(structure, "exact"))
    opts = np.zeros(N_OPTIONS)
    opts[O_T_END], opts[O_RTOL], opts[O_ATOL], opts[O_H_MAX] = t_end, 1e-11, 1e-13, math.inf
    opts[O_MAX_STEPS], opts[O_SCAN], opts[O_MAX_EVENTS] = 1e7, 8, 1e6
    t_out = np.linspace(0.0, t_end, 4001)
    out_y = np.zeros((t_out.size, 4))
    ev = (np.zeros(0), np.zeros(0, dtype=np.int64), np.zeros((0, 4)))
    m = no_motion()
    y0 = np.array([theta0, 0.0, 0.0, 0.0])
    if sp[P_TWO_DOF] != 0.0:
        from rockdesign.planar.dynamics.transitions import top_displacements
        y0[2] = top_displacements(np.array([theta0]), sp)[0]  # released with an undeformed superstructure
    summary, diag, n = integrate(sp, m.kind, m.params, m.samples, y0, 1.0, 0.0, opts, t_out, out_y, *ev)
    energies = []
    for y in out_y[:n]:
        if y[0] == 0.0 and y[1] == 0.0:
            energies.append(total_energy(y, False, 1.0, 1, sp))
        elif y[0] != 0.0:
            side = 1.0 if y[0] > 0 else -1.0
            phase = 2 if (sp[P_RADIUS] != 0.0 and abs(y[0]) > sp[P_BETA]) else 1
            energies.append(total_energy(y, True, side, phase, sp))
    return np.array(energies), int(summary[3])


@pytest.mark.parametrize("system,structure", [
    (table34_column("B1"), "block"), (table34_column("B2ec"), "block"), (table34_column("B4ec"), "block"),
    (table34_column("B5ef"), "block"), (reference_podium(30.0), "rigid-superstructure"),
    (reference_podium(3.0), "podium-2dof"), (reference_podium(6.0, zeta=0.0), "podium-2dof")])
def test_energy_never_increases_without_ground_motion(system, structure):
    alpha = math.atan(system.column.tan_alpha)
    e, impacts = _energy_history(system, structure, 0.8 * alpha)
    assert impacts >= 3                      # the history includes impacts (and, for curved bases, phases)
    assert e[-1] < 0.9 * e[0]                # impacts dissipate
    increase = np.diff(e)
    assert increase.max() <= 1e-7 * e[0]     # never increases beyond the integration error


def test_perfectly_elastic_impacts_agree_to_integration_accuracy():
    # c_r = 1: no dissipation after the pulse; E stays at V(θ_max) up to integration error, so a stop
    # may rest on that error — the peaks of the full run can then differ only at that level
    s = RockingSystem("elastic", "column", Column(1.5, 0.15, 1000.0, 1 / 3)).with_restitution(1.0)
    e, impacts = _energy_history(s, "block", 0.5 * math.atan(0.1), t_end=6.0)
    assert impacts >= 4
    assert np.ptp(e) <= 1e-7 * e[0]
    sp = system_parameters(s, ModelChoice("block", "exact"))
    motions, scales = _random_jobs(s, 120, seed=7)
    t_ends = [m.duration + 10.0 for m in motions]
    s_stop, d_stop = run_batch(sp, motions, scales, t_ends, batch_options(energy_stop=True))
    s_full, _ = run_batch(sp, motions, scales, t_ends, batch_options(energy_stop=False))
    assert np.any(d_stop[:, D_STATUS] == ST_ENERGY_BOUND)
    np.testing.assert_allclose(s_stop[:, S_THETA_MAX], s_full[:, S_THETA_MAX], rtol=1e-9, atol=0.0)
    for k in (S_EXCEEDED, S_DYNAMIC, S_IMPACTS_BEFORE_OVERTURN):
        np.testing.assert_array_equal(s_stop[:, k], s_full[:, k])
