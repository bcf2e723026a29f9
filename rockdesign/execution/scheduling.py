"""Dynamic load balance for the ``@njit(parallel=True)`` batch drivers: a shared counter of jobs.

numba's ``prange`` gives each thread a fixed share of the iterations (the OpenMP layer used here
hands out even the chunks of ``numba.parallel_chunksize`` statically), so a thread whose core is busy
with another program holds up the whole batch.  The drivers therefore run one ``prange`` iteration per
thread (a *worker*), and every worker takes the next job from a shared counter until none is left:

    counter = np.zeros(1, dtype=np.int64)
    for _ in prange(workers):
        j = take(counter)
        while j < n:
            ...job j, written into row j...
            j = take(counter)

Each job writes only its own rows, so the results are those of a serial loop, bit for bit and in
job order, whichever thread ran which job (docs/engine.md, "Threads").
"""
from __future__ import annotations

import numba
from numba import types
from numba.extending import intrinsic


@intrinsic
def take(typingctx, counter):
    """``counter[0]`` (an int64 array), atomically incremented by one (LLVM ``atomicrmw add``, sequentially
    consistent): the next job for the worker that calls it."""
    if not (isinstance(counter, types.Array) and counter.dtype == types.int64 and counter.ndim == 1):
        return None

    def codegen(context, builder, signature, args):
        ary = context.make_array(signature.args[0])(context, builder, args[0])
        return builder.atomic_rmw("add", ary.data, context.get_constant(types.int64, 1), "seq_cst")
    return types.int64(counter), codegen


def worker_count(jobs: int) -> int:
    """Workers for a batch of ``jobs``: one per numba thread (``numba.get_num_threads()``), at most one per job."""
    return max(1, min(int(jobs), numba.get_num_threads()))
