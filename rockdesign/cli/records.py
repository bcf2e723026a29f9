"""``rockdesign records list|show|spectrum|synth``: ground-motion tools (CONTRACT §2, §3).

The main CLI mounts :data:`app`; user errors are raised as RockdesignError subclasses and turned
into exit code 2 there. Record ids: built-in (``p695-ff/11a``), ``rsn:<RSN>:<component>`` (with
``--records-dir``), ``file:<path>`` or a plain path; a leading ``record:`` is accepted.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.table import Table

from ..console import make_console
from .. import DEFAULT_BAND, DEFAULT_DAMPING, DEFAULT_N_PERIODS
from .inputs import OptionsOnce

# the library (numba, pint) is imported by the commands that use them: the CLI mounts this module for every
# command, `--help` and `init` included

app = typer.Typer(cls=OptionsOnce, help="Ground-motion records: list, show, spectra, synthetic ensembles, scale-model records.", no_args_is_help=True)

RECORDS_DIR_HELP = "Folder of your PEER *.AT2 files (for rsn:<RSN>:<component> ids)."
FLAG = " "  # metavar of on/off options (typer prints "<bool>" otherwise)
GRAVITY_HELP = "Gravitational acceleration g [m/s²] for records in g."


def _console() -> Console:
    console = make_console(highlight=False, markup=False, soft_wrap=True)
    if not console.is_terminal:
        console.width = 160  # pipes and files: do not wrap tables at 80 columns
    return console


def _warn(result) -> None:
    for text in result.warnings:
        make_console(stderr=True, highlight=False, markup=False, soft_wrap=True).print(f"warning: {text}")


def _say(text: str) -> None:
    make_console(stderr=True).print(text)


def _fmt(value, digits: int = 4) -> str:
    if value is None:
        return "–"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


@app.command("list")
def list_command(
    suite: Optional[str] = typer.Option(None, "--suite",
                                        help="Suite name or manifest path (default: all built-in records)."),
    as_json: bool = typer.Option(False, "--json", metavar=FLAG, help="JSON on stdout (SI units)."),
    records_dir: Optional[Path] = typer.Option(None, "--records-dir", help=RECORDS_DIR_HELP),
    gravity: float = typer.Option(9.81, "--gravity", help=GRAVITY_HELP),
) -> None:
    """List built-in records, or the records of a suite (table: dt in s, PGA in g; --json: SI, PGA in m/s²)."""
    from .. import records_list
    listing = records_list(suite, gravity=gravity, records_dir=records_dir)
    rows = listing.rows
    if as_json:
        typer.echo(json.dumps(listing.as_json()))
        return
    table = Table(title=f"records of {suite}" if suite else "built-in records (FEMA P695)")
    labels = any(row.get("label") for row in rows)
    for column in (["label"] if labels else []) + ["id", "event", "year", "station", "RSN", "comp.", "dt [s]",
                                                    "npts", "PGA [g]"]:
        table.add_column(column)
    for row in rows:
        pga = "missing" if row["pga"] is None else f"{row['pga'] / gravity:.3f}"
        cells = [row["id"], _fmt(row["event"]), _fmt(row["year"]), _fmt(row["station"]), _fmt(row["rsn"]),
                 _fmt(row["component"]), _fmt(row["dt"]), _fmt(row["npts"]), pga]
        table.add_row(*(([row.get("label", "")] if labels else []) + cells))
    console = _console()
    console.print(table)
    for row in listing.missing:
        console.print(f"missing {row['id']}: {row['missing']}")


@app.command("show")
def show_command(
    record_id: str = typer.Argument(..., metavar="ID", help="Record id, file:path or a path."),
    plot: Optional[Path] = typer.Option(None, "--plot",
                                        help="Write acceleration/velocity/displacement plot (PNG, SVG, PDF)."),
    records_dir: Optional[Path] = typer.Option(None, "--records-dir", help=RECORDS_DIR_HELP),
    gravity: float = typer.Option(9.81, "--gravity", help=GRAVITY_HELP),
) -> None:
    """Metadata and intensity measures of one record."""
    from .inputs import FIGURE_SUFFIXES, output_file
    output_file(plot, "--plot", FIGURE_SUFFIXES)
    from .. import records_show
    shown = records_show(record_id, gravity=gravity, records_dir=records_dir, say=_say)
    _warn(shown)
    motion, measures, sd, period = shown.motion, shown.measures, shown.sd_max, shown.sd_max_period
    meta = motion.meta
    table = Table(title=shown.id, show_header=False)
    table.add_column("quantity")
    table.add_column("value")
    for label, key in (("event", "event"), ("year", "year"), ("station", "station"), ("RSN", "rsn"),
                       ("component", "component"), ("units in file", "units"), ("source", "source")):
        if meta.get(key) is not None:
            table.add_row(label, str(meta[key]))
    if meta.get("source_file"):
        table.add_row("file", meta["source_file"])
    table.add_row("dt / npts / duration", f"{motion.dt:g} s / {motion.samples.size} / {motion.duration:.2f} s")
    table.add_row("PGA", f"{measures['pga']:.4g} m/s² ({measures['pga'] / gravity:.4g} g)")
    table.add_row("PGV / PGD (no baseline correction)", f"{measures['pgv']:.4g} m/s / {measures['pgd']:.4g} m")
    table.add_row("Arias intensity (Eq 5.46)", f"{measures['arias']:.4g} m/s")
    table.add_row("CAV (Eq 5.44)", f"{measures['cav']:.4g} m/s")
    table.add_row("bracketed duration (0.05 g)", f"{measures['bracketed_duration']:.3f} s")
    table.add_row("significant duration D5–95", f"{measures['significant_duration']:.3f} s")
    table.add_row("a_rms over T_d (Eq 5.45)", f"{measures['a_rms']:.4g} m/s²")
    f_p = measures["predominant_frequency"]
    table.add_row("predominant frequency (Konno–Ohmachi b=40)", "n/a (no motion)" if f_p is None else f"{f_p:.3f} Hz")
    table.add_row("SD_max (2 % damping, 0.05–10 s)", f"{sd:.4g} m at T = {period:.3f} s")
    _console().print(table)
    if plot is not None:
        shown.write_figure(plot)
        _console().print(f"plot written to {plot}")


@app.command("spectrum")
def spectrum_command(
    record_id: str = typer.Argument(..., metavar="ID", help="Record id, file:path or a path."),
    damping: str = typer.Option(str(DEFAULT_DAMPING), "--damping", help="Damping ratio (0.02 or '2 %')."),
    band: str = typer.Option(f"{DEFAULT_BAND[0]:g}:{DEFAULT_BAND[1]:g}", "--band", help="Period band Tmin:Tmax [s]."),
    n_periods: int = typer.Option(DEFAULT_N_PERIODS, "--n-periods", min=2, help="Log-spaced periods in the band."),
    as_json: bool = typer.Option(False, "--json", metavar=FLAG, help="JSON on stdout (SI units)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write SD/PSA plot (PNG, SVG, PDF)."),
    records_dir: Optional[Path] = typer.Option(None, "--records-dir", help=RECORDS_DIR_HELP),
    gravity: float = typer.Option(9.81, "--gravity", help=GRAVITY_HELP),
) -> None:
    """Elastic response spectrum (exact, free vibration after the record included), SD_max and
    intensity measures."""
    from .inputs import FIGURE_SUFFIXES, output_file
    output_file(plot, "--plot", FIGURE_SUFFIXES)
    from .. import records_spectrum
    spectrum = records_spectrum(record_id, damping=damping, band=band, n_periods=n_periods, gravity=gravity,
                                records_dir=records_dir, say=_say)
    _warn(spectrum)
    result = spectrum.as_json()
    if plot is not None:
        spectrum.write_figure(plot)
    if as_json:
        typer.echo(json.dumps(result))
        return
    zeta, (lo, hi), measures = spectrum.damping, spectrum.band, spectrum.measures
    peak, period = spectrum.sd_max, spectrum.sd_max_period
    table = Table(title=f"{result['id']}: {100 * zeta:g} % damping, {lo:g}–{hi:g} s", show_header=False)
    table.add_column("quantity")
    table.add_column("value")
    table.add_row("SD_max", f"{peak:.4g} m at T = {period:.3f} s")
    table.add_row("PGA", f"{measures['pga']:.4g} m/s² ({measures['pga'] / gravity:.4g} g)")
    for key, unit in (("pgv", "m/s"), ("pgd", "m"), ("arias", "m/s"), ("cav", "m/s"), ("bracketed_duration", "s"),
                      ("significant_duration", "s"), ("a_rms", "m/s²"), ("predominant_frequency", "Hz")):
        table.add_row(key, "n/a" if measures[key] is None else f"{measures[key]:.4g} {unit}")
    console = _console()
    console.print(table)
    if plot is not None:
        console.print(f"plot written to {plot}")


@app.command("synth")
def synth_command(
    seed: str = typer.Option(..., "--seed", help="Seed record id, file:path or a path."),
    n: int = typer.Option(..., "-n", "--n", min=1, help="Number of synthetic records."),
    out_dir: Path = typer.Option(..., "-o", "--out", help="Output folder (ensemble.toml + ensemble.npz)."),
    seed_value: int = typer.Option(1, "--seed-value", help="Random seed (reproducible ensembles)."),
    scale_to: str = typer.Option("sdmax", "--scale-to", help="sdmax | spectrum | none (one common factor)."),
    records_dir: Optional[Path] = typer.Option(None, "--records-dir", help=RECORDS_DIR_HELP),
    gravity: float = typer.Option(9.81, "--gravity", help=GRAVITY_HELP),
) -> None:
    """Synthetic ensemble (sgsim stochastic model fitted to the seed), saved as a suite."""
    from .inputs import output_folder
    output_folder(out_dir, "--out")
    from .. import progress_bars, records_synth
    with progress_bars() as progress:
        ensemble = records_synth(seed, n, out_dir, seed_value=seed_value, scale_to=scale_to, gravity=gravity,
                                 records_dir=records_dir, progress=progress, say=_say)
    _warn(ensemble)
    path = ensemble.suite
    console = _console()
    console.print(f"wrote {n} records to {path} (+ {path.with_suffix('.npz').name}, model.json, match.json)")
    console.print(ensemble.describe())
    console.print(f"use it with [excitation] suites = [\"{path}\"]")


@app.command("scale-model")
def scale_model_command(
    record_id: str = typer.Argument(..., metavar="ID", help="Record id, file:path or a path."),
    length_ratio: float = typer.Option(..., "--length-ratio", help="R_m/R_p, e.g. 0.025 (Eq 6.5)."),
    table: Optional[str] = typer.Option(None, "--table", help="Table limits, e.g. 'd=0.125m,v=0.22m/s,a=1.5g'."),
    out: Optional[Path] = typer.Option(None, "-o", "--out", help="Write the scaled record (AT2, units of g)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Plot a, v, d (PNG, SVG, PDF)."),
    band: Optional[str] = typer.Option(None, "--band", help="Band-pass corners low:high [Hz, model time]."),
    as_json: bool = typer.Option(False, "--json", metavar=" ", help="JSON on stdout (SI)."),
    records_dir: Optional[Path] = typer.Option(None, "--records-dir", help=RECORDS_DIR_HELP),
    gravity: float = typer.Option(9.81, "--gravity", help=GRAVITY_HELP),
) -> None:
    """Time-scale a record for a small-scale model (Eq 6.5), correct it and check the shake table's limits
    (exit 1 when a limit is exceeded)."""
    from .inputs import FIGURE_SUFFIXES, output_file
    output_file(out, "-o/--out")
    output_file(plot, "--plot", FIGURE_SUFFIXES)
    from .. import records_scale_model
    model = records_scale_model(record_id, length_ratio, table=table, band=band, gravity=gravity,
                                records_dir=records_dir)
    _warn(model)
    if out is not None:
        model.write_at2(out)
    if plot is not None:
        model.write_figure(plot)
    if as_json:
        sys.stdout.write(json.dumps(model.as_json()) + "\n")
    else:
        _scale_model_tables(model, out, plot)
    raise typer.Exit(1 if model.exceeded else 0)


def _scale_model_tables(model, out: Optional[Path], plot: Optional[Path]) -> None:
    scaled, gravity, limits = model.scaled, model.gravity, model.limits
    console = _console()
    console.print(f"{model.id}: time scale √(R_m/R_p) = {scaled.time_factor:.5g} (Eq 6.5): dt {model.motion.dt:g} s "
                  f"→ {scaled.dt:.6g} s, duration {scaled.duration:.4g} s; accelerations unchanged")
    console.print(f"baseline correction and zero-phase Butterworth band-pass (order 4, sosfiltfilt): "
                  f"{scaled.corners[0]:.4g}–{scaled.corners[1]:.4g} Hz")
    t = Table(title="peaks after correction vs table limits")
    for col in ("quantity", "peak", "limit", "utilisation", ""):
        t.add_column(col)
    peaks = scaled.peaks
    for key, label, unit, factor in (("a", "acceleration", "g", 1.0 / gravity), ("v", "velocity", "m/s", 1.0),
                                     ("d", "displacement", "m", 1.0)):
        limit = limits.get(key)
        t.add_row(label, f"{peaks[key] * factor:.4g} {unit}", "–" if limit is None else f"{limit * factor:.4g} {unit}",
                  "–" if limit is None else f"{peaks[key] / limit:.3g}",
                  "" if limit is None else ("EXCEEDED" if key in scaled.exceeded else "ok"))
    console.print(t)
    if out is not None:
        console.print(f"wrote {out} (AT2, units of g)")
    if plot is not None:
        console.print(f"plot written to {plot}")
