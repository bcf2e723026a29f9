"""The data the planar report's figures draw, computed by the check (the report only draws them): plain arrays and
numbers in SI, kept on the check's result (``CheckResult.figure_data``), not in results.json.

    pushover_data(system)            -> {"theta" [rad], "force" F_R/(m_C g) [-], "theta_c" [rad], "beta" [rad], "radius" [m]}
    elastic_spectra(rule, motions)   -> {"periods" [s], "sd" [m], one row per record}
    report_figure_data(system, rule, motions) -> {"pushover": …, "spectra": …}
"""
from __future__ import annotations

import numpy as np

from ..design.geometry import rocking_geometry
from ..design.pushover import pushover_curve
from ...motions.spectra import motion_spectrum, period_grid

SPECTRUM_PERIODS = 160
"""Periods of the elastic spectra drawn in the report (log-spaced over the rule's band)."""


def pushover_data(system) -> dict:
    """The static pushover curve F_R/(m_C g) against θ of the system's column from θ = 0 to θc (Fig 3.15, Eqs
    3.18/3.48), with θc and, for curved extensions, the wedge angle β and the radius r of the arc."""
    geo = rocking_geometry(system.column)
    theta, force = pushover_curve(geo)
    return {"theta": np.asarray(theta, float), "force": np.asarray(force, float), "theta_c": float(geo.theta_c),
            "beta": float(geo.beta), "radius": float(geo.radius)}


def elastic_spectra(rule, motions, n_periods: int = SPECTRUM_PERIODS) -> dict:
    """Elastic displacement spectra of the scaled records at the rule's damping, on a log grid over its band."""
    periods = period_grid(rule.band, n_periods)
    sd = np.array([motion_spectrum(m, periods, rule.damping)[0] for m in motions]).reshape(len(motions), len(periods))
    return {"periods": periods, "sd": sd}


def report_figure_data(system, rule, motions) -> dict:
    """Everything the report's figures draw that results.json does not hold."""
    return {"pushover": pushover_data(system), "spectra": elastic_spectra(rule, motions)}
