"""The perturbation draws of a passing cylinder variant in the design grid (SPEC §15,
:mod:`rockdesign.design_space.grid`): the runs of the check's perturbation ensemble (same seed), one draw
after the other, stopping at the first draw in which the design-level acceptance rule fails."""
from __future__ import annotations

from ..acceptance.perturbations import TOLERANCE_FACTOR, draw_words, perturbations
from ..acceptance.rule import count_rule
from .batch import PairRunner
from .check import cylinder_rule


def grid_draws(result, *, records, executor):
    """The draws of a cylinder variant that passes at nominal values: ``ensemble_size`` runs of the whole suite,
    each pair's amplitude × (1 ± 0.1 %) and the tolerances ÷ 10, as the check's ensemble robustness criterion
    runs them (the cylinder has no c_r: its impacts follow from its geometry, thesis Sec 5.5.1).  A draw fails
    when the design-level rule fails in it; ``records``: the grid's :class:`~rockdesign.cylinder.check.SuitePairs`
    (its 3D analyses on ``executor``, one batch per draw; None: this process).  Returns ``{"n", "failed", "size",
    "first_failure", "what"}`` (see :meth:`rockdesign.kinds.base.StructureKind.grid_draws`)."""
    project = result.project
    cyl, a = project.system, project.analysis
    rule = cylinder_rule(a)
    outcomes = result.records
    ok = [not o.run.failed for o in outcomes]      # as the check's ensemble robustness criterion counts
    valid = [o for o in outcomes if not o.run.failed]
    size, n = a.ensemble_size or 0, len(records.pairs)
    amplitude, _ = perturbations(n, size, a.seed)
    what = f"the suite with {draw_words(restitution=False)}"
    runner = PairRunner(cyl, a, executor=executor)
    for m in range(size):
        draw = [i for i in range(n) if ok[i]]
        runs = runner([(records.pairs[i][1].scaled(records.factors[i] * amplitude[m, i]), a.rtol * TOLERANCE_FACTOR,
                        a.atol * TOLERANCE_FACTOR) for i in draw])
        ids = {outcomes[i].id for i, run in zip(draw, runs) if run.overturned}
        holds, k, total, _ = count_rule(rule, valid, ids)
        if not holds:
            return {"n": m + 1, "failed": 1, "size": size,
                    "first_failure": f"perturbed suite run {m + 1} of {size}: {k} of {total} ground motions "
                                     "unacceptable", "what": what}
    return {"n": size, "failed": 0, "size": size, "first_failure": None, "what": what}
