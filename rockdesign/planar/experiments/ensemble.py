"""A project run over a ground-motion ensemble (e.g. ``rockdesign records synth``'s stochastic
ensemble, thesis Ch. 7): one analysis per motion with the existing batch runner
(:func:`rockdesign.planar.checks.runner.run_jobs`), written as the ``analyses.csv`` that
``rockdesign validate`` reads (columns ``id``, ``theta_max_over_alpha``, ``overturned``, ...).

The model is the project's full model (``[analysis] model``; exact equations unless
``equations = "linear"``); overturning follows the project's ``[analysis] overturn`` criterion.
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

from ..checks.runner import RunSummary, run_jobs
from ..design.quantities import coefficient_of_restitution
from ..dynamics.model import ModelChoice, default_structure, resolve_structure
from ...errors import ProjectError
from ...motions.suites import load_suite

COLUMNS = ["id", "scale", "pga", "theta_max_over_alpha", "overturned", "overturn_mode", "impacts", "u_B_max"]


@dataclass
class EnsembleRun:
    """Results of a project over an ensemble: ids, scale factors, PGAs [m/s²], run summaries; model label
    and the coefficient of restitution used."""

    suite: str
    ids: list[str]
    scales: list[float]
    pgas: list[float]
    runs: list[RunSummary]
    model: str
    c_r: float

    def rows(self) -> list[dict]:
        return [{"id": i, "scale": s, "pga": a, "theta_max_over_alpha": r.theta_max_over_alpha,
                 "overturned": r.overturned, "overturn_mode": r.overturn_mode, "impacts": r.impacts,
                 "u_B_max": r.u_B_max} for i, s, a, r in zip(self.ids, self.scales, self.pgas, self.runs)]

    def as_json(self) -> dict:
        n_ot = sum(r.overturned for r in self.runs)
        return {"suite": self.suite, "model": self.model, "c_r": self.c_r, "n": len(self.runs),
                "n_overturned": n_ot, "p_overturn": n_ot / len(self.runs) if self.runs else None,
                "records": self.rows()}

    def write_csv(self, path) -> Path:
        """The analyses.csv that ``validation`` reads (:func:`write_analyses_csv`)."""
        return write_analyses_csv(self, path)


def run_ensemble(project, suite: str, *, scale: float = 1.0, restitution: float | None = None,
                 records_dir=None, progress=None, before_analyses=None) -> EnsembleRun:
    """Analyse ``project`` under every motion of ``suite`` (name or manifest path) × ``scale`` (× the
    manifest's own factor, if it has one).

    ``restitution`` replaces the project's c_r (e.g. the value measured by ``rockdesign calibrate``).
    ``progress(done, total)`` is called as chunks finish; ``before_analyses()`` once the input is
    checked (the CLI compiles the kernels there on a first run).
    """
    system = project.system
    a = project.analysis
    if restitution is not None:
        if not 0.0 < restitution <= 1.0:
            raise ProjectError("invalid coefficient of restitution", key="restitution", expected="0 < c_r <= 1",
                               found=repr(restitution))
        system = system.with_restitution(restitution)
    if not (math.isfinite(scale) and scale > 0.0):
        raise ProjectError("invalid scale factor", key="scale", expected="a finite factor > 0", found=repr(scale))
    loaded = load_suite(suite, gravity=system.g, records_dir=records_dir, key="suite")
    if not loaded.records:
        raise ProjectError("the ensemble has no available record", key="suite", expected="a suite with records",
                           found="; ".join(f"{i}: {r}" for i, r in loaded.missing) or "an empty suite")
    if loaded.missing:   # the CSV feeds 'validate': a dropped record would change its count silently
        shown = "; ".join(f"{i}: {r}" for i, r in loaded.missing[:3])
        more = f" and {len(loaded.missing) - 3} more" if len(loaded.missing) > 3 else ""
        raise ProjectError(f"{len(loaded.missing)} of {len(loaded.entries)} records of the ensemble are missing",
                           key="suite", expected="every record of the suite available (or records_dir: the folder "
                           "with the PEER AT2 files)", found=shown + more)
    rule = loaded.default_scale
    if rule is not None and rule.method != "factor":
        raise ProjectError("the ensemble's scale rule is not applied by 'ensemble'", file=str(loaded.path),
                           key="scale", expected="method = \"factor\" (or scale the motions with scale)",
                           found=f"method = \"{rule.method}\"")
    if rule is not None:
        scale *= rule.value
    structure = default_structure(system, a.rigid_superstructure_ratio)[0] if a.model == "auto" else \
        resolve_structure(system, a.model)
    if system.has_elastic_superstructure and a.model == "auto":
        structure = "podium-2dof"
    choice = ModelChoice(structure, "linear" if a.equations == "linear" else "exact")
    ids = [rid for rid, _, _ in loaded.records]
    motions = [m for _, m, _ in loaded.records]
    n = len(motions)
    if before_analyses is not None:
        before_analyses()
    runs = run_jobs(system, choice, motions, [scale] * n, rtol=a.rtol, atol=a.atol, free_vibration=a.free_vibration,
                    criterion=a.overturn, rest_velocity=a.rest_velocity,
                    progress=(lambda done: progress(done, n)) if progress else None)
    return EnsembleRun(loaded.name, ids, [scale] * n, [m.pga * scale for m in motions], runs, choice.label,
                       coefficient_of_restitution(system)[0])


def write_analyses_csv(run: EnsembleRun, path) -> Path:
    """Write one row per motion (COLUMNS; SI: pga [m/s²], u_B_max [m])."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=COLUMNS)
        w.writeheader()
        for row in run.rows():
            w.writerow({k: (str(v).lower() if isinstance(v, bool) else v) for k, v in row.items()})
    return path
