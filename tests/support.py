"""Systems and constants shared by the tests (import as ``from support import ...``)."""
from __future__ import annotations

import math

from rockdesign.planar.system import Column, RockingSystem, Superstructure

G = 9.81


def block_from_p(p: float, tan_alpha: float, lam: float = 1 / 3, g: float = G, name="block") -> RockingSystem:
    """A block with frequency parameter p [1/s] (Eq 3.13) and slenderness tan α."""
    R = g / (p * p * (1 + lam))
    a = math.atan(tan_alpha)
    return RockingSystem(name, "column", Column(R * math.cos(a), R * math.sin(a), 1000.0, lam), g=g)


def table34_column(kind: str) -> RockingSystem:
    """The five oscillators of thesis Table 3.4 (2H = 3 m, tan α = 0.1, tan α' = 0.2, λ = 1/3)."""
    H, B, Be = 1.5, 0.15, 0.3
    cols = {
        "B1": Column(H, B, 1000.0, 1 / 3),
        "B2ec": Column(H, B, 1000.0, 1 / 3, "curved", Be, 0.25 * 2 * H),
        "B3ec": Column(H, B, 1000.0, 1 / 3, "curved", Be, 0.5 * 2 * H),
        "B4ec": Column(H, B, 1000.0, 1 / 3, "curved", Be, 1.0 * 2 * H),
        "B5ef": Column(H, B, 1000.0, 1 / 3, "flat", Be),
    }
    rule = "thesis-eq-3.39" if kind == "B5ef" else "theory"
    return RockingSystem(kind, "column", cols[kind], restitution_rule=rule, g=G)


def reference_podium(omega_s_over_p: float = 6.0, zeta: float = 0.01, correction: bool = True,
                     gamma: float = 10.0, eta: float = 5.0) -> RockingSystem:
    """Thesis Sec 4.2 reference podium: 2H = 3 m, tan α = 0.15, λ = 1/3, γ = 10, η = 5."""
    H, B, lam = 1.5, 0.225, 1 / 3
    p = math.sqrt(G / (math.hypot(H, B) * (1 + lam)))
    m_c = 1000.0
    sup = Superstructure(eta * gamma * m_c, omega_s_over_p * p, zeta, correction)
    return RockingSystem("podium", "podium", Column(H, B, m_c, lam), 1, gamma * m_c, sup, g=G)


TWO_RECORD_LIMIT = ('acceptance = "binomial"\n'
                    "overturn_probability_limit = 0.8   # two ground motions: the one-sided 95 % bound with 0 "
                    "overturns is 0.776")
"""Small test suites: the binomial rule with a limit two ground motions can show (ASCE 7's rule needs 11)."""


def stocky_podium_toml(records=("p695-ff/12a", "p695-ff/15b"), pga: str = "0.1 g",
                       analysis: str = TWO_RECORD_LIMIT, height: str = "3.0 m") -> str:
    """A small, quick podium project file (rigid superstructure, built-in records scaled to ``pga``)."""
    listed = ", ".join(f'"{r}"' for r in records)
    return f"""\
[project]
name = "stocky podium"

[podium]
columns = 20
cap_beam_mass = "200 t"
height = "{height}"
width = "0.6 m"
mass = "2.7 t"
mass_distribution = 0.3333

[superstructure]
mass = "600 t"
period = "rigid"

[excitation]
records = [{listed}]
scale = {{ method = "pga", target = "{pga}" }}

[analysis]
overturn = "static"
{analysis}
"""


def brute_first_factors(project, result, factors_of) -> list:
    """Each record's first overturning factor of a check ``result`` by brute force: every factor of
    ``factors_of(i)`` analysed at the scans' tolerance (no early stop, no bisection), the lowest that overturns;
    the design-level overturn counts at 1 (as the check counts it).  The independent reference of the distance to
    the flip (tests/checks/test_flip_margin.py, benchmarks/flip_resolution.py)."""
    from rockdesign.planar.checks.runner import run_jobs
    a = project.analysis
    first = []
    for i, o in enumerate(result.records):
        fs = [float(f) for f in factors_of(i)]
        runs = run_jobs(project.system, result.selection.chosen, [o.motion] * len(fs), fs,
                        rtol=max(a.rtol, a.scan_rtol), atol=a.atol, free_vibration=a.free_vibration,
                        criterion=a.overturn, rest_velocity=a.rest_velocity, energy_stop=True,
                        stop_at_capacity=(a.overturn == "static"))
        hit = next((f for f, r in zip(fs, runs) if r.overturned), None)
        if o.run.overturned and (hit is None or hit > 1.0):
            hit = 1.0
        first.append(hit)
    return first

