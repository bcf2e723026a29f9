"""The Zhang–Makris thresholds of thesis Sec 2.2 appear in a sine-pulse rocking spectrum.

Sec 2.2 / Fig 2.4 (cases.json sec2.2_ZM_*): free-standing block p = 2.14 1/s, α = 0.25, c_r = 0.81,
one-sine pulse (Eq 2.20) at ω_p/p = 5, linearized EOM (uplift at g α), overturning at |θ| = π/2.
Along a_p/(α g): safe up to 3.0186, overturning with one impact up to 6.3181, safe again (with
θ_max > α) up to 7.1681, overturning without impact above. Published brackets (reference DOP853
bisection): [3.01857, 3.01863], [6.31805, 6.31811], [7.16811, 7.16816].

The spectrum's y axis is a_p/(g tan α) (CONTRACT §2), so a_p/(α g) = y · tan α / α.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from support import block_from_p
from rockdesign.spectra import Axis, SpectrumRequest, compute_spectrum, parse_axis

ALPHA = 0.25
TO_ZM = math.tan(ALPHA) / ALPHA          # y (a_p/(g tan α)) → a_p/(α g)
THRESHOLDS = {"safe→1": (3.01857, 3.01863), "1→safe": (6.31805, 6.31811), "safe→0": (7.16811, 7.16816)}


@pytest.fixture(scope="module")
def system():
    return block_from_p(2.14, math.tan(ALPHA)).with_restitution(0.81)


def _column(system, y_axis: Axis):
    req = SpectrumRequest("sine", parse_axis("omega_p/p:5", "x"), y_axis, equations="linear", overturn="dynamic")
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
