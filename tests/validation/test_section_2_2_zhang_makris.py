"""The Zhang–Makris thresholds of thesis Sec 2.2 appear in a sine-pulse rocking spectrum.

Source: thesis Sec 2.2 / Fig 2.4 (Zhang & Makris): free-standing block p = 2.14 1/s, α = 0.25,
c_r = 0.81, one-sine pulse (Eq 2.20) at ω_p/p = 5, linearized EOM (uplift at g α), overturning at
|θ| = π/2.  Along a_p/(α g): safe, overturning with one impact, safe again (with θ_max > α),
overturning without impact.  The brackets of the three boundaries (reference DOP853 bisection) and
ω_p, T_p are read from tests/validation/data/cases.json (sec2.2_ZM_*).

The spectrum's y axis is a_p/(g tan α) (CONTRACT §2), so a_p/(α g) = y · tan α / α.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from casedata import assert_case, case, expected
from rockdesign.planar.spectra import Axis, SpectrumRequest, compute_spectrum, parse_axis
from support import block_from_p

INPUTS = case("sec2.2_ZM_safe_upper")["inputs"]
ALPHA = INPUTS["alpha_rad"]
TO_ZM = math.tan(ALPHA) / ALPHA          # y (a_p/(g tan α)) → a_p/(α g)
THRESHOLDS = {"safe→1": tuple(expected("sec2.2_ZM_safe_upper")), "1→safe": tuple(expected("sec2.2_ZM_ot1_upper")),
              "safe→0": tuple(expected("sec2.2_ZM_safe2_upper"))}


@pytest.fixture(scope="module")
def system():
    return block_from_p(INPUTS["p_per_s"], math.tan(ALPHA)).with_restitution(INPUTS["c_r"])


def test_pulse_frequency_and_period():
    omega_p = INPUTS["omega_p_over_p"] * INPUTS["p_per_s"]
    assert_case("sec2.2_ZM_omega_p", [omega_p, 2 * math.pi / omega_p])


def _column(system, y_axis: Axis):
    req = SpectrumRequest("sine", parse_axis(f"omega_p/p:{INPUTS['omega_p_over_p']:g}", "x"), y_axis, equations="linear", overturn="dynamic")
    spec = compute_spectrum(system, req)
    labels = np.where(spec.overturned[:, 0], np.minimum(spec.impacts_before_overturn[:, 0], 2).astype(str), "safe")
    return spec.y * TO_ZM, labels, spec.theta_max_over_alpha[:, 0]


def test_sine_spectrum_column_has_the_four_zhang_makris_regions(system):
    zm, labels, psi = _column(system, Axis("ap/up", 0.0, 9.0 / TO_ZM, 361))
    runs = [labels[0]] + [labels[k] for k in range(1, labels.size) if labels[k] != labels[k - 1]]
    assert runs == ["safe", "1", "safe", "0"]
    edges = [k for k in range(1, labels.size) if labels[k] != labels[k - 1]]
    for k, (lo, hi) in zip(edges, THRESHOLDS.values()):
        assert zm[k - 1] < hi and zm[k] > lo            # the class changes between these grid rows
    first_safe = labels == "safe"
    first_safe[edges[1]:] = False
    assert psi[first_safe].max() <= 1.0                  # 1) safe with θ_max ≤ α
    second_safe = np.zeros_like(first_safe)
    second_safe[edges[1]:edges[2]] = True
    assert psi[second_safe].min() > 1.0                  # 3) safe again, with θ_max > α


@pytest.mark.parametrize("name", list(THRESHOLDS))
def test_fine_grid_locates_each_threshold(system, name):
    lo, hi = THRESHOLDS[name]
    centre = 0.5 * (lo + hi)
    # 41 rows, 5e-5 apart in a_p/(α g), around the published value
    axis = Axis("ap/up", (centre - 1e-3) / TO_ZM, (centre + 1e-3) / TO_ZM, 41)
    zm, labels, _ = _column(system, axis)
    changes = [k for k in range(1, labels.size) if labels[k] != labels[k - 1]]
    assert len(changes) == 1
    k = changes[0]
    before, after = {"safe→1": ("safe", "1"), "1→safe": ("1", "safe"), "safe→0": ("safe", "0")}[name]
    assert labels[k - 1] == before and labels[k] == after
    assert zm[k - 1] <= hi + 1e-9 and zm[k] >= lo - 1e-9   # the bracket overlaps the published one
    assert zm[k] - zm[k - 1] < 6e-5
