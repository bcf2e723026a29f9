"""The generic chunked executor: ordering, chunk store, fingerprints, process pool, resume after an
interruption (raised mid-run, or chunks deleted) — results identical to an uninterrupted run."""
from __future__ import annotations

import numpy as np
import pytest

from support import table34_column
from rockdesign.planar.spectra import (ChunkStore, LocalExecutor, SpectrumRequest, compute_spectrum, fingerprint,
                                parse_axis, run_chunks)
from rockdesign.planar.spectra import spectrum as spectrum_module


def square_rows(offset, values, power):
    """A module-level batch function (importable by worker processes)."""
    return {"v": (np.asarray(values, dtype=float) + offset) ** power, "n": np.array([len(values)])}


def test_run_chunks_returns_results_in_task_order():
    tasks = [(np.arange(k, k + 3), 2) for k in range(0, 30, 3)]
    run = run_chunks(square_rows, tasks, common=(1.0,))
    assert [int(r["n"][0]) for r in run.results] == [3] * 10
    np.testing.assert_array_equal(np.concatenate([r["v"] for r in run.results]), (np.arange(30) + 1.0) ** 2)
    assert run.computed == list(range(10)) and run.resumed == []


def test_process_pool_gives_the_same_results():
    tasks = [(np.arange(k, k + 5) * 0.1, 3) for k in range(0, 40, 5)]
    inline = run_chunks(square_rows, tasks, common=(0.5,))
    with LocalExecutor(processes=2) as ex:
        pooled = run_chunks(square_rows, tasks, common=(0.5,), executor=ex)
    assert sorted(pooled.computed) == list(range(8))
    for a, b in zip(inline.results, pooled.results):
        np.testing.assert_array_equal(a["v"], b["v"])


def test_fingerprint_is_exact():
    a = np.linspace(0, 1, 11)
    assert fingerprint(a, 1.0, "x") == fingerprint(a.copy(), 1.0, "x")
    b = a.copy()
    b[3] = np.nextafter(b[3], 2.0)
    assert fingerprint(b, 1.0, "x") != fingerprint(a, 1.0, "x")
    assert fingerprint(a, 1.0, "x") != fingerprint(a, 1.0 + 1e-16 * 2, "x")
    assert fingerprint(a.astype(np.float32)) != fingerprint(a)


def test_store_resumes_only_matching_chunks(tmp_path):
    tasks = [(np.arange(k, k + 2), 1) for k in range(0, 8, 2)]
    store = ChunkStore(tmp_path / "c", "fp-1")
    run_chunks(square_rows, tasks, common=(0.0,), store=store)
    assert store.completed() == [0, 1, 2, 3]
    # same fingerprint: everything resumed, nothing computed
    again = run_chunks(square_rows, tasks, common=(0.0,), store=ChunkStore(tmp_path / "c", "fp-1"))
    assert again.resumed == [0, 1, 2, 3] and again.computed == []
    # other inputs: the old chunks are discarded
    other = ChunkStore(tmp_path / "c", "fp-2")
    run = run_chunks(square_rows, tasks, common=(10.0,), store=other)
    assert run.resumed == [] and other.discarded == 4
    np.testing.assert_array_equal(run.results[0]["v"], [10.0, 11.0])
    # --no-resume recomputes even when the fingerprint matches
    run = run_chunks(square_rows, tasks, common=(10.0,), store=ChunkStore(tmp_path / "c", "fp-2"), resume=False)
    assert run.resumed == [] and len(run.computed) == 4


def test_torn_chunk_file_is_recomputed(tmp_path):
    tasks = [(np.arange(k, k + 2), 1) for k in range(0, 6, 2)]
    store = ChunkStore(tmp_path / "c", "fp")
    run_chunks(square_rows, tasks, common=(0.0,), store=store)
    store.path(1).write_bytes(b"not an npz")
    run = run_chunks(square_rows, tasks, common=(0.0,), store=ChunkStore(tmp_path / "c", "fp"))
    assert run.resumed == [0, 2] and run.computed == [1]
    np.testing.assert_array_equal(run.results[1]["v"], [2.0, 3.0])


REQ = SpectrumRequest("ricker-anti", parse_axis("omega_p/p:1:8:23", "x"), parse_axis("ap/up:0:8:17", "y"))


@pytest.fixture(scope="module")
def uninterrupted():
    return compute_spectrum(table34_column("B1"), REQ, chunk_rows=3)


def test_resume_after_an_interruption_mid_run(tmp_path, monkeypatch, uninterrupted):
    calls = {"n": 0}
    real = spectrum_module.spectrum_rows

    def failing(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 4:
            raise KeyboardInterrupt  # the user presses Ctrl-C while the 4th chunk runs
        return real(*args, **kwargs)

    monkeypatch.setattr(spectrum_module, "spectrum_rows", failing)
    with pytest.raises(KeyboardInterrupt):
        compute_spectrum(table34_column("B1"), REQ, store_dir=tmp_path / "chunks", chunk_rows=3)
    assert ChunkStore(tmp_path / "chunks", "").completed() == [0, 1, 2]
    monkeypatch.setattr(spectrum_module, "spectrum_rows", real)
    resumed = compute_spectrum(table34_column("B1"), REQ, store_dir=tmp_path / "chunks")  # chunk size from the store
    assert resumed.execution["chunk_rows"] == 3
    assert resumed.execution["chunks_resumed"] == 3 and resumed.execution["chunks_computed"] == 3
    np.testing.assert_array_equal(resumed.out, uninterrupted.out)
    assert not (tmp_path / "chunks").exists()  # cleaned up after success (keep_chunks=False)


def test_resume_after_deleting_chunks(tmp_path, uninterrupted):
    store = tmp_path / "chunks"
    first = compute_spectrum(table34_column("B1"), REQ, store_dir=store, chunk_rows=3, keep_chunks=True)
    np.testing.assert_array_equal(first.out, uninterrupted.out)
    files = sorted(store.glob("chunk-*.npz"))
    assert len(files) == 6
    for f in files[1::2]:
        f.unlink()
    again = compute_spectrum(table34_column("B1"), REQ, store_dir=store, chunk_rows=3, keep_chunks=True)
    assert again.execution["chunks_resumed"] == 3 and again.execution["chunks_computed"] == 3
    np.testing.assert_array_equal(again.out, uninterrupted.out)
    # changed inputs (another tolerance) never reuse the chunks
    other = compute_spectrum(table34_column("B1"), SpectrumRequest(**{**REQ.__dict__, "rtol": 1e-9}),
                             store_dir=store, chunk_rows=3)
    assert other.execution["chunks_resumed"] == 0 and other.execution["chunks_discarded"] == 6


def test_chunking_does_not_change_results(uninterrupted):
    for rows in (1, 17):
        np.testing.assert_array_equal(compute_spectrum(table34_column("B1"), REQ, chunk_rows=rows).out,
                                      uninterrupted.out)


def test_record_suite_batches_equal_run_batch(tmp_path):
    # the executor serves suite analyses: run_batch cut into chunks gives the same arrays, resumably
    from rockdesign.planar.dynamics.batch import batch_options, run_batch
    from rockdesign.motions.library import load_record
    from rockdesign.motions.motion import pulse_motion
    from rockdesign.planar.dynamics.model import ModelChoice, system_parameters
    from rockdesign.planar.dynamics.parallel import run_motions
    system = table34_column("B2ec")
    sp = system_parameters(system, ModelChoice("block", "exact"))
    rec = load_record("p695-ff/11a")
    motions = [rec] * 5 + [pulse_motion("sine", 2.0, 0.8), pulse_motion("ricker-anti", 3.0, 1.1)]
    scales = [0.5, 1.0, 1.5, 2.5, 4.0, 1.0, 1.0]
    t_ends = [m.duration + 10.0 for m in motions]
    opts = batch_options()
    s_ref, d_ref = run_batch(sp, motions, scales, t_ends, opts)
    s, d = run_motions(sp, motions, scales, t_ends, opts, chunk_jobs=2, store_dir=tmp_path / "suite")
    np.testing.assert_array_equal(s, s_ref)
    np.testing.assert_array_equal(d, d_ref)
    assert (s_ref[:, 0] > 0).all()


def test_a_one_core_function_runs_in_threads_of_this_process(monkeypatch):
    """A function marked one_core (its work releases the GIL: the cylinder's 3D analyses) runs in one thread per
    core in this process, every task once, each result under its own index; an unmarked function (a numba
    ``prange`` batch, which must not be entered by two threads) one task after the other in the caller's thread."""
    import threading
    import time

    from rockdesign.execution import executor as ex_module
    from rockdesign.execution.executor import one_core
    monkeypatch.setattr(ex_module, "usable_cores", lambda: 2)
    seen = []

    def work(offset, k):
        seen.append(threading.current_thread().name)
        time.sleep(0.05)             # long enough for the second thread to take a task
        return offset + k

    tasks = {i: (i,) for i in range(6)}
    plain = dict(LocalExecutor().map(work, (100,), tasks))
    assert plain == {i: 100 + i for i in range(6)} and set(seen) == {threading.current_thread().name}
    seen.clear()
    threaded = dict(LocalExecutor().map(one_core(work), (100,), tasks))
    assert threaded == plain and len(seen) == 6
    assert len(set(seen)) == 2 and threading.current_thread().name not in seen
