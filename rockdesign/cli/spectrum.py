"""``rockdesign spectrum P.toml --pulse K ...``: rocking spectra (CONTRACT §2, §4; docs/spectra.md).

Mounted by :mod:`rockdesign.cli` through :func:`register`.  The command only parses options and
calls :mod:`rockdesign.planar.spectra`.
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import List, Optional

import typer
from rich.console import Console
from rich.markup import escape

from ..console import make_console

HELP_PULSE = "ricker-anti | ricker-sym | sine | cycloidal-a | cycloidal-b | cycloidal-c"


def _progress(console: Console, enabled: bool):
    """A rich progress bar over analyses (a no-op when disabled)."""
    from rich.progress import (BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn,
                               TimeRemainingColumn)
    return Progress(TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(),
                    TextColumn("analyses"), TimeElapsedColumn(), TimeRemainingColumn(), console=console,
                    disable=not enabled, transient=False)


def _project_json(project) -> dict:
    return {"name": project.name, "file": str(project.path), "sha256": project.sha256,
            "warnings": list(project.warnings)}


def register(app: typer.Typer, handle_errors) -> None:
    """Add the ``spectrum`` command to the main typer app."""

    @app.command()
    @handle_errors
    def spectrum(
        ctx: typer.Context,
        project: Path = typer.Argument(..., help="Project file (TOML)"),
        pulse: Optional[str] = typer.Option(None, "--pulse", "-p", help=HELP_PULSE),
        record: Optional[str] = typer.Option(None, "--record", help="Cylinders: the record pair, e.g. p695-ff/11 "
                                             "(axes R:lo:hi:n and pga/up:lo:hi:n; thesis Figs 5.16-5.17)."),
        x: str = typer.Option("omega_p/p:0.5:12:801", "--x", show_default=False,
                              help="x axis AXIS:lo:hi:n, AXIS = omega_p/p | omega_p/p_hat | Tp (seconds) "
                                   "[default: omega_p/p from 0.5 to 12, 801 points]."),
        y: str = typer.Option("ap/up:0:12:401", "--y", show_default=False,
                              help="y axis AXIS:lo:hi:n, AXIS = ap/up (a_p over g tan α) | ap/g "
                                   "[default: ap/up from 0 to 12, 401 points]."),
        relative: Optional[Path] = typer.Option(None, "--relative", help="Reference project: relative spectrum "
                                                "Δθ_max (Eq 3.64) and equivalent size (Eq 3.65) on the same pulses."),
        dask: Optional[str] = typer.Option(None, "--dask", help="Run on dask.distributed: local:N (LocalCluster "
                                           "of N workers) or a scheduler address tcp://host:8786."),
        out: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder (default: named "
                                           "after the project and the pulse, e.g. pier-spectrum-sine)."),
        model: str = typer.Option("auto", "--model", help="Equations: exact | linear | auto (the "
                                  "project's [analysis] equations)."),
        structure: Optional[str] = typer.Option(None, "--structure", help="auto | block | frame | "
                                                "rigid-superstructure | podium-2dof (default: the project's "
                                                "[analysis] model)."),
        overturn: Optional[str] = typer.Option(None, "--overturn", help="static (θ_max ≥ θc) | dynamic (|θ| = "
                                               "π/2) (default: the project's [analysis] overturn)."),
        t_free: Optional[float] = typer.Option(None, "--t-free", help="Free vibration [s] after the pulse "
                                               "(default: the project's [analysis] free_vibration, 10 s)."),
        rtol: Optional[float] = typer.Option(None, "--rtol", help="Relative tolerance (default: project)."),
        tm_ratio: float = typer.Option(1.5, "--tm-ratio", help="Ricker centre t_m/T_p (1.5: thesis Table 3.4)."),
        chunk_rows: Optional[int] = typer.Option(None, "--chunk-rows", help="Grid rows per chunk (default: "
                                                 "about 48 chunks, or the interrupted run's)."),
        resume: bool = typer.Option(True, "--resume/--no-resume", metavar=" ", help="Reuse the chunks of an interrupted run "
                                    "with identical inputs."),
        keep_chunks: bool = typer.Option(False, "--keep-chunks", metavar=" ", help="Keep the chunk files after success."),
        energy_stop: bool = typer.Option(True, "--energy-stop/--no-energy-stop", metavar=" ", help="Stop each analysis once "
                                         "the energy bound proves θ_max final (docs: early_termination.md)."),
        stop_at_capacity: bool = typer.Option(False, "--stop-at-capacity", metavar=" ", help="Static criterion: stop each "
                                              "analysis when θ reaches θc (verdict final; θ_max shown as θc)."),
        polyakov: bool = typer.Option(True, "--polyakov/--no-polyakov", metavar=" ", help="Overlay Polyakov's overturning "
                                      "line (SD_max of the pulse = u_B(θc))."),
        equivalent_at: Optional[List[float]] = typer.Option(None, "--equivalent-at", metavar="Y", help="Ordinate(s) y for "
                                                            "the equivalent size of Eq 3.65 (repeatable)."),
        figures: bool = typer.Option(True, "--figures/--no-figures", metavar=" ", help="Write PNG and SVG figures."),
        as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print summary.json to stdout."),
        quiet: bool = typer.Option(False, "--quiet", "-q", metavar=" ", help="No progress bar."),
    ):
        """Rocking spectra: θ_max/α, overturning by impacts, limit states, Polyakov's line (docs/spectra.md)."""
        from ..errors import RockdesignError
        from ..library import load_project, spectrum_excitation
        from .. import parse_axis
        from .. import make_executor
        from .. import spectrum_warm_up as warm_up
        from .. import analyse_spectrum as analyse, write_spectrum_outputs as write_outputs
        from .. import SpectrumError, check_grid, check_ordinates, compute_spectrum, request_from_project

        t_start = time.perf_counter()
        console = make_console(stderr=True, highlight=False)
        proj = load_project(project)
        from .inputs import refuse_given
        if spectrum_excitation(proj) == "record pair":       # the 3D cylinder (thesis Ch. 5, Figs 5.16-5.17)
            from .cylinder_spectrum import PLANAR_ONLY, cylinder_spectrum_command
            refuse_given(ctx, PLANAR_ONLY, "the spectrum of a cylinder (a record pair on R × pga axes)",
                         "--record, --x R:…, --y pga/up:…, --relative, -o, --figures, --json")
            return cylinder_spectrum_command(proj, project, record, x, y, relative, out, as_json, figures, console)
        refuse_given(ctx, {"record": "--record"}, "the spectrum of a planar system (pulses)",
                     "--pulse (a cylinder project takes --record)")
        if pulse is None:
            raise RockdesignError("missing pulse", key="--pulse", expected="--pulse ricker-anti (or another pulse)",
                                  found="none")
        x_axis = parse_axis(x, "x")
        y_axis = parse_axis(y, "y")
        if model not in ("auto", "exact", "linear"):
            raise SpectrumError("unknown model", key="--model", expected="exact | linear | auto", found=repr(model))
        if rtol is not None and not 0.0 < rtol < 1e-2:
            raise SpectrumError("invalid tolerance", key="--rtol", expected="0 < rtol < 1e-2", found=repr(rtol))
        if chunk_rows is not None and chunk_rows < 1:
            raise SpectrumError("invalid chunk size", key="--chunk-rows", expected="an integer ≥ 1",
                                found=str(chunk_rows))
        pulse_name = pulse.strip().lower()
        request = request_from_project(proj, pulse_name, x=x_axis, y=y_axis, equations=model, structure=structure,
                                       overturn=overturn, rtol=rtol, t_free=t_free, tm_ratio=tm_ratio,
                                       energy_stop=energy_stop, stop_at_capacity=stop_at_capacity)
        ref_proj = load_project(relative) if relative is not None else None
        from .. import resolve_structure
        resolve_structure(proj.system, request.structure, request.rigid_ratio)  # fail before any work
        if ref_proj is not None:
            ref_request = request_from_project(ref_proj, pulse_name, x=x_axis, y=y_axis, equations=model,
                                               structure=None if structure is None else "auto",
                                               overturn=request.overturn, rtol=request.rtol, t_free=request.t_free,
                                               tm_ratio=tm_ratio, energy_stop=energy_stop,
                                               stop_at_capacity=stop_at_capacity)
            resolve_structure(ref_proj.system, ref_request.structure, ref_request.rigid_ratio)
        out_dir = out if out is not None else Path(f"{Path(project).stem}-spectrum-{pulse_name}")
        check_ordinates(equivalent_at, y_axis, ref_proj is not None)
        check_grid(x_axis, y_axis, 2 if ref_proj is not None else 1,    # memory and time, before any work
                   distributed=dask is not None and not str(dask).startswith("local"))
        executor = make_executor(dask, warm_up=warm_up)     # (an unreachable scheduler stops here)
        from .. import created_folder
        created_folder(out_dir, "-o/--out")                 # (removed again if the run fails before writing)
        chunks_root = out_dir / "chunks"
        if dask is None or str(dask).startswith("local"):   # (a remote cluster's workers compile there)
            from .inputs import compile_kernels
            compile_kernels("spectrum")
        ny, nx = y_axis.n, x_axis.n
        runs = [("spectrum", proj, request, chunks_root / "project")]
        if ref_proj is not None:
            runs.append(("reference", ref_proj, ref_request, chunks_root / "reference"))
        from .. import spectrum_scales
        # the reference is analysed at the project's pulses (T_p, a_p): the axes keep their meaning
        project_scales = spectrum_scales(proj.system)
        total = ny * nx * len(runs)
        results = []
        try:
            with _progress(console, not quiet) as bar:
                task = bar.add_task("spectrum", total=total)
                for label, prj, req, store in runs:
                    bar.update(task, description=escape(f"{label}: {prj.name[:40]}"))
                    results.append(compute_spectrum(prj.system, req, executor=executor, store_dir=store,
                                                    resume=resume, keep_chunks=True, chunk_rows=chunk_rows,
                                                    progress=lambda n: bar.advance(task, n),
                                                    axes_scales=project_scales))
        except KeyboardInterrupt:
            done = sum(len(list(p.glob("chunk-*.npz"))) for p in chunks_root.glob("*") if p.is_dir())
            console.print(f"[yellow]interrupted[/]: {done} completed chunks kept in {escape(str(chunks_root))}; "
                          "rerun the same command to resume.")
            raise typer.Exit(130)
        finally:
            executor.close()
        spec = results[0]
        ref = results[1] if len(results) > 1 else None
        a = proj.analysis
        prod = analyse(spec, ref, polyakov=polyakov, damping=a.sdmax_damping, band=a.sdmax_band,
                       ordinates=equivalent_at or None)
        compute_s = sum(r.execution["compute_s"] for r in results)
        n_comp = sum(r.execution["analyses_computed"] for r in results)
        timings = {"wall_s": None, "compute_s": compute_s,
                   "warm_up_s": sum(r.execution["warm_up_s"] for r in results),
                   "per_analysis_ms": 1e3 * compute_s / n_comp if n_comp else None,
                   "analyses_computed": n_comp, "postprocess_s": prod.seconds}
        timings["wall_s"] = time.perf_counter() - t_start
        summary = write_outputs(prod, out_dir, project=_project_json(proj),
                                reference_project=_project_json(ref_proj) if ref_proj else None, figures=figures,
                                title=proj.name, reference_title=ref_proj.name if ref_proj else None, timings=timings)
        if not keep_chunks:
            from .. import remove_tree
            remove_tree(chunks_root)
        if as_json:
            sys.stdout.write(json.dumps(summary, indent=1, ensure_ascii=False) + "\n")
            return
        _print_summary(make_console(highlight=False), summary, out_dir)


def _print_summary(console: Console, summary: dict, out_dir: Path) -> None:
    from rich.table import Table
    r = summary["results"]
    sysj = summary["system"]
    t = Table(title=escape(f"rocking spectrum — {summary['project']['name']}"), show_header=False,
              title_justify="left")
    t.add_column("quantity")
    t.add_column("value")
    ax = summary["axes"]
    t.add_row("pulse", f"{summary['pulse']['kind']}")
    t.add_row("model", f"{sysj['model']}, overturning {summary['analysis']['overturn']}")
    t.add_row("grid", f"{ax['x']['name']} {ax['x']['lo']:g}…{ax['x']['hi']:g} ({ax['x']['n']}) × "
                      f"{ax['y']['name']} {ax['y']['lo']:g}…{ax['y']['hi']:g} ({ax['y']['n']})")
    t.add_row("analyses", f"{r['n_analyses']:,}")
    ob = r["overturned_by_impacts"]
    t.add_row("overturned", f"{r['n_overturned']:,} (0 impacts {ob['0']:,}, 1 impact {ob['1']:,}, 2+ {ob['2+']:,})")
    lo = r.get("lowest_overturning")
    if lo:
        t.add_row("lowest overturning", f"y = {lo['y']:.4g} at x = {lo['x']:.4g} (T_p = {lo['Tp']:.4g} s)")
    eq = summary.get("equivalent_size")
    if eq and eq.get("median_R_hat_over_R") is not None:
        t.add_row("equivalent size (Eq 3.65)", f"R̂/R_ref = {eq['median_R_hat_over_R']:.4g} (median over y = "
                  f"{', '.join(f'{v:g}' for v in eq['ordinates'])})")
    tm = summary["timings"]
    per = tm.get("per_analysis_ms")
    t.add_row("time", f"{tm['wall_s']:.1f} s wall, {tm['compute_s']:.1f} s computing"
              + (f", {per:.3f} ms per analysis" if per else " (all chunks resumed)"))
    ex = summary["execution"]
    t.add_row("executor", ex.get("executor", "local") + (f" {ex.get('address')}" if ex.get("address") else "")
              + f", {ex['chunks']} chunks ({ex['chunks_resumed']} resumed)")
    t.add_row("output", escape(str(out_dir)))
    console.print(t)
