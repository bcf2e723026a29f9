"""engine_accuracy: the engine against the closed form (SPEC §3.8), for the check report's appendix."""
from __future__ import annotations

import math

from rockdesign.planar.dynamics.accuracy import accuracy_sentence, engine_accuracy


def test_engine_accuracy_at_the_default_tolerance():
    acc = engine_accuracy()
    assert acc["rtol"] == 1e-10 and acc["atol"] == 1e-12
    assert acc["status"] == "completed"
    assert acc["impacts"] == acc["impacts_reference"] >= 5
    assert acc["max_abs_dtheta_rad"] < 1e-8
    assert acc["theta_max_error_rad"] < 1e-8
    assert acc["max_impact_time_error_s"] < 1e-8
    # the case is Table 3.4 B1: θ_max/α of the linearized, sampled pulse lies near the exact 1.19
    assert 1.1 < acc["theta_max_over_alpha"] < 1.3
    text = accuracy_sentence(acc)
    assert "1e-10" in text and "impact times" in text


def test_engine_accuracy_follows_the_tolerance():
    loose = engine_accuracy(1e-6)
    tight = engine_accuracy(1e-10)
    assert math.isfinite(loose["max_abs_dtheta_rad"])
    assert loose["max_abs_dtheta_rad"] > 10 * tight["max_abs_dtheta_rad"]
