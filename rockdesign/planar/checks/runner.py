"""Run one system against many (record, scale) jobs and read the engine summaries (SI)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..design.geometry import displacement_capacity, slenderness_angle
from ..dynamics.batch import batch_options
from ..dynamics.shared_batches import balanced_order, batch_rows  # noqa: F401  (balanced_order: re-exported)
from ..dynamics.layout import (COMPLETED_STATUSES, D_STATUS, STATUS_NAMES, S_CAP_ACC_MAX, S_CAP_DV_MAX, S_DRIFT_MAX, S_FS_MAX, S_IMPACTS,
                                S_THETA_MAX, S_T_END, S_T_UPLIFT, S_UB_MAX, S_UPLIFT_TIME)
from ..dynamics.model import ModelChoice, system_parameters
from ..dynamics.eom import P_CR, P_THETA_C, P_TWO_DOF
from ..dynamics.overturning import classify
from ...execution.executor import chunk_size, here, slots_of, usable_cores
from ..system import RockingSystem


@dataclass(frozen=True)
class RunSummary:
    """What one analysis says about the design (SI)."""

    theta_max: float
    theta_max_over_alpha: float
    theta_max_over_theta_c: float
    u_B_max: float
    u_B_max_over_capacity: float
    impacts: int
    uplift_time: float | None
    time_uplifted: float
    overturn_mode: str          # none | exceeded | dynamic
    overturned: bool            # per the criterion
    impacts_before_overturn: int | None
    status: str
    t_end: float                # time the analysis ended [s] (early when it overturned or stopped)
    # superstructure demand (SPEC §13): 2DOF podium — peak absolute acceleration |f_s| [m/s²] and peak drift
    # |u_T − u_B| [m]; rigid masses — the cap beam's peak acceleration between impacts [m/s²] and largest
    # velocity jump at an impact [m/s]; None where the model has no such quantity
    superstructure_acceleration_max: float | None = None
    drift_max: float | None = None
    cap_acceleration_max: float | None = None
    cap_velocity_jump_max: float | None = None

    @property
    def failed(self) -> bool:
        """True when the analysis did not run to a conclusion (:func:`analysis_failed`)."""
        return analysis_failed(self.status)

    @property
    def response_ratio(self) -> float:
        """θ_max/θc (Eq 3.56), the response ratio the shared acceptance code reads
        (:class:`rockdesign.acceptance.outcome.Run`)."""
        return self.theta_max_over_theta_c


VALID_STATUSES = tuple(STATUS_NAMES[code] for code in COMPLETED_STATUSES)
"""Engine statuses of an analysis that ran to a conclusion (see docs/engine.md).  Any other status
(step size collapsed, step or event limit reached) means the analysis failed: the record is
listed as failed and never counted as safe."""


def analysis_failed(status: str) -> bool:
    """True when an engine status (:data:`VALID_STATUSES`) says the analysis did not finish."""
    return status not in VALID_STATUSES


def interpret(summary: np.ndarray, status: int, theta_c: float, alpha: float, capacity: float,
              criterion: str, two_dof: bool = False) -> RunSummary:
    """Turn an engine summary row into a :class:`RunSummary` (same rules as ``simulate``); ``two_dof``: the
    row is the 2DOF podium's (its superstructure demand is read, else the cap beam's)."""
    theta_max = float(summary[S_THETA_MAX])
    outcome = classify(summary, theta_c, criterion)
    mode, overturned, before = outcome.mode, outcome.overturned, outcome.impacts_before
    t_up = float(summary[S_T_UPLIFT])
    return RunSummary(theta_max, theta_max / alpha, theta_max / theta_c, float(summary[S_UB_MAX]),
                      float(summary[S_UB_MAX]) / capacity, int(summary[S_IMPACTS]),
                      None if math.isnan(t_up) else t_up, float(summary[S_UPLIFT_TIME]), mode, bool(overturned),
                      before, STATUS_NAMES[int(status)], float(summary[S_T_END]),
                      float(summary[S_FS_MAX]) if two_dof else None, float(summary[S_DRIFT_MAX]) if two_dof else None,
                      None if two_dof else float(summary[S_CAP_ACC_MAX]),
                      None if two_dof else float(summary[S_CAP_DV_MAX]))


def run_jobs(system: RockingSystem, choice: ModelChoice, motions, scales, *, rtol: float, atol: float,
             free_vibration: float, criterion: str, rest_velocity: float = 5e-4, energy_stop: bool = False,
             stop_at_capacity: bool = False, restitution_factor: float = 1.0, progress=None,
             chunk: int | None = None, executor=None, costs=None) -> list[RunSummary]:
    """Analyse ``motions[i]`` × ``scales[i]`` for one system and model, in parallel, in job order.

    ``restitution_factor`` multiplies the coefficient of restitution (capped at 1) for sensitivity
    studies.  ``progress(n_done)`` is called after each chunk.  With an ``executor`` (the chunked
    executor of :mod:`rockdesign.execution.executor`, e.g. a dask.distributed cluster) the jobs run
    there in chunks; the results are identical to the in-process run.  ``costs``: a predicted cost per
    job (e.g. the seconds of record a similar analysis ran): the longest run first, so the cores finish
    together (:func:`balanced_order`; default the end times); it changes the order the jobs run in, never
    their results.
    """
    sp = system_parameters(system, choice, rest_velocity=rest_velocity)
    if restitution_factor != 1.0:
        sp = sp.copy()
        sp[P_CR] = min(1.0, sp[P_CR] * restitution_factor)
    opts = batch_options(rtol, atol, energy_stop=energy_stop, stop_at_capacity=stop_at_capacity)
    theta_c = float(sp[P_THETA_C])
    two_dof = bool(sp[P_TWO_DOF] != 0.0)
    alpha = slenderness_angle(system.column.half_width, system.column.half_height)
    capacity = displacement_capacity(system.column)
    n = len(motions)
    runner = here(executor)
    runner.count(n)
    t_ends = [m.duration + free_vibration for m in motions]
    predicted = list(t_ends if costs is None else costs)
    step = chunk or jobs_per_chunk(n, runner)
    bounds = [(a, min(n, a + step)) for a in range(0, n, step)]
    motions, scales = list(motions), list(scales)
    tasks = {c: (motions[a:b], scales[a:b], t_ends[a:b], predicted[a:b]) for c, (a, b) in enumerate(bounds)}
    out: list = [None] * n
    done = 0
    for c, (summaries, diags) in runner.map(batch_rows, (sp, opts), tasks):
        a, b = bounds[c]
        for j in range(b - a):
            out[a + j] = interpret(summaries[j], diags[j, D_STATUS], theta_c, alpha, capacity, criterion, two_dof)
        done += b - a
        if progress is not None:
            progress(done)
    return out


def jobs_per_chunk(n: int, executor) -> int:
    """Jobs per task when ``n`` jobs go to ``executor``: on one slot (this process, a design grid's pool member)
    chunks of 4 jobs per core, at least 8 — the batch driver shares each chunk over numba's threads and the
    progress moves; on more slots :func:`~rockdesign.execution.executor.chunk_size` (a few chunks per slot)."""
    if slots_of(executor) == 1:
        return max(4 * usable_cores(), 8)
    return chunk_size(n, executor)
