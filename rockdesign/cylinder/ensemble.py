"""The perturbation ensemble of a cylinder's check (thesis Ch. 7: rocking is chaotic, single histories are
not predictable): further draws of the whole suite of record pairs at the design level."""
from __future__ import annotations

import numpy as np

from ..acceptance.perturbations import AMPLITUDE_VARIATION, TOLERANCE_FACTOR, perturbations


def suite_ensembles(run, pairs, factors, nominal, a, progress=None) -> dict | None:
    """The perturbation ensemble (thesis Ch. 7): ``ensemble_size`` runs of the whole suite, each pair's
    amplitude × (1 ± 0.1 %) and the tolerances one decade tighter; None for ``ensemble_size = 0``.

    ``run(jobs, done)`` analyses a batch of scaled pairs in 3D (``overturned``), each job ``(pair, rtol, atol)``
    (a :class:`~rockdesign.cylinder.batch.PairRunner`: the whole ensemble is one batch); ``nominal``: the
    design-level runs of the pairs, as recorded (``factors``: their design scale factors)."""
    size, n = a.ensemble_size, len(pairs)
    if not size:
        return None
    amplitude, _ = perturbations(n, size, a.seed)
    jobs = [(pair.scaled(factors[i] * amplitude[m, i]), a.rtol * TOLERANCE_FACTOR, a.atol * TOLERANCE_FACTOR)
            for m in range(size) for i, pair in enumerate(pairs)]
    runs = run(jobs, None if progress is None else
               lambda k: progress(f"perturbation ensembles ({size} runs per pair)", k, size * n))
    overturned = np.array([r.overturned for r in runs], dtype=bool).reshape(size, n)
    nominal_ot = np.array([r.overturned for r in nominal], dtype=bool)
    fractions = overturned.mean(axis=0)
    robust = (overturned == nominal_ot[None, :]).all(axis=0)
    return {"overturned": overturned, "restitution": np.ones(size), "robust": robust, "fractions": fractions,
            "size": size, "seed": a.seed, "amplitude_variation": AMPLITUDE_VARIATION,
            "tolerance_factor": TOLERANCE_FACTOR, "p_overturn": float(fractions.mean()),
            "n_not_robust": int((~robust).sum())}
