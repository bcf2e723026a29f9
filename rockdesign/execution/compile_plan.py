"""Compile the integrator's callees in two processes at once on the first run (numba compiles on one core).

numba compiles a kernel and, one by one, every kernel it calls; for the rocking engine that is ~45
functions and ~22 s before the integrator itself (~4 s) and the batch kernel around it (~10 s).  Each
callee lands in numba's on-disk cache, and a caller compiled later loads a cached callee instead of
compiling it again.  So on the first run :func:`rockdesign.execution.compilation.prepare` splits the
callees between itself and a second process; when both halves are in the cache the second process
compiles the integrator, which finds every callee there, while the first compiles the side kernels.

numba compiles a callee for the argument types of its call site, so the plan names each callee with
the signature the integrator calls it with (``compile_plan_table.py``, written by
``python -m rockdesign.execution.compile_plan_writer`` with an empty cache, which also measures each
callee's compile time to balance the two halves).  A stale entry costs time only — numba then
compiles the callee again inside the integrator; ``tests/dynamics/test_compilation.py`` fails when an
entry no longer matches the code.
"""
from __future__ import annotations

import importlib


def callee_table() -> tuple[tuple[str, str, str, float], ...]:
    """(module, function, signature, compile seconds) of the integrator's direct callees, in compile order."""
    from .compile_plan_table import CALLEES
    return CALLEES


def split(entries, head_start: float) -> tuple[list, list]:
    """Entries for this process and for the helper, balanced by compile seconds when the helper first
    spends ``head_start`` seconds on other work (starting Python, importing)."""
    total = sum(e[3] for e in entries)
    target = (total + head_start) / 2.0
    mine, theirs, done = [], [], 0.0
    for entry in entries:
        if done + entry[3] / 2.0 <= target:
            mine.append(entry)
            done += entry[3]
        else:
            theirs.append(entry)
    return mine, theirs


def compile_entries(entries) -> None:
    """Compile (or load from numba's cache) each callee for its signature; an entry that no longer fits
    its kernel (renamed, other arguments) is skipped — the integrator then compiles that callee itself.

    The signature goes to numba as a tuple of types, as a calling kernel passes it: numba's cache is
    keyed on the signature object it is given, and a string would be stored under the string.
    """
    from numba.core import sigutils
    for module, name, signature, _ in entries:
        try:
            args, _ = sigutils.normalize_signature(signature)
            getattr(importlib.import_module(module), name).compile(tuple(args))
        except Exception:      # a stale entry costs time only (tests/dynamics/test_compilation.py fails on it)
            continue
