"""Compile the integrator's callees in two processes at once on the first run (numba compiles on one core).

numba compiles a kernel and, one by one, every kernel it calls; for the rocking engine that is ~45
functions and ~25 s before the integrator itself (~4 s) and the batch kernel around it (~8 s).  Each
callee lands in numba's on-disk cache, and a caller compiled later loads a cached callee instead of
compiling it again.  So on the first run :func:`rockdesign.dynamics.compilation.prepare` splits the
callees between itself and a second process, waits for both, and only then compiles the integrator,
which finds every callee in the cache.

numba compiles a callee for the argument types of its call site, so the plan names each callee with
the signature the integrator calls it with (``compile_plan_table.py``, written by
``python -m rockdesign.dynamics.compile_plan`` with an empty cache, which also measures each callee's
compile time to balance the two halves).  A stale entry costs time only — numba then compiles the
callee again inside the integrator; ``tests/dynamics/test_compilation.py`` fails when an entry no
longer matches the code.
"""
from __future__ import annotations

import importlib
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TABLE = Path(__file__).with_name("compile_plan_table.py")
INTEGRATOR = ("rockdesign.dynamics.engine", "integrate")


def callee_table() -> tuple[tuple[str, str, str, float], ...]:
    """(module, function, signature, compile seconds) of the integrator's direct callees, in compile order."""
    from .compile_plan_table import CALLEES
    return CALLEES


def split(entries, head_start: float) -> tuple[list, list]:
    """Entries for this process and for the helper, balanced by compile seconds when the helper first
    spends ``head_start`` seconds on other kernels (the side kernels of ``check``)."""
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


def record_side_seconds() -> float:
    """Seconds to compile the side kernels of ``check`` alone (empty cache expected), as the helper does."""
    from .compilation import _warm
    import rockdesign.dynamics  # noqa: F401  (imported before the clock starts, as in the helper)
    t0 = time.perf_counter()
    _warm("check", ("side",))
    return time.perf_counter() - t0


def record_callees() -> list[tuple[str, str, str, float]]:
    """Compile the engine (empty cache expected) and list the integrator's direct callees in the order
    numba compiled them, with their compile seconds (nested callees included).  Uses numba's event API
    (``numba:compile``)."""
    from numba.core import event

    from .compilation import _warm

    stack: list[list] = []
    callees: list[tuple[str, str, str, float]] = []

    class Listener(event.Listener):
        def on_start(self, ev):
            d = ev.data["dispatcher"]
            stack.append([(d.py_func.__module__, d.py_func.__qualname__), tuple(ev.data["args"]), time.perf_counter()])

        def on_end(self, ev):
            key, args, t0 = stack.pop()
            if stack and stack[-1][0] == INTEGRATOR and key[0].startswith("rockdesign."):
                callees.append((*key, str(args), round(time.perf_counter() - t0, 2)))

    listener = Listener()
    event.register("numba:compile", listener)
    try:
        _warm("check", ("engine",))
    finally:
        event.unregister("numba:compile", listener)
    return callees


def write_table() -> Path:
    """Regenerate ``compile_plan_table.py``, measuring in child processes with empty numba caches."""
    callees = _in_child("record_callees")
    side = _in_child("record_side_seconds")
    lines = ['"""The integrator\'s direct callees with the signatures it calls them with, in numba\'s compile order,',
             "and their first-run compile seconds (nested callees included) on the machine that wrote it.",
             "", "Written by ``python -m rockdesign.dynamics.compile_plan``; see :mod:`.compile_plan`.", '"""', "",
             f"SIDE_SECONDS = {side:.1f}", '"""Compile seconds of the side kernels of ``check`` (helper\'s head start)."""',
             "", "CALLEES = ("]
    lines += [f"    ({m!r}, {f!r},\n     {s!r}, {sec}),"
              for m, f, s, sec in callees]
    lines.append(")")
    TABLE.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return TABLE


def _in_child(function: str):
    import json
    with tempfile.TemporaryDirectory() as cache:
        code = f"import json; from rockdesign.dynamics.compile_plan import {function}; print(json.dumps({function}()))"
        out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True,
                             env={**os.environ, "NUMBA_CACHE_DIR": cache})
    return json.loads(out.stdout.strip().splitlines()[-1])


if __name__ == "__main__":
    print(write_table())
