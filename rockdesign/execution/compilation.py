"""First run: compile the numerical kernels a command needs before its work, and say so.

numba compiles a kernel on its first call and keeps the machine code in rockdesign's kernel cache, a
folder of the user's cache named by the digest of the kernel sources (:mod:`rockdesign.kernel_cache`).
After an installation or an upgrade the first command therefore spends tens of seconds compiling.
Every command that runs kernels calls :func:`prepare` after checking its input (so a typo is reported
at once on a first run too) with the groups of kernels it runs (:class:`Kernels`; a kind of structure
names its own, :meth:`rockdesign.kinds.base.StructureKind.kernels`).  A group whose marker file
(``compiled-<name>-…``) is missing from the cache folder is compiled by its warm-up — its kernels called
once on a tiny problem with the argument types of the real calls, so that the real calls load them —
in this process, after the line

    first run: compiling the numerical kernels of `check` (about 60 s, once per version)

and the marker is written when it is done.  The folder changes with the kernel sources, so a marker
always speaks of the kernels in its folder; with every marker present nothing is printed or compiled.
``ROCKDESIGN_NO_WARMUP=1`` skips the step (kernels then compile on first use, as numba does by default).
"""
from __future__ import annotations

import hashlib
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from ..kernel_cache import PACKAGE, kernel_cache_dir

MESSAGE = "first run: compiling the numerical kernels of `{command}` (about {seconds} s, once per version)"
"""The line printed before a first-run compilation."""


@dataclass(frozen=True)
class Kernels:
    """A group of numba kernels compiled together on a first run.

    Attributes:
        name: the group's name, unique among all groups (its marker is ``compiled-<name>``).
        warm_up: calls the group's kernels once on a tiny problem, with the argument types of the real calls.
        seconds: its first-run compile time on a quiet machine [s] (measured on the shared 2-core VM:
            docs/engine.md, "First run"); the announced estimate is this times :func:`_load_factor`.
    """

    name: str
    warm_up: Callable[[], object]
    seconds: float


def marker(group: Kernels) -> Path:
    """The file that says ``group`` is compiled into the kernel cache folder in use, for this installation:
    numba keeps the kernels of each source folder apart (by its path), so two installations of the same
    sources share the folder but not the machine code (``compiled-<name>-<12 hex digits of the package's path>``)."""
    where = hashlib.sha1(str(PACKAGE).encode()).hexdigest()[:12]
    return kernel_cache_dir() / f"compiled-{group.name}-{where}"


def missing(kernels: Sequence[Kernels]) -> list[Kernels]:
    """The groups of ``kernels`` not yet compiled into the kernel cache folder (no marker)."""
    return [k for k in kernels if not marker(k).is_file()]


PROBE_SECONDS = 1.0
"""CPU seconds of the busy loop that measures how much of a core this process gets (:func:`_load_factor`): long
enough to average over the scheduler's slices and a passing spike (a 0.2-s loop scattered from a quarter to two
thirds of a core at one load), short beside a compilation of a minute or more."""


CONTENTION_EXPONENT = 1.5
"""How a compilation's time grows with the slowdown of a core: ``slowdown ** CONTENTION_EXPONENT``.  Under load
the compilation gets a smaller share of a core and also needs more CPU time itself (42 s of CPU for the planar
engine at a load of 2.5, 60 s at 5.5, on the shared 2-core VM), so its time grows faster than the share falls;
fitted to first runs of `check` at loads 2.5–6 (docs/engine.md, "First run")."""


def _load_factor() -> float:
    """How much slower than on a quiet machine a compilation runs now: the slowdown of a core — the wall time over
    the CPU time of a short busy loop in this process, which gets the share of a core a one-thread compilation
    gets — to the power :data:`CONTENTION_EXPONENT`.

    The 1-minute load average over the cores, used before, lags the machine and counts what does not compete:
    on first runs of `check` (2 cores, shared) it announced 132 s for a compilation of 69 s (load 6.3, falling)
    and 88 s for one of 132 s (load 4.2, rising)."""
    wall, cpu = time.perf_counter(), time.process_time()
    while time.process_time() - cpu < PROBE_SECONDS:
        pass
    share = (time.process_time() - cpu) / max(time.perf_counter() - wall, 1e-9)
    return max(1.0, 1.0 / max(share, 1e-3)) ** CONTENTION_EXPONENT


def announcement(command: str, kernels: Sequence[Kernels]) -> str:
    """The line printed before compiling ``kernels`` for ``command``: :data:`MESSAGE`, the estimate being
    their idle-machine seconds times the current :func:`_load_factor` (rounded to 5 s above a minute: an
    estimate, not a measurement)."""
    seconds = sum(k.seconds for k in kernels) * _load_factor()
    return MESSAGE.format(command=command, seconds=max(1, round(seconds) if seconds < 60 else 5 * round(seconds / 5)))


def prepare(command: str, kernels: Sequence[Kernels], say: Callable[[str], object] | None = None) -> float:
    """Compile the groups of ``kernels`` that are not yet in the kernel cache, announcing it with ``say``
    (a print function, or None for silence); returns the seconds spent (0 when all were compiled before).

    Each group's marker is written as soon as its warm-up has run; a group whose marker cannot be written
    (a read-only cache folder) is compiled again by the next first run, which numba then loads from its
    cache if it could store the kernels."""
    if os.environ.get("ROCKDESIGN_NO_WARMUP"):
        return 0.0
    todo = missing(kernels)
    if not todo:
        return 0.0
    if say is not None:
        say(announcement(command, todo))
    t0 = time.perf_counter()
    for group in todo:
        started = time.perf_counter()
        group.warm_up()
        _write_marker(group, time.perf_counter() - started)
    seconds = time.perf_counter() - t0
    if say is not None:
        say(f"compiled in {seconds:.0f} s")
    return seconds


def _write_marker(group: Kernels, seconds: float) -> None:
    """Write the marker (with the measured seconds) atomically: another process may be compiling too."""
    path = marker(group)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
        temporary.write_text(f"{seconds:.1f}\n", encoding="utf-8")
        os.replace(temporary, path)
    except OSError:     # an unwritable cache folder: the next run announces the compilation again, nothing else
        return
