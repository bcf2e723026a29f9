"""``rockdesign records list|show|spectrum|synth``: ground-motion tools (CONTRACT §2, §3).

The main CLI mounts :data:`app`; user errors are raised as RockdesignError subclasses and turned
into exit code 2 there. Record ids: built-in (``p695-ff/11a``), ``rsn:<RSN>:<component>`` (with
``--records-dir``), ``file:<path>`` or a plain path; a leading ``record:`` is accepted.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.table import Table

from ..console import make_console
from ..errors import MotionError
from .. import DEFAULT_BAND, DEFAULT_DAMPING, DEFAULT_N_PERIODS
from .inputs import OptionsOnce

# the records, spectra and units modules (numba, pint) are imported by the commands that use them: the
# CLI mounts this module for every command, `--help` and `init` included

app = typer.Typer(cls=OptionsOnce, help="Ground-motion records: list, show, spectra, synthetic ensembles, scale-model records.", no_args_is_help=True)

RECORDS_DIR_HELP = "Folder of your PEER *.AT2 files (for rsn:<RSN>:<component> ids)."
FLAG = " "  # metavar of on/off options (typer prints "<bool>" otherwise)
GRAVITY_HELP = "Gravitational acceleration g [m/s²] for records in g."


def _console() -> Console:
    console = make_console(highlight=False, markup=False, soft_wrap=True)
    if not console.is_terminal:
        console.width = 160  # pipes and files: do not wrap tables at 80 columns
    return console


def _record_id(text: str) -> str:
    text = text.strip()
    return text[7:] if text.lower().startswith("record:") else text


def _load(record_id: str, gravity: float, records_dir: Optional[Path]):
    from .inputs import gravity as check_gravity
    from .. import plausibility_warnings
    check_gravity(gravity)
    from .. import load_record
    motion = load_record(_record_id(record_id), gravity=gravity, records_dir=records_dir)
    for text in plausibility_warnings(motion, gravity):
        make_console(stderr=True, highlight=False, markup=False, soft_wrap=True).print(f"warning: {text}")
    return motion


def _parse_band(text: str) -> tuple[float, float]:
    parts = text.split(":")
    try:
        lo, hi = (float(p) for p in parts)
    except ValueError:
        raise MotionError("invalid period band", key="--band", expected="Tmin:Tmax in seconds, e.g. 0.05:10",
                          found=repr(text)) from None
    if not (0 < lo < hi and math.isfinite(hi)):
        raise MotionError("invalid period band", key="--band", expected="0 < Tmin < Tmax", found=repr(text))
    return lo, hi


def _parse_damping(text: str) -> float:
    from .. import QuantityParseError, parse_quantity
    try:
        value = parse_quantity(float(text) if _is_number(text) else text, "dimensionless")
    except QuantityParseError:
        raise MotionError("invalid damping", key="--damping", expected="a ratio like 0.02 or '2 %'",
                          found=repr(text)) from None
    if not 0.0 <= value < 1.0:
        raise MotionError("invalid damping", key="--damping", expected="a damping ratio in [0, 1)",
                          found=repr(text))
    return value


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


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
    from .inputs import gravity as check_gravity
    check_gravity(gravity)
    from .. import list_records
    rows = list_records(suite, gravity=gravity, records_dir=records_dir)
    if as_json:
        typer.echo(json.dumps(rows))
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
    missing = [r for r in rows if r.get("missing")]
    for row in missing:
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
    from .. import motion_measures, record_history_figure, save_figure, sd_max
    motion = _load(record_id, gravity, records_dir)
    from .inputs import compile_kernels
    compile_kernels("records")
    measures = motion_measures(motion, gravity)
    sd, period = sd_max(motion, DEFAULT_DAMPING, DEFAULT_BAND)
    meta = motion.meta
    table = Table(title=_record_id(record_id), show_header=False)
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
        save_figure(record_history_figure(motion), plot, dpi=130)
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
    zeta = _parse_damping(damping)
    lo, hi = _parse_band(band)
    from .. import motion_measures, motion_spectrum, period_grid, record_spectrum_figure, save_figure, sd_max
    motion = _load(record_id, gravity, records_dir)
    from .inputs import compile_kernels
    compile_kernels("records")
    periods = period_grid((lo, hi), n_periods)
    sd, psv, psa = motion_spectrum(motion, periods, zeta)
    peak, period = sd_max(motion, zeta, (lo, hi), n_periods)
    measures = motion_measures(motion, gravity)
    result = {"id": _record_id(record_id), "damping": zeta, "band": [lo, hi], "periods": periods.tolist(),
              "SD": sd.tolist(), "PSV": psv.tolist(), "PSA": psa.tolist(), "sd_max": peak, "t_sd_max": period,
              **{k: measures[k] for k in ("pga", "pgv", "pgd", "arias", "cav", "bracketed_duration",
                                          "significant_duration", "a_rms", "predominant_frequency")}}
    if plot is not None:
        save_figure(record_spectrum_figure(result, gravity), plot, dpi=130)
    if as_json:
        typer.echo(json.dumps(result))
        return
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
    from .. import SCALE_CHOICES, synthesize
    if scale_to not in SCALE_CHOICES:
        raise MotionError("invalid --scale-to", key="--scale-to", expected=" | ".join(SCALE_CHOICES),
                          found=repr(scale_to))
    from .inputs import output_folder
    output_folder(out_dir, "--out")
    motion = _load(seed, gravity, records_dir)
    from .inputs import compile_kernels
    compile_kernels("records")                  # (SD_max of the seed and of every member)
    from .. import progress_bars
    with progress_bars() as progress:
        path, match = synthesize(motion, n, out_dir, seed_value=seed_value, scale_to=scale_to, progress=progress)
    console = _console()
    console.print(f"wrote {n} records to {path} (+ {path.with_suffix('.npz').name}, model.json, match.json)")
    console.print(match.describe())
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
    from .experiments import scale_model_command as run
    code = run(_record_id(record_id), length_ratio, table, out, plot, band, as_json, gravity,
               _load(record_id, gravity, records_dir))
    raise typer.Exit(code)
