"""Write ``compile_plan_table.py`` (:mod:`.compile_plan`): the integrator's direct callees, the argument
types it calls them with and their compile seconds, measured in child processes with empty numba
caches.  A developer's tool, run after changing a kernel's arguments::

    python -m rockdesign.execution.compile_plan_writer

It uses numba's event API (``numba:compile``) to see what the integrator compiles, in which order.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .compilation import _warm

TABLE = Path(__file__).with_name("compile_plan_table.py")
INTEGRATOR = ("rockdesign.planar.dynamics.engine", "integrate")


def record_callees() -> list[tuple[str, str, str, float]]:
    """Compile the engine (empty cache expected) and list the integrator's direct callees in the order
    numba compiled them, with their compile seconds (nested callees included).  Uses numba's event API
    (``numba:compile``)."""
    from numba.core import event

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
    lines = ['"""The integrator\'s direct callees with the signatures it calls them with, in numba\'s compile order,',
             "and their first-run compile seconds (nested callees included) on the machine that wrote it.",
             "", "Written by ``python -m rockdesign.execution.compile_plan_writer``; see :mod:`.compile_plan`.", '"""', "",
             "CALLEES = ("]
    lines += [f"    ({m!r}, {f!r},\n     {s!r}, {sec}),"
              for m, f, s, sec in callees]
    lines.append(")")
    TABLE.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return TABLE


def _in_child(function: str):
    with tempfile.TemporaryDirectory() as cache:
        code = f"import json; from rockdesign.execution.compile_plan_writer import {function}; print(json.dumps({function}()))"
        out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True,
                             env={**os.environ, "NUMBA_CACHE_DIR": cache})
    return json.loads(out.stdout.strip().splitlines()[-1])


if __name__ == "__main__":
    print(write_table())
