"""Wall-time measurement: warm-up, median of repeats within a time budget, machine description."""
from __future__ import annotations

import datetime as _dt
import os
import platform
import time
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class TimingPolicy:
    """How often a call is repeated.

    Attributes:
        max_repeats: at most this many timed runs.
        min_repeats: at least this many timed runs (unless one run exceeds ``budget``).
        budget: stop repeating once the timed runs have used this many seconds [s].
    """

    max_repeats: int = 7
    min_repeats: int = 3
    budget: float = 2.0


FULL = TimingPolicy(max_repeats=7, min_repeats=3, budget=3.0)
QUICK = TimingPolicy(max_repeats=5, min_repeats=1, budget=0.15)


def time_call(fn, policy: TimingPolicy = FULL) -> tuple[float, int, list[float]]:
    """(median seconds, repeats, all samples) of ``fn()`` — call ``fn`` once untimed beforehand to warm up.

    A run longer than ``policy.budget`` is timed once; otherwise runs repeat until ``min_repeats``
    are done and either ``max_repeats`` is reached or the budget is used.
    """
    samples: list[float] = []
    while len(samples) < policy.max_repeats:
        t0 = time.perf_counter()
        fn()
        samples.append(time.perf_counter() - t0)
        spent = sum(samples)
        if len(samples) >= policy.min_repeats and spent + float(np.median(samples)) > policy.budget:
            break
        if samples[0] > policy.budget:
            break
    return float(np.median(samples)), len(samples), samples


def machine_info() -> dict:
    """Date, host description (``uname -a``), CPU model, core count, load and library versions."""
    import numba
    import scipy
    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        load = os.getloadavg()
    except OSError:
        load = (float("nan"),) * 3
    u = platform.uname()
    return {"date": _dt.datetime.now().astimezone().isoformat(timespec="seconds"),
            "uname": " ".join([u.system, u.node, u.release, u.version, u.machine]),
            "cpu": cpu, "nproc": os.cpu_count(), "load_average": [round(x, 2) for x in load],
            "python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
            "numba": numba.__version__}


def host_description(machine: dict) -> str:
    """Operating system, kernel release and architecture from :func:`machine_info`'s ``uname``
    ("Linux 6.18.44 x86_64"): the kernel's build string ("#1 SMP …") and the host name say nothing to a reader."""
    parts = str(machine.get("uname", "")).split()
    if len(parts) < 3:
        return " ".join(parts)
    return f"{parts[0]} {parts[2].split('-')[0]} {parts[-1]}"
