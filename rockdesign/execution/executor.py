"""A generic chunked executor: map a batch function over chunks of jobs, locally or on dask.distributed.

Rocking spectra, large suite analyses and the margins of the design check are all "the same batch
function on many independent chunks of jobs".  This module runs such work:

* :class:`LocalExecutor` — in this process, one chunk after the other (the batch function itself
  parallelises over the cores, e.g. a numba ``prange`` kernel), or in a pool of N worker processes
  (for batch functions that run on one core).
* :class:`DaskExecutor` — on a dask.distributed cluster: ``local:N`` starts a ``LocalCluster`` of N
  single-threaded worker processes; any other string is a scheduler address
  (``tcp://host:8786``).  The batch function must be importable on the workers (a module-level
  function of an installed package); a ``warm_up`` function is run on every worker first so that
  no chunk pays numba's compilation or cache load.
* :class:`~rockdesign.execution.store.ChunkStore` (re-exported here) — chunk results as ``.npz``
  files in a folder, written atomically as each chunk completes, with a manifest holding the
  fingerprint of the inputs.  A rerun with the same
  fingerprint loads the completed chunks and computes only the missing ones (resume after an
  interruption); a different fingerprint discards them.

Results are returned in chunk order, whatever the completion order, and each chunk is computed by
the same function on the same inputs, so local and distributed runs give the same arrays (bit for
bit when the batch function is deterministic, as the numba kernels are).

Usage::

    store = ChunkStore(out / "chunks", fingerprint(sp, periods, amplitudes))
    with make_executor("local:2", warm_up=kernel.warm_up) as ex:
        run = run_chunks(kernel.spectrum_rows, tasks, common=(sp,), executor=ex, store=store)
    arrays = run.results          # list of dict[str, ndarray], one per task, in task order
"""
from __future__ import annotations

import os
import shutil
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Callable, Iterator, Sequence

import numpy as np

from .counting import Counted
from .address import (HANDSHAKE_TIMEOUT, PROBE_TIMEOUT, SCHEMES, ExecutorError, check_address,  # noqa: F401
                      is_local, probe_scheduler, reach_scheduler, require_dask, tls_hint)
from .store import ChunkResult, ChunkStore, fingerprint  # noqa: F401  (re-exported: the executor's API)


def usable_cores() -> int:
    """Cores this process may run on (its CPU affinity where the OS reports it, else the CPU count)."""
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)


# ------------------------------------------------------------------------------------------ executors
def one_core(func: Callable) -> Callable:
    """Mark a batch function that runs on one core and releases the GIL while it computes (a numba kernel
    compiled with ``nogil=True`` does most of its work): in this process :class:`LocalExecutor` spreads its tasks
    over threads, one per core.  Unmarked functions are taken to use the cores themselves (a numba ``prange``
    batch, whose parallel regions must not be entered by two threads at once) and run one task after the other."""
    func.one_core = True
    return func


def _call(func, common, args):
    return func(*common, *args)


_KERNEL_LOCK = threading.Lock()


def _set_numba_threads(n: int | None) -> None:
    if n is None:
        return
    import numba
    numba.set_num_threads(max(1, min(int(n), numba.config.NUMBA_NUM_THREADS)))


def _dask_task(func, common, args, numba_threads, warm_up):
    """Run one chunk on a dask worker: warm up once, cap numba's threads, one kernel at a time per
    process (numba's parallel regions are not meant to be entered by several threads at once)."""
    with _KERNEL_LOCK:
        if warm_up is not None:
            warm_up()
        _set_numba_threads(numba_threads)
        return func(*common, *args)


def _pool_initializer(numba_threads, warm_up):
    _set_numba_threads(numba_threads)
    if warm_up is not None:
        warm_up()


class LocalExecutor(Counted):
    """Run chunks on this machine.

    Args:
        processes: 0 (default) runs the chunks one after the other in this process — right for batch
            functions that parallelise themselves (numba ``prange``); N > 0 uses a pool of N worker
            processes (spawned, each with one numba thread) — right for single-core batch functions.
        warm_up: a function called once (in this process, or in each pool worker) before any chunk.
    """

    name = "local"

    def __init__(self, processes: int = 0, warm_up: Callable[[], object] | None = None):
        self.processes = int(processes)
        self.warm_up = warm_up
        self.warm_up_seconds = 0.0
        self._pool = None
        self._started = False

    @property
    def slots(self) -> int:
        """How many chunks run at the same time."""
        return max(1, self.processes)

    def describe(self) -> dict:
        import numba
        return {"executor": "local", "processes": self.processes,
                "threads": numba.get_num_threads() if self.processes == 0 else 1}

    def start(self) -> None:
        if self._started:
            return
        t0 = time.perf_counter()
        if self.processes == 0:
            if self.warm_up is not None:
                self.warm_up()
        else:
            import multiprocessing as mp
            from concurrent.futures import ProcessPoolExecutor
            self._pool = ProcessPoolExecutor(self.processes, mp_context=mp.get_context("spawn"),
                                             initializer=_pool_initializer, initargs=(1, self.warm_up))
            # start the workers (and their warm-up) now, not inside the first chunk
            list(self._pool.map(_noop, range(self.processes)))
        self.warm_up_seconds = time.perf_counter() - t0
        self._started = True

    def map(self, func, common: tuple, tasks: dict[int, tuple]) -> Iterator[tuple[int, ChunkResult]]:
        """Yield (index, result) for every task, as they complete.  In this process a :func:`one_core` function's
        tasks run in threads, one per core; any other function's one after the other."""
        self.start()
        if self.processes == 0:
            threads = min(len(tasks), usable_cores()) if getattr(func, "one_core", False) else 1
            if threads < 2:
                for i, args in tasks.items():
                    yield i, func(*common, *args)
                return
            yield from _threaded(func, common, tasks, threads)
            return
        from concurrent.futures import as_completed
        futures = {self._pool.submit(_call, func, common, args): i for i, args in tasks.items()}
        try:
            for fut in as_completed(futures):
                yield futures[fut], fut.result()
        finally:
            for fut in futures:
                fut.cancel()

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None
        self._started = False

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _noop(_):
    return None


def _threaded(func, common, tasks, threads: int):
    """(index, result) of every task as it completes, in ``threads`` threads of this process (a Ctrl-C here
    cancels the tasks not started; the running ones end with their analysis)."""
    from concurrent.futures import ThreadPoolExecutor, as_completed
    pool = ThreadPoolExecutor(threads, thread_name_prefix="rockdesign-one-core")
    futures = {pool.submit(func, *common, *args): i for i, args in tasks.items()}
    try:
        for fut in as_completed(futures):
            yield futures[fut], fut.result()
    finally:
        pool.shutdown(wait=False, cancel_futures=True)


class DaskExecutor(Counted):
    """Run chunks on a dask.distributed cluster.

    Args:
        address: ``local:N`` (start a LocalCluster of N worker processes with one thread each) or a
            scheduler address such as ``tcp://10.0.0.5:8786``.
        warm_up: a module-level function run on every worker before chunks are sent (and lazily in
            every task, for workers that join later); it must be importable on the workers.
        numba_threads: numba threads per task; default: the machine's cores shared among the
            LocalCluster's workers, and all of a worker's cores on a remote cluster (one kernel runs
            at a time per worker process).
    """

    name = "dask"

    def __init__(self, address: str, warm_up: Callable[[], object] | None = None, numba_threads: int | None = None):
        self.address = check_address(address)     # a bad address is named whether or not dask is installed
        require_dask(self.address)
        self.warm_up = warm_up
        self.numba_threads = numba_threads
        self.warm_up_seconds = 0.0
        self.client = None
        self.cluster = None
        self._n_local = None
        if is_local(self.address):
            rest = self.address[len("local:"):]
            self._n_local = int(rest) if rest else os.cpu_count() or 1
            if self.numba_threads is None:
                self.numba_threads = max(1, (os.cpu_count() or 1) // self._n_local)
        else:
            reach_scheduler(self.address)
            probe_scheduler(self.address)           # accepts and never speaks, or answers junk: refused here

    @property
    def slots(self) -> int:
        if self.client is None:
            return self._n_local or 1
        info = self.client.scheduler_info()
        return max(1, sum(w.get("nthreads", 1) for w in info.get("workers", {}).values()))

    def describe(self) -> dict:
        workers = {}
        if self.client is not None:
            workers = self.client.scheduler_info().get("workers", {})
        return {"executor": "dask", "address": self.address,
                "scheduler": self.client.scheduler.address if self.client is not None else None,
                "workers": len(workers), "worker_threads": sum(w.get("nthreads", 1) for w in workers.values()),
                "numba_threads_per_task": self.numba_threads}

    def start(self) -> None:
        if self.client is not None:
            return
        import logging

        from distributed import Client, LocalCluster
        t0 = time.perf_counter()
        if self._n_local is not None:
            import warnings
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # e.g. "port 8787 in use" from another cluster on this host
                self.cluster = LocalCluster(n_workers=self._n_local, threads_per_worker=1, processes=True,
                                            dashboard_address=None, silence_logs=logging.ERROR)
            self.client = Client(self.cluster)
        else:
            try:
                self.client = Client(self.address, timeout="20s")
            except (OSError, TimeoutError, ValueError, TypeError) as exc:
                # TypeError: a tls:// address without dask's TLS configuration (distributed.comm.tls)
                raise ExecutorError(f"cannot connect to the dask scheduler: {exc}", key="executor",
                                    expected="a running scheduler (dask scheduler; dask worker ADDRESS)"
                                    + tls_hint(self.address),
                                    found=repr(self.address)) from None
        if self.warm_up is not None:
            workers = list(self.client.scheduler_info().get("workers", {}))
            futs = [self.client.submit(_dask_task, _noop_func, (), (), self.numba_threads, self.warm_up,
                                       workers=[w], allow_other_workers=False, pure=False) for w in workers]
            self.client.gather(futs)
        self.warm_up_seconds = time.perf_counter() - t0

    def map(self, func, common: tuple, tasks: dict[int, tuple]) -> Iterator[tuple[int, ChunkResult]]:
        """Yield (index, result) for every task as it completes on the cluster."""
        from distributed import as_completed
        self.start()
        client = self.client
        # hash=False: a fresh key per call (with content hashing, a second map over the same arrays gets the
        # key the first call is releasing, and its tasks fail with "lost dependencies")
        shared = tuple(client.scatter(c, broadcast=True, hash=False) if isinstance(c, np.ndarray) and c.nbytes > 100_000
                       else c for c in common)
        futures = {}
        for i, args in tasks.items():
            fut = client.submit(_dask_task, func, shared, args, self.numba_threads, self.warm_up, pure=False,
                                key=f"rockdesign-chunk-{i}-{os.urandom(4).hex()}")
            futures[fut] = i
        try:
            for fut in as_completed(list(futures)):
                yield futures[fut], fut.result()
        finally:
            client.cancel(list(futures))

    def close(self) -> None:
        if self.client is not None:
            self.client.close()
            self.client = None
        if self.cluster is not None:
            self.cluster.close()
            self.cluster = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _noop_func():
    return None


EXECUTOR_METHODS = ("start", "map", "close", "describe", "count")
"""The executor protocol every kind's check accepts (:class:`LocalExecutor`, :class:`DaskExecutor`, the design
grid's :class:`~rockdesign.execution.batch_pool.PoolMember`): ``start()``; ``map(func, common, tasks)`` runs a batch —
``func(*common, *tasks[i])`` for every task, yielding ``(i, result)`` as they complete; ``count(n)`` counts the
analyses a caller ran through it (``analyses``, :class:`~rockdesign.execution.counting.Counted`); ``slots`` (how
many tasks run at once; 1 when absent), ``describe()`` and ``close()``."""
HOW_TO_MAKE = ("None (this machine), a dask value such as 'local:4' or 'tcp://host:8786', or an executor: "
               "rockdesign.make_executor('tcp://host:8786')")


def is_executor(value) -> bool:
    """Whether ``value`` is an executor object (it has :data:`EXECUTOR_METHODS`)."""
    return all(callable(getattr(value, name, None)) for name in EXECUTOR_METHODS)


def check_executor(executor, *, text: bool = True, reach: bool = True) -> None:
    """Refuse an ``executor`` argument that is neither None, a dask value (when ``text``) nor an executor
    object, naming the parameter ``executor``.  A dask value is checked (:func:`check_address`; dask installed;
    with ``reach`` a remote scheduler must answer dask's handshake), before any work or output."""
    if executor is None or is_executor(executor):
        return
    if isinstance(executor, str) and text:
        address = check_address(executor)
        require_dask(address)
        if reach and not is_local(address):
            reach_scheduler(address)
            probe_scheduler(address)
        return
    if isinstance(executor, str):
        raise ExecutorError("a dask address is not an executor here", key="executor",
                            expected="an executor object: rockdesign.make_executor(" + repr(executor) + ") (or pass "
                            "the address to rockdesign.design, which starts and closes it)", found=repr(executor))
    raise ExecutorError("not an executor", key="executor", expected=HOW_TO_MAKE,
                        found=f"{executor!r} ({type(executor).__name__})")


CHUNKS_PER_SLOT = 4
"""A batch goes to an executor in about this many chunks per slot (a worker's concurrent task): few round trips
(a dask task's is about as long as one short analysis), while the slots still finish together."""


def slots_of(executor) -> int:
    """How many tasks ``executor`` runs at once (its ``slots``; one when it has none)."""
    return max(1, int(getattr(executor, "slots", 1) or 1))


def chunk_size(n: int, executor) -> int:
    """Items per chunk when ``n`` items go to ``executor`` (:data:`CHUNKS_PER_SLOT` chunks per slot; an executor
    without ``slots`` counts as one)."""
    return max(1, -(-n // (CHUNKS_PER_SLOT * slots_of(executor))))


def here(executor):
    """``executor``, or for None a :class:`LocalExecutor` of this process (it counts the analyses run through it)."""
    return executor if executor is not None else LocalExecutor()


def make_executor(dask: str | None = None, *, processes: int = 0, warm_up: Callable[[], object] | None = None,
                  numba_threads: int | None = None) -> LocalExecutor | DaskExecutor:
    """The executor for a CLI ``--dask`` value: None → :class:`LocalExecutor`, else :class:`DaskExecutor` (an
    empty or blank value is refused there: it names no cluster, :func:`check_address`)."""
    if dask is None:
        return LocalExecutor(processes, warm_up)
    return DaskExecutor(dask, warm_up=warm_up, numba_threads=numba_threads)


@contextmanager
def running_on(executor, *, warm_up: Callable[[], object] | None = None, here: bool = False, start: bool = True):
    """The executor a library call runs on — the one place a library call turns a ``--dask`` value into an
    executor: an executor object as given (started by its user, not closed here); a dask value ("local:N", a
    scheduler address) made, started here (unless ``start`` is False: the first ``map`` starts it) and closed
    when the call ends; None stays None (the call's own analyses in this process), or with ``here`` a
    :class:`LocalExecutor` of this process, closed at the end."""
    if executor is not None and not isinstance(executor, str):
        yield executor
        return
    if executor is None and not here:
        yield None
        return
    with make_executor(executor, warm_up=warm_up) as owned:    # (an unreachable scheduler stops here)
        if start:
            owned.start()
        yield owned


# ------------------------------------------------------------------------------------------ the loop
@dataclass
class ChunkRun:
    """What :func:`run_chunks` did: results in task order and how they were obtained."""

    results: list
    computed: list[int] = field(default_factory=list)
    resumed: list[int] = field(default_factory=list)
    seconds: float = 0.0            # computing the missing chunks [s]
    warm_up_seconds: float = 0.0    # starting the executor (cluster, workers, kernel warm-up) [s]
    executor: dict = field(default_factory=dict)


def run_chunks(func: Callable[..., ChunkResult], tasks: Sequence[tuple], *, common: tuple = (), executor=None,
               store: ChunkStore | None = None, resume: bool = True,
               progress: Callable[[int, bool], None] | None = None) -> ChunkRun:
    """Map ``func(*common, *tasks[i])`` over all tasks; return the results in task order.

    Args:
        func: the batch function (module-level, importable where it runs); returns a dict of arrays.
        tasks: per-chunk positional arguments (picklable).
        common: arguments shared by every chunk, passed first (large arrays are broadcast once to
            dask workers).
        executor: a :class:`LocalExecutor` (default) or :class:`DaskExecutor`; started if needed,
            not closed.
        store: where completed chunks are saved as they arrive (and loaded from on resume).
        resume: reuse matching chunks found in ``store``.
        progress: called as ``progress(index, resumed)`` after every chunk (resumed or computed).

    Returns:
        :class:`ChunkRun`.
    """
    executor = here(executor)
    n = len(tasks)
    results: list = [None] * n
    run = ChunkRun(results)
    if store is not None:
        store.open(resume)
        for i in range(n):
            r = store.load(i) if resume else None
            if r is not None:
                results[i] = r
                run.resumed.append(i)
                if progress is not None:
                    progress(i, True)
    todo = {i: tuple(tasks[i]) for i in range(n) if results[i] is None}
    if todo:
        t0 = time.perf_counter()
        executor.start()
        run.warm_up_seconds = time.perf_counter() - t0
        t0 = time.perf_counter()
        for i, r in executor.map(func, tuple(common), todo):
            results[i] = r
            if store is not None:
                store.save(i, r)
            run.computed.append(i)
            if progress is not None:
                progress(i, False)
        run.seconds = time.perf_counter() - t0
    run.executor = executor.describe()
    return run


def remove_tree(path) -> None:
    """Delete a folder of chunk stores (after the final outputs are written)."""
    shutil.rmtree(path, ignore_errors=True)
