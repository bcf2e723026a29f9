"""Quiet steps (quiet_steps.quiet_step, _quiet_rest): accepted steps whose dense output is skipped.

The pinned outputs (tests/golden) prove that skipping changes no result on the examples (only the count
of function evaluations fell); these tests check the screening itself: the quintic Hermite interpolant is
exact on quintics, and a step with an extremum, an impact, a phase change or the first exceedance of θc
inside is never quiet.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.planar.dynamics import quiet_steps
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import pulse_motion
from support import block_from_p

quiet = quiet_steps.quiet_step.py_func
H = 0.01
K_DIP = 1.16 / H ** 2


def test_hermite_interpolant_is_exact_on_quintics():
    c = np.array([0.3, -1.2, 0.7, 2.1, -0.4, 0.9])   # p(x) = Σ c_k x^k on [0, 1]
    p = np.polynomial.Polynomial(c)
    d, dd = p.deriv(), p.deriv(2)
    ends = (p(0.0), d(0.0), dd(0.0), p(1.0), d(1.0), dd(1.0))
    for x in np.linspace(0.0, 1.0, 11):
        assert quiet_steps.hermite_value.py_func(x, *ends) == pytest.approx(p(x), abs=1e-13)
        assert quiet_steps.hermite_rate.py_func(x, *ends) == pytest.approx(d(x), abs=1e-12)


def _step(theta, h=0.01):
    """(y, y_new, f0, f1) of a rocking step whose θ(t) on [0, h] is the callable ``theta`` (θ, θ̇, θ̈)."""
    (a0, v0, c0), (a1, v1, c1) = theta(0.0), theta(h)
    y, y_new = np.array([a0, v0, 0.0, 0.0]), np.array([a1, v1, 0.0, 0.0])
    f0, f1 = np.array([v0, c0, 0.0, 0.0]), np.array([v1, c1, 0.0, 0.0])
    return y, y_new, f0, f1


def _block_quiet(theta, h=0.01, theta_c=0.2, exceeded=False):
    y, y_new, f0, f1 = _step(theta, h)
    return quiet(h, y, y_new, f0, f1, 8, 1.0, 2, False, 0.0, math.pi / 2, theta_c, exceeded, False, 0.0, 0.0,
                 np.zeros(1))


def test_monotone_step_away_from_levels_is_quiet():
    assert _block_quiet(lambda t: (0.05 + 0.3 * t + 2.0 * t * t, 0.3 + 4.0 * t, 4.0))


@pytest.mark.parametrize("theta, why", [
    (lambda t: (0.05 + 0.3 * t - 40.0 * t * t, 0.3 - 80.0 * t, -80.0), "an extremum inside (θ̇ = 0 at t = 3.75 ms)"),
    (lambda t: (0.001 - 0.3 * t, -0.3, 0.0), "impact: θ reaches 0 falling"),
    (lambda t: (0.198 + 0.3 * t, 0.3, 0.0), "first exceedance of θc = 0.2 inside"),
    (lambda t: (0.05 + 0.3 * t - K_DIP * (H * t * t / 2 - t ** 3 / 3), 0.3 - K_DIP * (H * t - t * t),
                -K_DIP * (H - 2 * t)), "θ̇ dips from 0.3 to 0.01 rad/s inside while both ends rise"),
])
def test_step_with_something_inside_is_not_quiet(theta, why):
    assert not _block_quiet(theta), why


def test_exceedance_already_recorded_does_not_prevent_quiet():
    assert _block_quiet(lambda t: (0.198 + 0.3 * t, 0.3, 0.0), exceeded=True)


def test_quiet_steps_save_evaluations_without_changing_the_history():
    """A block under a pulse: the quiet steps skip the DOP853 interpolant's 3 extra evaluations; the
    history at the output times (where no step is quiet) and the peak are those of every step scanned,
    which tests/dynamics/test_closed_form.py bounds against the closed form."""
    system = block_from_p(2.0, 0.15)
    pulse = pulse_motion("ricker-sym", 0.6 * 9.81, 0.5)
    full = simulate(system, pulse, method="dop853", rtol=1e-10, output_dt=1e-4)
    summary = simulate(system, pulse, method="dop853", rtol=1e-10, record_history=False)
    assert summary.theta_max_over_alpha == full.theta_max_over_alpha
    assert summary.impacts == full.impacts
    assert summary.diagnostics["steps"] == full.diagnostics["steps"]
    assert summary.diagnostics["function_evaluations"] < full.diagnostics["function_evaluations"]
