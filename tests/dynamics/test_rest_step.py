"""The exact step of a resting podium (rockdesign.planar.dynamics.rest_step, Eq 4.3 under a piecewise-linear record).

Checked against independent numbers: scipy's solve_ivp on the same oscillator at rtol 1e-12, and
scipy.signal.lsim (a matrix exponential with a first-order hold, i.e. the same exact solution computed
another way) for a whole resting history and for the time of the first uplift (Eq 4.7).
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy import signal
from scipy.integrate import solve_ivp

from rockdesign.planar.dynamics.eom import P_HYST, P_OMEGA, P_ZETA, uplift_condition
from rockdesign.planar.dynamics.model import ModelChoice, system_parameters
from rockdesign.planar.dynamics.rest_step import TAYLOR_BELOW, rest_state, rest_substeps
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import record_motion
from support import reference_podium


def _sp(omega, zeta):
    sp = np.zeros(32)
    sp[P_OMEGA] = omega
    sp[P_ZETA] = zeta
    return sp


@pytest.mark.parametrize("omega, zeta, tau", [(15.0, 0.02, 0.01), (60.0, 0.05, 0.007), (3.0, 0.0, 0.05),
                                              (25.0, 0.4, 0.013), (15.0, 0.02, 2e-5)])
def test_one_step_matches_solve_ivp(omega, zeta, tau):
    u0, v0, a0, a1 = 0.012, -0.3, 1.7, -2.4
    sol = solve_ivp(lambda t, y: [y[1], -(a0 + (a1 - a0) * t / tau) - omega ** 2 * y[0] - 2 * zeta * omega * y[1]],
                    (0.0, tau), [u0, v0], method="DOP853", rtol=1e-13, atol=1e-16)
    u1, v1 = rest_state.py_func(u0, v0, a0, a1, tau, _sp(omega, zeta))
    assert u1 == pytest.approx(sol.y[0, -1], rel=1e-10, abs=1e-15)
    assert v1 == pytest.approx(sol.y[1, -1], rel=1e-10, abs=1e-13)


def test_taylor_branch_joins_the_closed_form():
    omega, zeta = 20.0, 0.03
    sp = _sp(omega, zeta)
    tau = TAYLOR_BELOW / omega
    below = rest_state.py_func(0.01, 0.2, 1.0, 1.5, tau * (1 - 1e-9), sp)
    above = rest_state.py_func(0.01, 0.2, 1.0, 1.5, tau * (1 + 1e-9), sp)
    assert below[0] == pytest.approx(above[0], rel=1e-12)
    assert below[1] == pytest.approx(above[1], rel=1e-10)


def test_substeps_keep_the_phase_per_step_small():
    sp = _sp(40.0, 0.02)
    assert rest_substeps.py_func(0.005, sp) == 1          # ω h = 0.2
    assert rest_substeps.py_func(0.02, sp) == 2           # ω h = 0.8 → two steps of 0.4
    assert rest_substeps.py_func(10.0, sp) == 1000        # free vibration after the record


def _record(amplitude, dt=0.01, seconds=6.0):
    t = np.arange(0.0, seconds, dt)
    acc = amplitude * (np.sin(2 * np.pi * 1.3 * t) + 0.6 * np.sin(2 * np.pi * 3.1 * t + 0.4)) * np.minimum(1, t)
    return record_motion("synthetic", acc, dt), acc


def _lsim(omega, zeta, t, acc, x0=(0.0, 0.0)):
    sdof = signal.StateSpace([[0.0, 1.0], [-omega ** 2, -2 * zeta * omega]], [[0.0], [-1.0]], np.eye(2), [[0.0], [0.0]])
    _, _, x = signal.lsim(sdof, acc, t, X0=x0, interp=True)
    return x


def test_resting_podium_follows_the_oscillator():
    """Below uplift the engine's u_T is the fixed-base oscillator's displacement at every sample."""
    system = reference_podium()
    sp = system_parameters(system, ModelChoice("podium-2dof", "exact"))
    motion, acc = _record(0.02)
    r = simulate(system, motion, structure="podium-2dof", t_end=6.0)
    assert r.uplift_time is None
    x = _lsim(sp[P_OMEGA], sp[P_ZETA], np.arange(acc.size) * 0.01, acc)
    n = min(x.shape[0], r.u_T.size)
    assert np.abs(r.u_T[:n] - x[:n, 0]).max() <= 1e-10 * np.abs(x[:, 0]).max()


def test_first_uplift_is_the_first_crossing_of_eq_4_7():
    """The uplift time equals the first crossing of the uplift criterion (Eq 4.7 above the hysteresis) on
    the oscillator's response computed by lsim on a 1-µs grid (linear interpolation between grid points)."""
    system = reference_podium()
    sp = system_parameters(system, ModelChoice("podium-2dof", "exact"))
    dt = 0.01
    for amplitude in (1.2, 2.5):
        motion, acc = _record(amplitude, dt)
        r = simulate(system, motion, structure="podium-2dof", t_end=6.0)
        assert r.uplift_time is not None
        t = np.arange(acc.size) * dt
        x = _lsim(sp[P_OMEGA], sp[P_ZETA], t, acc)
        crit = np.array([max(uplift_condition(1.0, a, u, v, sp), uplift_condition(-1.0, a, u, v, sp))
                         for a, (u, v) in zip(acc, x)]) - sp[P_HYST]
        k = int(np.argmax(crit >= 0.0))          # first sample at or above the threshold
        fine = np.linspace(t[k - 1], t[k], 10_001)
        xf = _lsim(sp[P_OMEGA], sp[P_ZETA], fine - fine[0], np.interp(fine, t, acc), x0=x[k - 1])
        af = np.interp(fine, t, acc)
        cf = np.array([max(uplift_condition(1.0, a, u, v, sp), uplift_condition(-1.0, a, u, v, sp))
                       for a, (u, v) in zip(af, xf)]) - sp[P_HYST]
        j = int(np.argmax(cf >= 0.0))
        t_cross = fine[j - 1] + (fine[j] - fine[j - 1]) * (-cf[j - 1]) / (cf[j] - cf[j - 1])
        assert r.uplift_time == pytest.approx(t_cross, abs=1e-9)
