"""Verdicts that survive chaos: a seeded perturbation ensemble per record (thesis Ch. 7).

Rocking after many impacts is chaotic: a 0.03 % change of a record's amplitude can flip its
overturning outcome.  Each record is therefore re-analysed at the design level by an ensemble of
runs perturbed well inside the input's own accuracy — the amplitude by a factor uniform in
1 ± 0.1 %, c_r by a factor uniform in 1 ± 2 % (capped at 1) and the integrator tolerances one decade
tighter.  Per record this gives the fraction of runs that overturn; a record whose runs disagree with
each other or with the nominal analysis has an "outcome not robust".  The suite's P(overturn) is also
given as the mean of these fractions.

Each ensemble member shares one c_r factor across the suite (one batch of all records per member, on
all cores, with the compiled kernels of the check) and draws its own amplitude factor per record.
"""
from __future__ import annotations

import numpy as np

from ...acceptance.perturbations import AMPLITUDE_VARIATION, RESTITUTION_VARIATION, TOLERANCE_FACTOR, perturbations
from .runner import run_jobs

def run_ensembles(system, choice, motions, nominal, *, size: int, seed: int, rtol: float, atol: float,
                  free_vibration: float, criterion: str, rest_velocity: float, progress=None, executor=None) -> dict:
    """Analyse every design-level motion ``size`` times with perturbed amplitude, c_r and tolerance.

    Args:
        nominal: the nominal :class:`~rockdesign.planar.checks.runner.RunSummary` of each motion.
        rtol, atol: the check's tolerances (the ensemble uses them × 0.1).

    Returns:
        ``{"fractions": [...], "overturned": size × n bool array, "amplitude", "restitution"}``.
    """
    n = len(motions)
    amplitude, restitution = perturbations(n, size, seed)
    overturned = np.zeros((size, n), dtype=bool)
    for m in range(size):
        res = run_jobs(system, choice, motions, list(amplitude[m]), rtol=rtol * TOLERANCE_FACTOR,
                       atol=atol * TOLERANCE_FACTOR, free_vibration=free_vibration, criterion=criterion,
                       rest_velocity=rest_velocity, energy_stop=True, stop_at_capacity=(criterion == "static"),
                       restitution_factor=float(restitution[m]), executor=executor,
                       progress=(lambda d, m=m: progress(m * n + d)) if progress else None)
        overturned[m] = [r.overturned for r in res]
    fractions = overturned.mean(axis=0) if size else np.full(n, np.nan)
    nominal_ot = np.array([r.overturned for r in nominal], dtype=bool)
    robust = (overturned == nominal_ot[None, :]).all(axis=0)
    return {"fractions": fractions, "overturned": overturned, "robust": robust, "amplitude": amplitude,
            "restitution": restitution}


def ensemble_summary(ids, ensemble: dict, *, size: int, seed: int, rtol: float, atol: float,
                     nominal_overturned: int) -> dict:
    """The ``ensemble`` section of results.json: settings, suite P(overturn) from the per-record
    fractions, and the records whose outcome is not robust."""
    fr = ensemble["fractions"]
    robust = ensemble["robust"]
    return {
        "size": size, "seed": seed, "amplitude_variation": AMPLITUDE_VARIATION,
        "restitution_variation": RESTITUTION_VARIATION, "rtol": rtol * TOLERANCE_FACTOR,
        "atol": atol * TOLERANCE_FACTOR,
        "p_overturn": float(np.mean(fr)),
        "p_overturn_nominal": nominal_overturned / len(ids),
        "n_overturn_any": int(np.sum(fr > 0)),
        "n_not_robust": int(np.sum(~robust)),
        "records_not_robust": [i for i, ok in zip(ids, robust) if not ok],
    }


def record_fields(ensemble: dict | None, index: int) -> dict:
    """Per-record keys of results.json: ``ensemble_overturn_fraction`` and ``outcome_robust``."""
    if not ensemble:
        return {"ensemble_overturn_fraction": None, "outcome_robust": None}
    return {"ensemble_overturn_fraction": float(ensemble["fractions"][index]),
            "outcome_robust": bool(ensemble["robust"][index])}
