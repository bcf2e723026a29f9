"""First-run compilation of the numerical kernels: detect it, say so, compile only what a command needs.

numba compiles a kernel on its first call and keeps the machine code in its on-disk cache
(``cache=True``; :mod:`rockdesign.kernel_cache` drops stale entries).  After an installation (or an
upgrade) the first command therefore spends tens of seconds compiling — formerly behind a progress
bar that did not move.  :func:`prepare` is called by the CLI commands before their work starts: when
numba's cache index of a kernel the command needs is missing, it prints

    compiling the numerical kernels of `check` (first use after installing or upgrading; later runs
    load them from the cache): expect 30–51 s at the current machine load


and compiles exactly those kernels by calling them on a tiny problem with the argument types of the
real calls (so the real calls load them from the cache), then reports the seconds it took.  On two or
more cores a second process shares the work (numba compiles on one core; :mod:`.compile_plan`), and
``check`` reads its records and computes SD_max while the helper finishes the rocking engine.
Commands compile only their own kernels (:data:`KERNELS`): ``simulate`` never compiles the closed-form
linear integrator, ``records`` only the elastic response spectrum, the cylinder's commands their own
integrator.  Every CLI command that runs kernels calls :func:`prepare` after checking its input, so a
typo is reported at once on a first run too (docs/engine.md, "First run").

Imports of the kernels' modules stay inside the functions here, on purpose: each command imports only
the modules of its own kernels (``records`` never loads the engine, ``simulate`` never the cylinder),
which is what keeps a first run of a light command light; the table names them as strings.
"""
from __future__ import annotations

import atexit
import contextlib
import importlib
import os
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

# Kernels (module, function) each command calls; the estimates are first-run compile seconds measured
# on the 2-core development machine (benchmarks/bench_check.py reports the first `check` run).
ENGINE = (("rockdesign.planar.dynamics.batch", "_run_batch"), ("rockdesign.planar.dynamics.batch", "_job"),
          ("rockdesign.planar.dynamics.engine", "integrate"), ("rockdesign.planar.dynamics.transitions", "top_displacements"))
"""The planar rocking engine: the parallel batch driver, the job it runs in every driver (``simulate``'s
one analysis, serial batches) and the integrator the job calls."""
ELASTIC_SPECTRUM = (("rockdesign.motions.spectra", "spectral_displacements"),)
LINEAR_EXACT = (("rockdesign.planar.dynamics.linear_exact", "integrate_linear_exact"),)
CYLINDER = (("rockdesign.cylinder.kernel", "integrate"),)
KERNELS: dict[str, tuple[tuple[str, str], ...]] = {
    "check": ENGINE + LINEAR_EXACT + ELASTIC_SPECTRUM,
    "simulate": ENGINE,
    "ensemble": ENGINE,
    "calibrate": ENGINE,                       # the simulated free vibration of --plot
    "records": ELASTIC_SPECTRUM,
    "spectrum": (("rockdesign.planar.dynamics.engine", "integrate"), ("rockdesign.planar.spectra.kernel", "spectrum_kernel")),
    "cylinder": CYLINDER,
    "cylinder-check": CYLINDER + ENGINE + ELASTIC_SPECTRUM,   # the 3D records and their planar components
    "cylinder-spectrum": (("rockdesign.cylinder.spectrum", "_grid"),),
    "bench": ENGINE + LINEAR_EXACT,
}
WARM_UPS: dict[str, tuple[str, str]] = {"spectrum": ("rockdesign.planar.spectra.kernel", "warm_up")}
"""Warm-up functions (module, function) of kernels that live above the dynamics layer, by command: reached
by name through :func:`_dispatcher` like the kernels of :data:`KERNELS`, so this module imports no analysis
module (the pulse-spectrum kernel stays in ``rockdesign.planar.spectra``; no dynamics ↔ spectra cycle)."""
ENGINE_COMMANDS = ("check", "simulate", "ensemble", "calibrate", "spectrum", "cylinder-check", "bench")
"""Commands that run the planar integrator: a helper process compiles half of its callees (:func:`prepare`)."""
ESTIMATE_SECONDS = {"check": 30, "simulate": 30, "ensemble": 30, "calibrate": 30, "records": 5, "spectrum": 30,
                    "cylinder": 30, "cylinder-check": 45, "cylinder-spectrum": 30, "bench": 30}
"""First-run compile seconds of each command on an idle 2-core machine (the low end of the estimate)."""
MESSAGE = ("compiling the numerical kernels of `{command}` (first use after installing or upgrading; later runs "
           "load them from the cache): expect {low}–{high} s at the current machine load")
SPREAD = 1.7
"""High end / low end of the estimate: compile times measured at one load scatter by this much."""
MEASURED = Path(__file__).resolve().parents[1] / "__pycache__" / "compile-seconds.json"
"""Compile seconds measured on this machine, per command, normalised to an idle machine (:func:`estimate`)."""


def _load_factor() -> float:
    """How much slower than on an idle machine a compilation runs now: the 1-minute load average over the
    usable cores (at least 1; 1 where the load average is unknown)."""
    from .executor import usable_cores
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):
        return 1.0
    return max(1.0, load / max(1, usable_cores()))


def _measured() -> dict:
    import json
    try:
        return json.loads(MEASURED.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}


def estimate(command: str) -> tuple[int, int]:
    """(low, high) seconds the first-run compilation of ``command`` will take now: its idle-machine time —
    measured on this machine by an earlier compilation when there is one (of this command, else scaled
    from another command's), else :data:`ESTIMATE_SECONDS` — times the current :func:`_load_factor`."""
    base = float(ESTIMATE_SECONDS.get(command, 30))
    measured = _measured()
    if command in measured:
        base = float(measured[command])
    elif measured:
        ratios = [v / ESTIMATE_SECONDS[k] for k, v in measured.items() if k in ESTIMATE_SECONDS]
        if ratios:
            base *= max(ratios)
    low = base * _load_factor()
    return max(1, round(low)), max(2, round(SPREAD * low))


def _remember(command: str, seconds: float, factor: float) -> None:
    """Store the idle-machine equivalent of a measured compilation for :func:`estimate` (best effort)."""
    import json
    data = _measured()
    data[command] = round(seconds / factor, 1)
    try:
        MEASURED.parent.mkdir(parents=True, exist_ok=True)
        MEASURED.write_text(json.dumps(data, indent=1, sort_keys=True), encoding="utf-8")
    except OSError:     # a read-only install: the next announcement falls back to the built-in estimate
        pass


def announcement(command: str) -> str:
    """The line printed before a first-run compilation of ``command`` (:data:`MESSAGE`)."""
    low, high = estimate(command)
    return MESSAGE.format(command=command, low=low, high=high)


CYLINDER_WARM_UP = ("rockdesign.cylinder.warm_up", "warm_up")
"""The cylinder's warm-up (its integrator, or its spectrum grid), reached by name like :data:`WARM_UPS`: the
cylinder's spectrum runs on :mod:`rockdesign.execution.scheduling`, so a direct import would make a cycle."""


def _dispatcher(module: str, name: str):
    return getattr(importlib.import_module(module), name)


def is_cached(dispatcher) -> bool:
    """True when numba's on-disk cache holds an index for ``dispatcher`` (compiled before).

    False when the cache cannot be inspected (no ``cache=True``, a read-only installation).
    """
    try:
        index = Path(dispatcher._cache._cache_file._index_path)
    except AttributeError:
        return False
    return index.is_file()


def missing_kernels(command: str) -> list[str]:
    """Names (``module.function``) of the kernels ``command`` needs that are not in numba's cache."""
    from ..kernel_cache import refresh_stale_caches
    refresh_stale_caches()
    return [f"{m}.{f}" for m, f in KERNELS.get(command, ()) if not is_cached(_dispatcher(m, f))]


PARTS = ("engine", "side")
"""What :func:`_warm` compiles: the rocking engine (the batch kernel and the integrator it runs, or the
pulse-spectrum kernel around the integrator), which the helper process compiles, and the side kernels
this process compiles meanwhile (the closed-form linear integrator of the accuracy statement, the
elastic spectrum of Polyakov's rule, the cylinder's integrator)."""


PLANAR_WARM_UP = ("rockdesign.planar.dynamics.warm_up", "warm_up")
"""The planar kernels' warm-up, reached by name like :data:`WARM_UPS`."""


def _warm(command: str, parts: tuple[str, ...] = PARTS) -> None:
    """Call the command's kernels once on a tiny problem, with the argument types of the real calls."""
    _dispatcher(*PLANAR_WARM_UP)(command, parts, ENGINE_COMMANDS, WARM_UPS, CYLINDER_WARM_UP)


HELPER_STARTUP_SECONDS = 1.0
"""Seconds the helper spends starting Python and importing numba and rockdesign before it compiles: its
head start on this process's half of the callees (:func:`.compile_plan.split`)."""


def _shares(command: str) -> tuple[list, list]:
    """The integrator's callees this process and the helper compile (:mod:`.compile_plan`)."""
    from .compile_plan import callee_table, split
    return split(callee_table(), HELPER_STARTUP_SECONDS)


def _helper(command: str) -> None:
    """The second process's work: its half of the integrator's callees, then — once this process has
    compiled the other half and writes ``go`` — the integrator and the batch kernel."""
    from .compile_plan import compile_entries
    compile_entries(_shares(command)[1])
    if sys.stdin.readline().strip() == "go":
        _warm(command, ("engine",))


class _Helper:
    """The helper process (:func:`_start_helper`)."""

    def __init__(self, process: subprocess.Popen):
        self.process = process

    def go(self) -> None:
        """Tell the helper that this process's half of the callees is in the cache."""
        with contextlib.suppress(OSError):     # the helper has died: wait() says so, its work is done here
            self.process.stdin.write(b"go\n")
            self.process.stdin.close()

    def wait(self) -> int:
        return self.process.wait()

    def kill(self) -> None:
        self.process.kill()
        self.process.wait()


def _start_helper(command: str) -> _Helper | None:
    """A second Python process compiling into numba's on-disk cache while this one compiles too
    (numba compiles on one core); None on one core or when it cannot start."""
    from .executor import usable_cores
    if command not in ENGINE_COMMANDS or usable_cores() < 2:
        return None
    code = f"from rockdesign.execution.compilation import _helper; _helper({command!r})"
    from ..paths import child_environment
    try:   # (the helper shares numba's cache with this process)
        return _Helper(subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                        env=child_environment()))
    except OSError:
        return None


@dataclass
class _Pending:
    """Compilation still running in the helper after :func:`prepare` returned (``background=True``)."""
    helper: _Helper
    command: str
    kernels: int
    t0: float
    say: object
    factor: float = 1.0
    full: bool = False


_pending: _Pending | None = None


def prepare(command: str, say=None, *, background: bool = False) -> float:
    """Compile the kernels ``command`` needs if numba's cache lacks them, announcing it; returns seconds.

    ``say(text)`` prints a line (the CLI passes its stderr console); nothing is printed and nothing is
    compiled when every kernel is cached.  ``ROCKDESIGN_NO_WARMUP=1`` skips the step (kernels then
    compile on first use, as numba does by default).

    On two or more cores a second process shares the work (:mod:`.compile_plan`): each process compiles
    half of the integrator's callees; then the helper compiles the integrator and the batch kernel around
    it (loading every callee from the cache) while this process compiles the side kernels of ``check``
    (the closed-form linear integrator, the elastic spectrum).  With ``background=True`` this function
    returns then, and the caller does work that needs no rocking engine (reading records, SD_max) before
    :func:`finish_compilation` waits for the helper; ``check`` does so (its progress shows the wait).
    If the helper fails, what it did not compile is compiled here: the outcome is the same.
    """
    if os.environ.get("ROCKDESIGN_NO_WARMUP") or command not in KERNELS:
        return 0.0
    missing = missing_kernels(command)
    if not missing:
        return 0.0
    if say is not None:
        say(announcement(command))
    factor = _load_factor()
    full = len(missing) == len(KERNELS[command])     # only a complete compilation measures the command
    t0 = time.perf_counter()
    helper = _start_helper(command)
    if helper is None:
        _warm(command, PARTS)
        return _compiled(len(missing), t0, say, command if full else None, factor)
    try:
        from .compile_plan import compile_entries
        compile_entries(_shares(command)[0])
        helper.go()                        # the helper compiles the integrator and the batch kernel now
        _warm(command, ("side",))
    except BaseException:
        helper.kill()
        raise
    global _pending
    _pending = _Pending(helper, command, len(missing), t0, say, factor, full)
    return time.perf_counter() - t0 if background else finish_compilation()


def compilation_pending() -> bool:
    """True while the helper started by :func:`prepare` (``background=True``) may still be compiling."""
    return _pending is not None


def finish_compilation() -> float:
    """Wait for the helper of :func:`prepare` (``background=True``) and return the seconds since the
    compilation began (0 when none is pending); compile here whatever a failed helper did not."""
    global _pending
    pending, _pending = _pending, None
    if pending is None:
        return 0.0
    try:
        ok = pending.helper.wait() == 0
    except BaseException:             # Ctrl-C while waiting
        pending.helper.kill()
        raise
    if not ok:
        _warm(pending.command, ("engine",))
    return _compiled(pending.kernels, pending.t0, pending.say, pending.command if pending.full else None,
                     pending.factor)


def _abandon() -> None:
    """At exit, a helper nobody waited for (the command failed before its analyses) is stopped."""
    global _pending
    pending, _pending = _pending, None
    if pending is not None:
        pending.helper.kill()


atexit.register(_abandon)


def _compiled(kernels: int, t0: float, say, command: str | None = None, factor: float = 1.0) -> float:
    seconds = time.perf_counter() - t0
    if command is not None:
        _remember(command, seconds, max(factor, _load_factor()))
    if say is not None:
        say(f"compiled {kernels} kernel{'s' if kernels > 1 else ''} in {seconds:.0f} s")
    return seconds
