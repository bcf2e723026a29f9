"""``rockdesign spectrum P.toml --pulse K ...``: rocking spectra (CONTRACT §2, §4; docs/spectra.md).

Mounted by :mod:`rockdesign.cli` through :func:`register`.  The command parses its options, calls
``rd.spectrum`` (the project's kind runs the spectrum and writes the folder), draws the progress through a
callback and prints the summary.  An option left out is passed as None: the kind's default applies, and an
option the kind does not use is refused by it.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import List, Optional

import typer
from rich.console import Console
from rich.markup import escape

from ..console import make_console

HELP_PULSE = "Planar structures: ricker-anti | ricker-sym | sine | cycloidal-a | cycloidal-b | cycloidal-c"
ON = " "
"""metavar of on/off options (typer would print "<bool>" after them in --help)."""


def register(app: typer.Typer, handle_errors) -> None:
    """Add the ``spectrum`` command to the main typer app."""

    @app.command()
    @handle_errors(executor="--dask", out_dir="-o/--out", pulse="--pulse")
    def spectrum(
        project: Path = typer.Argument(..., help="Project file (TOML)"),
        pulse: Optional[str] = typer.Option(None, "--pulse", "-p", help=HELP_PULSE),
        record: Optional[str] = typer.Option(None, "--record", help="Cylinders: the record pair, e.g. p695-ff/11 "
                                             "(axes R:lo:hi:n and pga/up:lo:hi:n; thesis Figs 5.16-5.17)."),
        x: Optional[str] = typer.Option(None, "--x", help="x axis AXIS:lo:hi:n, AXIS = omega_p/p | omega_p/p_hat | "
                                        "Tp (seconds) (default: omega_p/p from 0.5 to 12, 801 points); cylinders: "
                                        "R in m (default: R:0.5:30:60)."),
        y: Optional[str] = typer.Option(None, "--y", help="y axis AXIS:lo:hi:n, AXIS = ap/up (a_p over g tan α) | "
                                        "ap/g (default: ap/up from 0 to 12, 401 points); cylinders: pga/up "
                                        "(default: pga/up:1:6:51)."),
        relative: Optional[Path] = typer.Option(None, "--relative", help="Reference project: relative spectrum "
                                                "Δθ_max (Eq 3.64) and equivalent size (Eq 3.65) on the same pulses."),
        dask: Optional[str] = typer.Option(None, "--dask", help="Run on dask.distributed: local:N (LocalCluster "
                                           "of N workers) or a scheduler address tcp://host:8786."),
        out: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder (default: named "
                                           "after the project and the pulse, e.g. pier-spectrum-sine)."),
        model: Optional[str] = typer.Option(None, "--model", help="Equations: exact | linear | auto (default: "
                                            "auto, the equations of the project's analysis table)."),
        structure: Optional[str] = typer.Option(None, "--structure", help="auto | block | frame | "
                                                "rigid-superstructure | podium-2dof (default: the model of the "
                                                "project's analysis table)."),
        overturn: Optional[str] = typer.Option(None, "--overturn", help="static (θ_max ≥ θc) | dynamic (|θ| = "
                                               "π/2) (default: the project's analysis overturn)."),
        t_free: Optional[float] = typer.Option(None, "--t-free", help="Free vibration in s after the pulse "
                                               "(default: the project's analysis free_vibration, 10 s)."),
        rtol: Optional[float] = typer.Option(None, "--rtol", help="Relative tolerance (default: project)."),
        tm_ratio: Optional[float] = typer.Option(None, "--tm-ratio", help="Ricker centre t_m/T_p (default: 1.5, "
                                                 "thesis Table 3.4)."),
        chunk_rows: Optional[int] = typer.Option(None, "--chunk-rows", help="Grid rows per chunk (default: "
                                                 "about 48 chunks, or the interrupted run's)."),
        resume: Optional[bool] = typer.Option(None, "--resume/--no-resume", metavar=ON, help="Reuse the chunks of "
                                              "an interrupted run with identical inputs (default: resume)."),
        keep_chunks: Optional[bool] = typer.Option(None, "--keep-chunks", metavar=ON,
                                                   help="Keep the chunk files after success."),
        energy_stop: Optional[bool] = typer.Option(None, "--energy-stop/--no-energy-stop", metavar=ON,
                                                   help="Stop each analysis once the energy bound proves θ_max "
                                                        "final (docs: early_termination.md; default: on)."),
        stop_at_capacity: Optional[bool] = typer.Option(None, "--stop-at-capacity", metavar=ON, help="Static "
                                                        "criterion: stop each analysis when θ reaches θc (verdict "
                                                        "final; θ_max shown as θc)."),
        polyakov: Optional[bool] = typer.Option(None, "--polyakov/--no-polyakov", metavar=ON, help="Overlay "
                                                "Polyakov's overturning line (SD_max of the pulse = u_B(θc); "
                                                "default: on)."),
        equivalent_at: Optional[List[float]] = typer.Option(None, "--equivalent-at", metavar="Y", help="Ordinate(s) y "
                                                            "for the equivalent size of Eq 3.65 (repeatable)."),
        figures: bool = typer.Option(True, "--figures/--no-figures", metavar=ON, help="Write the figures."),
        as_json: bool = typer.Option(False, "--json", metavar=ON, help="Print summary.json to stdout."),
        quiet: bool = typer.Option(False, "--quiet", "-q", metavar=ON, help="No progress bar."),
    ):
        """Rocking spectra: θ_max/α, overturning by impacts, limit states, Polyakov's line (docs/spectra.md)."""
        import rockdesign as rd
        console = make_console(stderr=True, highlight=False)
        proj = rd.load_project(project)
        with rd.progress_bars(console, disable=quiet or (as_json and not console.is_terminal)) as progress:
            try:
                result = rd.spectrum(proj, pulse=pulse, record=record, x=x, y=y, relative=relative, out_dir=out,
                                     executor=dask, model=model, structure=structure, overturn=overturn,
                                     t_free=t_free, rtol=rtol, tm_ratio=tm_ratio, chunk_rows=chunk_rows,
                                     resume=resume, keep_chunks=keep_chunks, energy_stop=energy_stop,
                                     stop_at_capacity=stop_at_capacity, polyakov=polyakov,
                                     equivalent_at=equivalent_at or None, figures=figures, progress=progress,
                                     say=console.print)
            except KeyboardInterrupt as exc:
                if not exc.args:
                    raise
                console.print(f"[yellow]interrupted[/]: {escape(str(exc.args[0]))}")   # (the chunks kept)
                raise typer.Exit(130) from None
        if as_json:
            sys.stdout.write(json.dumps(result.as_json(), indent=1, ensure_ascii=False) + "\n")
            return
        _print_summary(make_console(highlight=False), result)


def _print_summary(console: Console, result) -> None:
    from rich.table import Table
    t = Table(title=escape(result.title), show_header=False, title_justify="left")
    t.add_column("quantity")
    t.add_column("value")
    for quantity, value in result.summary_rows():
        t.add_row(escape(quantity), escape(value))
    console.print(t)
