"""Speed against accuracy: the work-precision study, the solver stability study, engine accuracy.

Modules: :mod:`~rockdesign.bench.problems` (3 excitations × 3 systems), :mod:`~rockdesign.bench.methods`
(our engine, our closed form, scipy RK45/DOP853/LSODA/Radau), :mod:`~rockdesign.bench.reference`
(closed-form or converged references with error bounds), :mod:`~rockdesign.planar.dynamics.metrics`,
:mod:`~rockdesign.bench.runner` (bench.json), :mod:`~rockdesign.bench.figures`,
:mod:`~rockdesign.bench.stability` and :mod:`~rockdesign.bench.stability_cases` (stability.md),
:mod:`~rockdesign.planar.dynamics.accuracy` (``engine_accuracy`` for the check report),
:mod:`~rockdesign.bench.speed` (summary of ``benchmarks/results``), :mod:`~rockdesign.bench.timing`.
The CLI is ``rockdesign bench`` (:mod:`rockdesign.cli.bench`).
"""
from ..planar.dynamics.accuracy import engine_accuracy

__all__ = ["engine_accuracy"]
