"""The rocking spectrum of a planar project over a pulse family, written to a folder: the work of
``rockdesign spectrum P.toml --pulse K`` (thesis Sec 3.3.2, 4.2.4; docs/spectra.md), reached through
``rd.spectrum`` and the planar kind.

:func:`pulse_spectrum` validates every option before any work (axes, model, tolerances, grid size, the
reference project, the output folder), compiles the pulse kernel on a first run, runs the spectrum (and the
reference's, at the project's pulses: Eq 3.64) chunk by chunk on an executor with a resumable chunk store,
reads the products off it (:func:`rockdesign.planar.spectra.output.analyse`) and writes ``spectrum.npz``,
``summary.json`` and the figures (:func:`rockdesign.planar.spectra.output.write_outputs`).
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from ...execution import compilation
from ...execution.executor import remove_tree, running_on
from ...motions.motion import PULSE_KINDS
from ...outdir import created_folder
from ..dynamics.model import resolve_structure
from . import spectrum as engine
from .axes import DEFAULT_X, DEFAULT_Y, Axis, parse_axis, spectrum_scales
from .kernel import warm_up
from .output import SpectrumProducts, analyse, write_outputs
from .spectrum import RockingSpectrum, SpectrumError, check_grid, check_ordinates, request_from_project

PULSE_SPECTRUM = compilation.Kernels("planar-pulse-spectrum", warm_up, 30.0)
"""The integrator inside the pulse-spectrum kernel, compiled on a first run (:func:`.kernel.warm_up`)."""

MODELS = ("auto", "exact", "linear")


@dataclass
class PulseSpectrum:
    """A planar rocking spectrum and the folder it was written to.

    Attributes:
        out_dir: the output folder (spectrum.npz, summary.json, figures).
        summary: the summary.json object (SI; docs/spectra.md).
        spectrum: the project's :class:`~rockdesign.planar.spectra.spectrum.RockingSpectrum` (θ_max/α,
            overturning, impacts per grid point; T_p [s] per column, a_p [m/s²] per row).
        reference: the reference's spectrum at the same pulses (``relative``), or None.
        products: what was read off them (limit-state lines, Polyakov's line, Δθ_max/α of Eq 3.64, the
            equivalent size of Eq 3.65).
    """

    out_dir: Path
    summary: dict
    spectrum: RockingSpectrum
    reference: RockingSpectrum | None
    products: SpectrumProducts

    def as_json(self) -> dict:
        """summary.json (the ``spectrum --json`` output)."""
        return self.summary

    @property
    def title(self) -> str:
        return f"rocking spectrum — {self.summary['project']['name']}"

    def summary_rows(self) -> list[tuple[str, str]]:
        """(quantity, value) rows of the console summary."""
        summary = self.summary
        r, ax, sysj = summary["results"], summary["axes"], summary["system"]
        ob = r["overturned_by_impacts"]
        rows = [("pulse", f"{summary['pulse']['kind']}"),
                ("model", f"{sysj['model']}, overturning {summary['analysis']['overturn']}"),
                ("grid", f"{ax['x']['name']} {ax['x']['lo']:g}…{ax['x']['hi']:g} ({ax['x']['n']}) × "
                         f"{ax['y']['name']} {ax['y']['lo']:g}…{ax['y']['hi']:g} ({ax['y']['n']})"),
                ("analyses", f"{r['n_analyses']:,}"),
                ("overturned", f"{r['n_overturned']:,} (0 impacts {ob['0']:,}, 1 impact {ob['1']:,}, 2+ {ob['2+']:,})")]
        lo = r.get("lowest_overturning")
        if lo:
            rows.append(("lowest overturning", f"y = {lo['y']:.4g} at x = {lo['x']:.4g} (T_p = {lo['Tp']:.4g} s)"))
        eq = summary.get("equivalent_size")
        if eq and eq.get("median_R_hat_over_R") is not None:
            rows.append(("equivalent size (Eq 3.65)", f"R̂/R_ref = {eq['median_R_hat_over_R']:.4g} (median over y = "
                         f"{', '.join(f'{v:g}' for v in eq['ordinates'])})"))
        tm = summary["timings"]
        per = tm.get("per_analysis_ms")
        rows.append(("time", f"{tm['wall_s']:.1f} s wall, {tm['compute_s']:.1f} s computing"
                     + (f", {per:.3f} ms per analysis" if per else " (all chunks resumed)")))
        ex = summary["execution"]
        rows.append(("executor", ex.get("executor", "local") + (f" {ex.get('address')}" if ex.get("address") else "")
                     + f", {ex['chunks']} chunks ({ex['chunks_resumed']} resumed)"))
        rows.append(("output", str(self.out_dir)))
        return rows


def _project_json(project) -> dict:
    return {"name": project.name, "file": str(project.path), "sha256": project.sha256,
            "warnings": list(project.warnings)}


def _axis(value, which: str, default: Axis) -> Axis:
    if value is None:
        return default
    return value if isinstance(value, Axis) else parse_axis(value, which)


def _where(executor) -> str:
    """"local" or the dask address of an executor (or of a dask value such as "local:2", "tcp://host:8786")."""
    if executor is None:
        return "local"
    if isinstance(executor, str):
        return executor.strip()
    return str(getattr(executor, "address", "local"))


def pulse_spectrum(project, *, pulse: str | None = None, x: str | Axis | None = None, y: str | Axis | None = None,
                   relative=None, out_dir: str | Path | None = None, executor=None, model: str = "auto",
                   structure: str | None = None, overturn: str | None = None, t_free: float | None = None,
                   rtol: float | None = None, tm_ratio: float = 1.5, chunk_rows: int | None = None,
                   resume: bool = True, keep_chunks: bool = False, energy_stop: bool = True,
                   stop_at_capacity: bool = False, polyakov: bool = True, equivalent_at=None, figures: bool = True,
                   progress: Callable[[str, int, int], None] | None = None, say=None) -> PulseSpectrum:
    """θ_max/α and overturning of a planar project over a grid of pulses (thesis Figs 3.19–3.20, 4.6–4.7),
    written into ``out_dir``.  The parameters are those of ``rd.spectrum`` (docs/api.md, docs/spectra.md).

    Args:
        project: a planar :class:`~rockdesign.project_tables.Project`.
        pulse: ``ricker-anti`` | ``ricker-sym`` | ``sine`` | ``cycloidal-a`` | ``cycloidal-b`` | ``cycloidal-c``.
        x: ``AXIS:lo:hi:n`` with AXIS ``omega_p/p`` (ω_p/p, Eq 3.13), ``omega_p/p_hat`` or ``Tp`` [s]; default
            ``omega_p/p:0.5:12:801``.
        y: ``ap/up`` (a_p/(g tan α), Eq 3.34) or ``ap/g``; default ``ap/up:0:12:401``.
        relative: a reference planar project analysed at the same pulses: Δθ_max/α (Eq 3.64) and the equivalent
            size (Eq 3.65).
        out_dir: output folder (default: ``<project file stem>-spectrum-<pulse>``).
        executor: None (this machine's cores), a dask value ``"local:N"`` or a scheduler address (started and
            closed here), or a started executor of :mod:`rockdesign.execution.executor` (not closed).
        model: ``auto`` (the project's equations) | ``exact`` | ``linear``.
        structure, overturn, t_free [s], rtol: default the project's ``[analysis]`` model, overturn,
            free_vibration and rtol.
        tm_ratio: Ricker wavelet centre t_m/T_p (thesis Table 3.4: 1.5).
        chunk_rows: grid rows per chunk (default: about 48 chunks, or the interrupted run's).
        resume, keep_chunks: reuse the chunks of an interrupted run with identical inputs; keep the chunk files.
        energy_stop, stop_at_capacity: stop an analysis once its result is final (docs/early_termination.md).
        polyakov: Polyakov's overturning line (SD_max of the pulse = u_B(θc)).
        equivalent_at: ordinates y of the equivalent size (Eq 3.65; with ``relative`` only).
        figures: write the PNG and SVG figures.
        progress: ``progress(stage, done, total)`` as chunks of analyses finish.
        say: prints the first-run compilation announcement.

    Raises:
        SpectrumError, AxisError, ModelError, ExecutorError, OutputError: named by the parameter, before any
            work.  KeyboardInterrupt: with the count and folder of the chunks kept for a resumed run.
    """
    t_start = time.perf_counter()
    if not isinstance(pulse, str):
        raise SpectrumError("missing pulse" if pulse is None else "the pulse must be a name", key="pulse",
                            expected="ricker-anti (or another pulse: " + " | ".join(PULSE_KINDS) + ")",
                            found="none" if pulse is None else type(pulse).__name__)
    x_axis = _axis(x, "x", DEFAULT_X)
    y_axis = _axis(y, "y", DEFAULT_Y)
    if model not in MODELS:
        raise SpectrumError("unknown model", key="model", expected="exact | linear | auto", found=repr(model))
    if rtol is not None and not 0.0 < rtol < 1e-2:
        raise SpectrumError("invalid tolerance", key="rtol", expected="0 < rtol < 1e-2", found=repr(rtol))
    if chunk_rows is not None and chunk_rows < 1:
        raise SpectrumError("invalid chunk size", key="chunk_rows", expected="an integer ≥ 1", found=str(chunk_rows))
    pulse_name = pulse.strip().lower()
    settings = dict(x=x_axis, y=y_axis, equations=model, tm_ratio=tm_ratio, energy_stop=energy_stop,
                    stop_at_capacity=stop_at_capacity)
    request = request_from_project(project, pulse_name, structure=structure, overturn=overturn, rtol=rtol,
                                   t_free=t_free, **settings)
    resolve_structure(project.system, request.structure, request.rigid_ratio)       # fail before any work
    runs = [("spectrum", project, request, "project")]
    if relative is not None:
        ref_request = request_from_project(relative, pulse_name, structure=None if structure is None else "auto",
                                           overturn=request.overturn, rtol=request.rtol, t_free=request.t_free,
                                           **settings)
        resolve_structure(relative.system, ref_request.structure, ref_request.rigid_ratio)
        runs.append(("reference", relative, ref_request, "reference"))
    out_dir = Path(out_dir) if out_dir is not None else Path(f"{Path(project.path).stem}-spectrum-{pulse_name}")
    check_ordinates(equivalent_at, y_axis, relative is not None)
    distributed = not _where(executor).startswith("local")
    check_grid(x_axis, y_axis, len(runs), distributed=distributed)     # memory and time, before any work
    with running_on(executor, warm_up=warm_up, here=True, start=False) as executor:
        created_folder(out_dir, "out_dir")            # (removed again if the run fails before writing)
        if not distributed:                           # (a remote cluster's workers compile there)
            compilation.prepare("spectrum", (PULSE_SPECTRUM,), say)
        chunks_root = out_dir / "chunks"
        # the reference is analysed at the project's pulses (T_p, a_p): the axes keep their meaning
        project_scales = spectrum_scales(project.system)
        results = []
        try:
            for label, prj, req, store in runs:
                results.append(_run(prj, req, label, executor, chunks_root / store, resume=resume,
                                    chunk_rows=chunk_rows, progress=progress, axes_scales=project_scales))
        except KeyboardInterrupt:
            done = sum(len(list(p.glob("chunk-*.npz"))) for p in chunks_root.glob("*") if p.is_dir())
            raise KeyboardInterrupt(f"{done} completed chunks kept in {chunks_root}; rerun the same command to "
                                    "resume.") from None
    spec = results[0]
    ref = results[1] if len(results) > 1 else None
    a = project.analysis
    prod = analyse(spec, ref, polyakov=polyakov, damping=a.sdmax_damping, band=a.sdmax_band,
                   ordinates=equivalent_at or None)
    compute_s = sum(r.execution["compute_s"] for r in results)
    n_comp = sum(r.execution["analyses_computed"] for r in results)
    timings = {"wall_s": None, "compute_s": compute_s, "warm_up_s": sum(r.execution["warm_up_s"] for r in results),
               "per_analysis_ms": 1e3 * compute_s / n_comp if n_comp else None,
               "analyses_computed": n_comp, "postprocess_s": prod.seconds}
    timings["wall_s"] = time.perf_counter() - t_start
    summary = write_outputs(prod, out_dir, project=_project_json(project),
                            reference_project=_project_json(relative) if relative is not None else None,
                            figures=figures, title=project.name,
                            reference_title=relative.name if relative is not None else None, timings=timings)
    if not keep_chunks:
        remove_tree(chunks_root)
    return PulseSpectrum(out_dir, summary, spec, ref, prod)


def _run(project, request, label: str, executor, store: Path, *, resume: bool, chunk_rows, progress,
         axes_scales) -> RockingSpectrum:
    """One spectrum of the run, its progress reported as the stage ``label: project name``."""
    stage = f"{label}: {project.name[:40]}"
    total = request.x.n * request.y.n
    done = [0]

    def tick(n: int) -> None:
        done[0] += n
        progress(stage, done[0], total)

    if progress is not None:
        progress(stage, 0, total)
    return engine.compute_spectrum(project.system, request, executor=executor, store_dir=store, resume=resume,
                                   keep_chunks=True, chunk_rows=chunk_rows,
                                   progress=tick if progress is not None else None, axes_scales=axes_scales)
