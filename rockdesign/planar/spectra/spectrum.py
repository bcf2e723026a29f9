"""Rocking spectra: θ_max/α and overturning of one system over a grid of pulses (thesis Sec 3.3.2, SPEC §4).

:func:`compute_spectrum` runs one nonlinear time-history analysis per grid point (row = pulse
amplitude a_p, column = pulse period T_p) with the engine of :mod:`rockdesign.planar.dynamics` through the
parallel kernel of :mod:`rockdesign.planar.spectra.kernel`, chunked by rows over an executor of
:mod:`rockdesign.execution.executor` (this machine's cores, or dask.distributed), resumable from the
chunk files of an interrupted run.

Each analysis ends at the excitation end + ``t_free`` (10 s: Zhang–Makris near-threshold cases
overturn up to ~9 s after the pulse) or earlier, as soon as the remaining mechanical energy cannot
raise θ_max or reach θc any more (docs/early_termination.md) — the result is the same as the
full-length run's.
"""
from __future__ import annotations

import math
import os
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from ..dynamics.batch import batch_options
from ..dynamics.model import REST_VELOCITY, ModelChoice, resolve_structure, system_parameters
from ..dynamics.overturning import overturned_by
from ...errors import RockdesignError
from ...motions.motion import PULSE_KINDS
from ..design.quantities import RIGID_SUPERSTRUCTURE_RATIO
from ..system import RockingSystem
from .axes import DEFAULT_X, DEFAULT_Y, Axis, SpectrumScales, pulse_amplitudes, pulse_periods, spectrum_scales
from ...execution.executor import ChunkStore, LocalExecutor, fingerprint, run_chunks
from .kernel import (N_OUT, SOURCE_DIGEST, OUT_DYNAMIC, OUT_EXCEEDED, OUT_IMPACTS, OUT_IMPACTS_BEFORE_DYNAMIC,
                     OUT_IMPACTS_BEFORE_EXCEEDED, OUT_STATUS, OUT_STEPS, OUT_T_STOP, OUT_THETA_MAX, pulse_shape,
                     spectrum_rows, warm_up)

KERNEL_VERSION = "rockdesign-spectrum-kernel-1"
"""Part of every chunk fingerprint: bump when the kernel's results change, so old chunks are not reused."""
TARGET_CHUNKS = 48
"""Default number of row chunks (more on large dask clusters: 4 per worker thread)."""


class SpectrumError(RockdesignError):
    """Invalid spectrum settings (pulse, model, tolerances, free-vibration time...)."""


BYTES_PER_POINT = 8 * (3 * N_OUT + 12)
"""Memory [B] per grid point: the chunk results, the assembled (ny, nx, N_OUT) array and a copy while
it is assembled (float64), plus the derived grids of the analysis, the lines and the figures."""
CPU_PER_ANALYSIS = 0.12e-3
"""CPU seconds per analysis of the cheapest system (a block, exact EOM; docs/spectra.md's measurement):
the time estimate is a lower bound (a 2DOF podium costs about 20 times more)."""
MAX_HOURS = 24.0
"""A grid estimated to take longer than this on this machine's cores is refused (split it, or run it on
a dask cluster)."""


def check_grid(x: Axis, y: Axis, n_spectra: int = 1, *, distributed: bool = False,
               available: float | None = None) -> tuple[float, float]:
    """(memory [B], time [s]) of ``n_spectra`` spectra on the x × y grid; raise :class:`SpectrumError` with
    the estimates when the memory exceeds the ``available`` memory [B] (default: this machine's) or, on
    this machine (not ``distributed``), the time exceeds :data:`MAX_HOURS`."""
    points = x.n * y.n * n_spectra
    memory = float(points) * BYTES_PER_POINT
    cores = os.cpu_count() or 1
    seconds = points * CPU_PER_ANALYSIS / cores
    available = available_memory() if available is None else available
    grid = f"{x.n:,} × {y.n:,}" + (f" × {n_spectra} spectra" if n_spectra > 1 else "") + f" = {points:,} analyses"
    estimate = f"{grid}: about {_bytes(memory)} of memory and at least {_duration(seconds)} on {cores} core(s)"
    if available is not None and memory > available:
        raise SpectrumError("the spectrum grid does not fit in memory", key="x/y",
                            expected=f"a grid that needs less than the {_bytes(available)} available "
                            "(fewer points per axis)", found=estimate)
    if not distributed and seconds > MAX_HOURS * 3600:
        raise SpectrumError("the spectrum grid would take too long on this machine", key="x/y",
                            expected=f"a grid of at most about {MAX_HOURS:g} h (fewer points, or a dask cluster as the executor on "
                            "a cluster)", found=estimate)
    return memory, seconds


def check_ordinates(ordinates, y: Axis, relative: bool) -> None:
    """Refuse ``equivalent_at`` ordinates that would be ignored or meaningless: without a reference (``relative``)
    (Eq 3.65 compares two systems), non-finite, or outside the y axis [lo, hi]."""
    if not ordinates:
        return
    shown = ", ".join(f"{v:g}" for v in ordinates)
    if not relative:
        raise SpectrumError("used by a relative spectrum only (Eq 3.65 compares two systems)",
                            key="equivalent_at", expected="a reference project (relative) with it", found=shown)
    for value in ordinates:
        if not (math.isfinite(value) and y.lo <= value <= y.hi):
            raise SpectrumError("ordinate outside the y axis", key="equivalent_at",
                                expected=f"a value of {y.name} within {y.lo:g}…{y.hi:g}", found=f"{value:g}")


def available_memory() -> float | None:
    """Memory [B] available to this process: Linux's MemAvailable (free + reclaimable cache), else the
    free physical memory (sysconf); None where unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0
    except (OSError, ValueError, IndexError):
        pass
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_AVPHYS_PAGES"))
    except (AttributeError, ValueError, OSError):
        return None


def _bytes(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if n < 1000 or unit == "PB":
            return f"{n:.3g} {unit}"
        n /= 1000.0
    return f"{n:.3g} PB"


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.3g} s"
    if seconds < 7200:
        return f"{seconds / 60:.3g} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.3g} h"
    return f"{seconds / 86400:.3g} days"


@dataclass(frozen=True)
class SpectrumRequest:
    """What to compute.

    Attributes:
        pulse: ``ricker-anti`` | ``ricker-sym`` | ``sine`` | ``cycloidal-a`` | ``cycloidal-b`` | ``cycloidal-c``.
        x, y: the axes (:mod:`rockdesign.planar.spectra.axes`).
        equations: ``exact`` (nonlinear EOM) or ``linear`` (linearized EOM, uplift at g α).
        structure: ``auto`` | ``block`` | ``frame`` | ``rigid-superstructure`` | ``podium-2dof``.
        overturn: ``static`` (θ_max ≥ θc counts as overturning) or ``dynamic`` (|θ| reaches π/2).
        rtol, atol: integrator tolerances.
        rest_velocity: rest threshold [rad/s] (SPEC §3.6).
        t_free: free vibration [s] simulated after the pulse ends (at most; see the energy bound).
        tm_ratio: t_m/T_p of Ricker wavelets (SPEC §4: 1.5).
        energy_stop: stop each analysis when the energy bound proves the result final.
        rigid_ratio: ω_s/p above which ``auto`` treats a superstructure as rigid (SPEC §6).
        stop_at_capacity: (static criterion only) stop an analysis when |θ| first reaches θc — the
            verdict is final there; θ_max of such points is θc, the impacts before overturning are
            those before θc, and dynamic overturning is not followed (~20 % fewer steps).
    """

    pulse: str
    x: Axis = DEFAULT_X
    y: Axis = DEFAULT_Y
    equations: str = "exact"
    structure: str = "auto"
    overturn: str = "static"
    rtol: float = 1e-10
    atol: float = 1e-12
    rest_velocity: float = REST_VELOCITY
    t_free: float = 10.0
    tm_ratio: float = 1.5
    energy_stop: bool = True
    rigid_ratio: float = RIGID_SUPERSTRUCTURE_RATIO
    stop_at_capacity: bool = False

    def validate(self) -> None:
        """Raise :class:`SpectrumError` for settings the engine cannot run."""
        if self.pulse not in PULSE_KINDS:
            raise SpectrumError("unknown pulse", key="pulse", expected=" | ".join(PULSE_KINDS),
                                found=repr(self.pulse))
        if self.equations not in ("exact", "linear"):
            raise SpectrumError("unknown equations", key="model", expected="exact | linear (or auto)",
                                found=repr(self.equations))
        if self.overturn not in ("static", "dynamic"):
            raise SpectrumError("unknown overturning criterion", key="overturn", expected="static | dynamic",
                                found=repr(self.overturn))
        if not (math.isfinite(self.t_free) and self.t_free >= 0.0):
            raise SpectrumError("invalid free-vibration time", key="t_free", expected="a time ≥ 0 s",
                                found=repr(self.t_free))
        if not (0.0 < self.rtol < 1e-2 and 0.0 < self.atol < 1e-2):
            raise SpectrumError("invalid tolerance", key="rtol", expected="0 < rtol, atol < 1e-2",
                                found=f"rtol={self.rtol!r}, atol={self.atol!r}")
        if self.stop_at_capacity and self.overturn != "static":
            raise SpectrumError("stopping at θc cannot tell dynamic overturning", key="stop_at_capacity",
                                expected="overturn = static", found=f"overturn = {self.overturn}")
        if not (math.isfinite(self.tm_ratio) and self.tm_ratio >= 0.0):
            raise SpectrumError("invalid wavelet centre", key="tm_ratio", expected="t_m/T_p ≥ 0 (1.5: thesis)",
                                found=repr(self.tm_ratio))

    def as_json(self) -> dict:
        d = asdict(self)
        d["x"] = self.x.as_json()
        d["y"] = self.y.as_json()
        return d


@dataclass
class RockingSpectrum:
    """A computed rocking spectrum (arrays have shape len(y) × len(x)).

    Attributes:
        request: the :class:`SpectrumRequest`.
        system: the analysed system.
        structure: the structural model used (``auto`` resolved).
        scales: the system's normalisations (:class:`SpectrumScales`: α, θc, p, g tan α...).
        x, y: axis values; ``periods`` T_p [s] per column, ``amplitudes`` a_p [m/s²] per row.
        out: raw kernel outputs (ny, nx, ``kernel.N_OUT``).
        execution: executor, chunks, timings.
        axes_scales: the normalisations that turned axis values into pulses (the system's own, or
            the project's for the reference of a relative spectrum).
    """

    request: SpectrumRequest
    system: RockingSystem
    structure: str
    scales: SpectrumScales
    x: np.ndarray
    y: np.ndarray
    periods: np.ndarray
    amplitudes: np.ndarray
    out: np.ndarray
    execution: dict = field(default_factory=dict)
    axes_scales: SpectrumScales | None = None

    @property
    def shape(self) -> tuple[int, int]:
        return self.out.shape[0], self.out.shape[1]

    @property
    def n_analyses(self) -> int:
        return self.out.shape[0] * self.out.shape[1]

    @property
    def model_label(self) -> str:
        return f"{self.structure}/{self.request.equations}"

    @property
    def theta_max(self) -> np.ndarray:
        """max |θ| [rad] (π/2 where the system overturned dynamically)."""
        return self.out[:, :, OUT_THETA_MAX]

    @property
    def theta_max_over_alpha(self) -> np.ndarray:
        """θ_max/α with α = atan(B/H) of the column (thesis Figs 3.19–3.20)."""
        return self.theta_max / self.scales.alpha

    @property
    def exceeded(self) -> np.ndarray:
        """θ_max ≥ θc (static overturning: the capacity was exceeded)."""
        return self.out[:, :, OUT_EXCEEDED] != 0.0

    @property
    def dynamic(self) -> np.ndarray:
        """|θ| reached π/2 (dynamic overturning)."""
        return self.out[:, :, OUT_DYNAMIC] != 0.0

    @property
    def overturned(self) -> np.ndarray:
        """Overturning by the request's criterion (``static``: exceeded; ``dynamic``: |θ| = π/2)."""
        return overturned_by(self.request.overturn, self.exceeded, self.dynamic)

    @property
    def impacts_before_overturn(self) -> np.ndarray:
        """Impacts before overturning, −1 where the system did not overturn (by the request's criterion).

        As ``simulate`` reports them: where the system fell (|θ| reached π/2), the impacts before the
        fall — the Zhang–Makris overturning mode (thesis Sec 2.2); where it only exceeded θc and came
        back (static criterion), the impacts before θc was first reached.
        """
        n = np.where(self.dynamic, self.out[:, :, OUT_IMPACTS_BEFORE_DYNAMIC],
                     self.out[:, :, OUT_IMPACTS_BEFORE_EXCEEDED]).astype(np.int64)
        n[~self.overturned] = -1
        return n

    @property
    def impacts(self) -> np.ndarray:
        """Impacts counted until each analysis stopped (an early stop ends the count)."""
        return self.out[:, :, OUT_IMPACTS].astype(np.int64)

    @property
    def status(self) -> np.ndarray:
        """Engine status code per analysis (``rockdesign.planar.dynamics.engine.ST_*``)."""
        return self.out[:, :, OUT_STATUS].astype(np.int64)

    @property
    def steps(self) -> np.ndarray:
        return self.out[:, :, OUT_STEPS].astype(np.int64)

    @property
    def t_stop(self) -> np.ndarray:
        """Time [s] at which each analysis stopped."""
        return self.out[:, :, OUT_T_STOP]


def request_from_project(project, pulse: str, *, x: Axis | None = None, y: Axis | None = None,
                         equations: str = "auto", structure: str | None = None, overturn: str | None = None,
                         rtol: float | None = None, t_free: float | None = None, tm_ratio: float = 1.5,
                         energy_stop: bool = True, stop_at_capacity: bool = False) -> SpectrumRequest:
    """A :class:`SpectrumRequest` with the project's ``[analysis]`` settings as defaults."""
    a = project.analysis
    if equations == "auto":
        equations = "linear" if a.equations == "linear" else "exact"
    req = SpectrumRequest(pulse=pulse, x=x or DEFAULT_X, y=y or DEFAULT_Y, equations=equations,
                          structure=structure or a.model, overturn=overturn or a.overturn,
                          rtol=rtol if rtol is not None else a.rtol, atol=a.atol, rest_velocity=a.rest_velocity,
                          t_free=t_free if t_free is not None else a.free_vibration, tm_ratio=tm_ratio,
                          energy_stop=energy_stop, rigid_ratio=a.rigid_superstructure_ratio,
                          stop_at_capacity=stop_at_capacity)
    req.validate()
    return req


def prepare(system: RockingSystem, request: SpectrumRequest, axes_scales: SpectrumScales | None = None):
    """(structure, sp, kind, shape, periods, amplitudes, opts, scales) of a spectrum, validated.

    ``axes_scales`` turns axis values into pulses (default: the system's own normalisations).
    """
    request.validate()
    structure = resolve_structure(system, request.structure, request.rigid_ratio)
    sp = system_parameters(system, ModelChoice(structure, request.equations), rest_velocity=request.rest_velocity)
    kind, shape = pulse_shape(request.pulse, request.tm_ratio)
    scales = spectrum_scales(system)
    grid = axes_scales if axes_scales is not None else scales
    periods = pulse_periods(request.x, grid)
    amplitudes = pulse_amplitudes(request.y, grid)
    opts = batch_options(request.rtol, request.atol, energy_stop=request.energy_stop,
                         stop_at_capacity=request.stop_at_capacity)
    return structure, sp, kind, shape, periods, amplitudes, opts, scales


def compute_spectrum(system: RockingSystem, request: SpectrumRequest, *, executor=None,
                     store_dir: str | Path | None = None, resume: bool = True, keep_chunks: bool = False,
                     chunk_rows: int | None = None, progress: Callable[[int], None] | None = None,
                     axes_scales: SpectrumScales | None = None) -> RockingSpectrum:
    """Compute the rocking spectrum of ``system`` (thesis Figs 3.19–3.20, 4.6–4.7).

    Args:
        system: the rocking system (SI).
        request: pulse, axes, model and tolerances.
        executor: :class:`~rockdesign.execution.executor.LocalExecutor` (default: in-process, all
            cores) or :class:`~rockdesign.execution.executor.DaskExecutor`; not closed here.
        store_dir: folder for chunk files; completed chunks are saved there as they arrive, and a
            rerun with identical inputs resumes from them. None: no chunk files.
        resume: reuse matching chunks in ``store_dir``.
        keep_chunks: keep the chunk files after success (default: delete them once assembled).
        chunk_rows: rows per chunk (default: the interrupted run's value when resuming, else
            ceil(ny / max(48, 4 × executor slots))).
        progress: called with the number of analyses of every finished chunk.
        axes_scales: normalisations that turn the axis values into pulses T_p, a_p — default the
            system's own; a relative spectrum passes the project's, so that the reference system is
            analysed at exactly the project's pulses.

    Returns:
        :class:`RockingSpectrum`.
    """
    t_start = time.perf_counter()
    structure, sp, kind, shape, periods, amplitudes, opts, scales = prepare(system, request, axes_scales)
    executor = executor if executor is not None else LocalExecutor(warm_up=warm_up)
    ny, nx = amplitudes.size, periods.size
    base = fingerprint(KERNEL_VERSION, SOURCE_DIGEST, sp, int(kind), shape, periods, amplitudes, opts,
                       float(request.t_free))
    if chunk_rows is None and store_dir is not None and resume:
        found = ChunkStore(store_dir, "").manifest()
        if found and found.get("base") == base:
            chunk_rows = int(found["chunk_rows"])
    warm = 0.0
    if chunk_rows is None:
        t0 = time.perf_counter()
        executor.start()  # a remote cluster reports its size only once connected
        warm = time.perf_counter() - t0
        chunk_rows = max(1, math.ceil(ny / max(TARGET_CHUNKS, 4 * executor.slots)))
    if int(chunk_rows) < 1:
        raise SpectrumError("invalid chunk size", key="chunk_rows", expected="an integer ≥ 1",
                            found=str(chunk_rows))
    chunk_rows = int(chunk_rows)
    bounds = [(r, min(r + chunk_rows, ny)) for r in range(0, ny, chunk_rows)]
    tasks = [(np.ascontiguousarray(amplitudes[r0:r1]), opts, float(request.t_free)) for r0, r1 in bounds]
    store = None
    if store_dir is not None:
        store = ChunkStore(store_dir, fingerprint(base, chunk_rows),
                           {"base": base, "chunk_rows": chunk_rows, "n_chunks": len(bounds), "ny": ny, "nx": nx,
                            "pulse": request.pulse, "x": request.x.text, "y": request.y.text})

    def on_chunk(i, resumed):
        if progress is not None:
            progress((bounds[i][1] - bounds[i][0]) * nx)

    run = run_chunks(spectrum_rows, tasks, common=(sp, int(kind), shape, periods), executor=executor,
                     store=store, resume=resume, progress=on_chunk)
    out = np.concatenate([r["out"] for r in run.results], axis=0) if run.results else np.zeros((0, nx, N_OUT))
    if out.shape != (ny, nx, N_OUT):
        raise RuntimeError(f"assembled spectrum has shape {out.shape}, expected {(ny, nx, N_OUT)}")
    if store is not None and not keep_chunks:
        store.clear()
    wall = time.perf_counter() - t_start
    compute = run.seconds
    execution = dict(run.executor)
    execution.update({
        "chunk_rows": chunk_rows, "chunks": len(bounds), "chunks_computed": len(run.computed),
        "chunks_resumed": len(run.resumed), "chunks_discarded": store.discarded if store is not None else 0,
        "analyses": ny * nx,
        "analyses_computed": int(sum((bounds[i][1] - bounds[i][0]) * nx for i in run.computed)),
        "warm_up_s": warm + run.warm_up_seconds, "compute_s": compute, "wall_s": wall,
    })
    n_comp = execution["analyses_computed"]
    execution["per_analysis_ms"] = 1e3 * compute / n_comp if n_comp else None
    return RockingSpectrum(request, system, structure, scales, request.x.values, request.y.values, periods,
                           amplitudes, out, execution, axes_scales if axes_scales is not None else scales)
