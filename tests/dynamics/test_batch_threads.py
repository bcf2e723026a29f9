"""The batch drivers (dynamics.batch): the parallel driver's workers take jobs from a shared counter, small
batches and single analyses run serially in the calling thread — and every driver, worker count and
job order gives the results of one-by-one ``integrate`` calls, bit for bit and in job order."""
from __future__ import annotations

import math

import numba
import numpy as np
import pytest

from support import G, reference_podium, table34_column
from rockdesign.planar.dynamics import batch
from rockdesign.planar.dynamics.batch import batch_options, pack_motions, run_batch, run_history, use_threads
from rockdesign.planar.dynamics.engine import integrate
from rockdesign.planar.dynamics.layout import D_EVENTS_STORED, O_T_END
from rockdesign.planar.dynamics.model import ModelChoice, system_parameters
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.library import load_record
from rockdesign.motions.motion import pulse_motion


def _jobs():
    """Jobs of very different cost: short pulses that overturn at once, safe and rocking records."""
    record = load_record("p695-ff/1a", gravity=G)
    motions = [record, pulse_motion("sine", 0.6 * G, 0.4), record, pulse_motion("ricker-anti", 0.38 * G, 0.95),
               pulse_motion("sine", 3.0 * G, 1.5), record, pulse_motion("cycloidal-a", 0.25 * G, 0.8)] * 3
    scales = [0.2, 1.0, 0.6, 1.0, 1.0, 1.1, 1.0, 0.35, 1.5, 0.9, 0.8, 1.0, 0.45, 2.0,
              0.05, 0.7, 1.0, 1.2, 1.3, 0.75, 0.5]
    t_ends = [m.duration + (5.0 if k % 2 else 0.5) for k, m in enumerate(motions)]
    return motions, scales, t_ends


def _one_by_one(sp, motions, scales, t_ends, opts):
    """Summaries and diagnostics of each job by a direct call of the engine's integrator (no batch driver)."""
    kinds, xps, samples, offsets, lengths = pack_motions(motions, scales)
    rows, diags = [], []
    for j in range(len(motions)):
        o = opts.copy()
        o[O_T_END] = t_ends[j]
        s = samples[offsets[j]:offsets[j] + lengths[j]]
        summ, diag, _ = integrate(sp, kinds[j], xps[j], s, np.zeros(4), 1.0, 0.0, o, np.zeros(0), np.zeros((0, 4)),
                                  np.zeros(0), np.zeros(0, dtype=np.int64), np.zeros((0, 4)))
        rows.append(summ.copy())
        diags.append(diag.copy())
    return np.array(rows), np.array(diags)


@pytest.mark.parametrize("name, system, choice", [
    ("block", lambda: table34_column("B1"), ModelChoice("block", "exact")),
    ("podium", reference_podium, ModelChoice("podium", "exact"))])
def test_every_driver_gives_the_one_by_one_results_in_job_order(name, system, choice):
    sp = system_parameters(system(), choice)
    motions, scales, t_ends = _jobs()
    opts = batch_options(1e-8, 1e-10)
    expected_s, expected_d = _one_by_one(sp, motions, scales, t_ends, opts)
    assert len({float(v) for v in expected_s[:, 0]}) > 5           # the jobs differ
    kinds, xps, samples, offsets, lengths = pack_motions(motions, scales)
    y0s = np.zeros((len(motions), 4))
    t = np.asarray(t_ends)
    previous = numba.get_num_threads()
    try:
        for threads in sorted({1, previous}):
            numba.set_num_threads(threads)
            for parallel in (True, False, None):
                s, d = run_batch(sp, motions, scales, t_ends, opts, threads=parallel)
                np.testing.assert_array_equal(s, expected_s)
                np.testing.assert_array_equal(d, expected_d)
    finally:
        numba.set_num_threads(previous)
    # more workers than threads, one worker per job, one worker for all: the counter hands each job out once
    sides = np.ones(len(motions))
    empty, rows = np.zeros(0), np.zeros((0, 4))
    for workers in (1, 3, len(motions)):
        s, d, _ = batch._run_batch(sp.reshape(1, -1), np.zeros(len(motions), dtype=np.int64), kinds, xps, samples,
                                   offsets, lengths, t, opts, y0s, sides, empty, rows, empty,
                                   np.zeros(0, dtype=np.int64), rows, workers)
        np.testing.assert_array_equal(s, expected_s)
        np.testing.assert_array_equal(d, expected_d)
    # a reordered batch gives the same rows, reordered
    order = np.argsort(-t, kind="stable")
    s, _ = run_batch(sp, [motions[k] for k in order], [scales[k] for k in order], t[order], opts, threads=True)
    np.testing.assert_array_equal(s, expected_s[order])


def test_jobs_of_several_systems_in_one_batch_equal_their_own_batches():
    """A batch whose jobs analyse different systems (the design grid's shared batches) gives each job the
    result of a batch of its own system alone, bit for bit, whatever the mix and order."""
    sps = [system_parameters(table34_column("B1"), ModelChoice("block", "exact")),
           system_parameters(table34_column("B4ec"), ModelChoice("block", "exact")),
           system_parameters(reference_podium(), ModelChoice("podium-2dof", "exact"))]
    motions = [pulse_motion("ricker-anti", a * G, 0.95) for a in (0.3, 0.38, 0.5)]
    opts = batch_options(1e-8, 1e-10)
    t_ends = [6.0] * len(motions)
    alone = [run_batch(sp, motions, [1.0] * len(motions), t_ends, opts, threads=False) for sp in sps]
    assert not np.array_equal(alone[0][0], alone[1][0])            # the systems respond differently
    jobs = [(k, i) for i in range(len(motions)) for k in (2, 0, 1)]   # interleaved, the podium first
    table = np.vstack(sps)
    for threads in (True, False):
        s, d = run_batch(table, [motions[i] for _, i in jobs], [1.0] * len(jobs), [6.0] * len(jobs), opts,
                         threads=threads, systems=[k for k, _ in jobs])
        for row, (k, i) in enumerate(jobs):
            np.testing.assert_array_equal(s[row], alone[k][0][i])
            np.testing.assert_array_equal(d[row], alone[k][1][i])
    with pytest.raises(ValueError):
        run_batch(table, motions, [1.0] * 3, t_ends, opts, systems=[0, 3, 1])


def test_small_work_runs_serially_and_a_history_is_the_batch_job():
    assert not use_threads(1)
    assert use_threads(batch.SERIAL_BELOW_JOBS) == (numba.get_num_threads() > 1)
    system = table34_column("B1")
    sp = system_parameters(system, ModelChoice("block", "exact"))
    motion = pulse_motion("ricker-anti", 0.38 * G, 0.95)
    opts = batch_options()
    opts[O_T_END] = 8.0
    t_out = np.linspace(0.0, 8.0, 801)
    out_y = np.zeros((t_out.size, 4))
    ev = (np.empty(64), np.empty(64, dtype=np.int64), np.empty((64, 4)))
    summary, diag, written = run_history(sp, motion.kind, motion.params, motion.samples, np.zeros(4), 1.0, opts,
                                         t_out, out_y, *ev)
    assert written == t_out.size and summary[0] > 0.0
    s, d = run_batch(sp, [motion], [1.0], [8.0], opts, threads=True)       # the same job in a parallel region
    np.testing.assert_array_equal(s[0], summary)
    keep = np.arange(diag.size) != D_EVENTS_STORED                       # the batch stores no events
    np.testing.assert_array_equal(d[0][keep], diag[keep])
    assert diag[D_EVENTS_STORED] > 0
    r = simulate(system, motion, t_end=8.0)
    assert r.theta_max == summary[0] and not math.isnan(r.theta_max)
