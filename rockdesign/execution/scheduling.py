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

numba (0.68) has no atomic operation for the CPU (numba issue #2988), so the counter is one LLVM
``atomicrmw add``, built from public APIs only: the counter's data pointer from cffi's ``from_buffer``
(which numba compiles, docs: "Supported Python features", cffi), and the instruction from numba's
documented ``numba.extending.intrinsic`` with llvmlite's ``IRBuilder.atomic_rmw``.  No integer ↔ pointer
cast is involved (llvmlite warns against those under LLVM 22).  The machine code is the one of the
earlier intrinsic on numba's internal array model: one ``lock xadd`` on the array's data.
"""
from __future__ import annotations

import cffi
import numba
from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic

_FFI = cffi.FFI()
"""cffi's ``from_buffer`` turns a contiguous array into a typed raw pointer in nopython code."""


@intrinsic
def _fetch_add_one(typingctx, pointer):
    """``*pointer`` (an int64 pointer) before adding one to it atomically (LLVM ``atomicrmw add``,
    sequentially consistent)."""
    if not (isinstance(pointer, types.CPointer) and pointer.dtype == types.int64):
        return None

    def codegen(context, builder, signature, args):
        return builder.atomic_rmw("add", args[0], ir.Constant(ir.IntType(64), 1), "seq_cst")
    return types.int64(pointer), codegen


@njit(cache=True)
def take(counter):
    """``counter[0]`` (a contiguous int64 array), atomically incremented by one: the next job for the worker
    that calls it."""
    return _fetch_add_one(_FFI.from_buffer(counter))


def worker_count(jobs: int) -> int:
    """Workers for a batch of ``jobs``: one per numba thread (``numba.get_num_threads()``), at most one per job."""
    return max(1, min(int(jobs), numba.get_num_threads()))
