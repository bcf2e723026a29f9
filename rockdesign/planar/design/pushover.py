"""Static pushover (restoring-force) curve of a rocking column through both contact phases (Fig 3.15).

With the contact kinematics of SPEC §3.1 the restoring force of one column, as a fraction of its
weight, is F_R/(m_C g) = w_C'(θ)/u_C'(θ): Eq 3.18 for a block (tan(α−θ)), Eq 3.48 in phase I
(N/D with N = R sin(α−θ) + r sin θ, D = R cos(α−θ) + r(1−cos θ)) and its phase-II counterpart.
It is also the ground acceleration (in g) that holds the tilt θ statically, for a frame or a
podium as well; the frame's force multiplies by (1+2γ)N (Eq 3.78).
"""
from __future__ import annotations

import numpy as np

from .kinematics import centre_kinematics
from .geometry import RockingGeometry


def restoring_force_ratio(theta: float, geometry: RockingGeometry) -> float:
    """F_R/(m_C g) [-] at tilt θ ≥ 0 (Eqs 3.18, 3.48; phase II per SPEC §2)."""
    phase = 1 if geometry.radius > 0.0 and theta <= geometry.beta else 2
    _, u1, _, _, w1, _ = centre_kinematics(theta, 1.0, phase, geometry.R, geometry.alpha,
                                           geometry.radius, geometry.beta)
    return w1 / u1


def restoring_stiffness_ratio(theta: float, geometry: RockingGeometry) -> float:
    """dF_R/dθ/(m_C g) [1/rad] at θ ≥ 0: (w_C''u_C' − w_C'u_C'')/u_C'² (corrected Eq 3.49 in phase I)."""
    phase = 1 if geometry.radius > 0.0 and theta <= geometry.beta else 2
    _, u1, u2, _, w1, w2 = centre_kinematics(theta, 1.0, phase, geometry.R, geometry.alpha,
                                             geometry.radius, geometry.beta)
    return (w2 * u1 - w1 * u2) / (u1 * u1)


def pushover_curve(geometry: RockingGeometry, n_points: int = 401, theta_max: float | None = None):
    """(θ [rad], F_R/(m_C g) [-]) from 0 to θc (or ``theta_max``), with β included as a grid point."""
    end = geometry.theta_c if theta_max is None else theta_max
    theta = np.linspace(0.0, end, n_points)
    if geometry.radius > 0.0 and 0.0 < geometry.beta < end:
        theta = np.unique(np.concatenate([theta, [geometry.beta]]))
    force = np.array([restoring_force_ratio(t, geometry) for t in theta])
    return theta, force


def post_uplift_stiffness_linear(rho: float, phase: int) -> float:
    """Linearized post-uplift stiffness k* [-]: k*_I = 2ρ − 1 (Eq 3.50), k*_II = −1 (Eq 3.53)."""
    return 2.0 * rho - 1.0 if phase == 1 else -1.0
