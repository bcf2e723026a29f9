"""Command-line interface: thin wrappers over the library API (CONTRACT §2).

Every command turns a :class:`~rockdesign.errors.RockdesignError` into one line on stderr and exit
code 2 (no traceback); ``check`` exits 1 when the design fails a criterion.
"""
from __future__ import annotations

import functools
import json
import sys
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.markup import escape

from . import __version__
from .errors import RockdesignError

app = typer.Typer(add_completion=False, no_args_is_help=True,
                  help="Design checks for rocking columns, rocking frames and rocking podium buildings.")
err_console = Console(stderr=True)
console = Console()


def handle_errors(func):
    """Convert user-input errors to a clean message and exit code 2."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except RockdesignError as exc:
            err_console.print(f"[bold red]error:[/] {escape(str(exc))}", highlight=False, markup=True, soft_wrap=True)
            raise typer.Exit(2) from None

    return wrapper


def _version_callback(value: bool):
    if value:
        console.print(f"rockdesign {__version__}")
        raise typer.Exit()


@app.callback()
def _root(version: bool = typer.Option(False, "--version", callback=_version_callback, is_eager=True,
                                       help="Print the version and exit.")):
    """rockdesign: uplift thresholds, capacities, time-history analysis and Polyakov checks."""


@app.command()
@handle_errors
def init(kind: str = typer.Argument(..., help="podium | column"),
         path: Optional[Path] = typer.Argument(None, help="Where to write (default: KIND.toml)"),
         force: bool = typer.Option(False, "--force", help="Overwrite an existing file.")):
    """Write a commented template project file."""
    from .templates import write_template
    out = write_template(kind, path, force=force)
    console.print(f"wrote {out}")


@app.command()
@handle_errors
def quantities(project: Path = typer.Argument(..., help="Project file (TOML)"),
               as_json: bool = typer.Option(False, "--json", help="Print CONTRACT §3 JSON (SI units)."),
               units: Optional[str] = typer.Option(None, "--units",
                                                   help="Display units, comma separated, e.g. 'mm,deg,kN,g'."),
               pushover: Optional[Path] = typer.Option(None, "--pushover", help="Write the pushover curve "
                                                       "F_R/(m g) vs θ: .csv for the numbers, .png/.svg/.pdf for a plot.")):
    """Closed-form design quantities (SPEC §2)."""
    from .api import quantities_json, quantities_table, write_pushover
    from .project import load_project
    proj = load_project(project)
    if pushover is not None:
        write_pushover(proj.system, pushover)
    if as_json:
        sys.stdout.write(json.dumps(quantities_json(proj), indent=2) + "\n")
        return
    quantities_table(proj, console, units)


@app.command()
@handle_errors
def simulate(project: Path = typer.Argument(..., help="Project file (TOML)"),
             motion: str = typer.Option(..., "--motion", "-m", help="e.g. 'ricker-anti:ap=0.38g,Tp=0.95s', "
                                        "'free:theta0=0.8alpha', 'record:p695-ff/11a,scale=1.5', 'file:X.AT2'"),
             model: str = typer.Option("auto", "--model", help="exact | linear | linear-exact | auto"),
             as_json: bool = typer.Option(False, "--json", help="Print CONTRACT §3 JSON (SI units)."),
             plot: Optional[Path] = typer.Option(None, "--plot", help="Write a time-history figure (png/svg/pdf)."),
             csv: Optional[Path] = typer.Option(None, "--csv", help="Write the time history as CSV."),
             t_end: Optional[float] = typer.Option(None, "--t-end", help="End time [s] (default: motion + "
                                                   "free vibration)."),
             rtol: Optional[float] = typer.Option(None, "--rtol", help="Relative tolerance (default: project)."),
             records_dir: Optional[Path] = typer.Option(None, "--records-dir", help="Folder of PEER AT2 files.")):
    """One nonlinear time-history analysis (SPEC §3)."""
    from .api import simulate_project
    from .project import load_project
    proj = load_project(project)
    from .dynamics.compilation import prepare
    prepare("simulate", Console(stderr=True).print)
    result = simulate_project(proj, motion, model=model, t_end=t_end, rtol=rtol,
                              records_dir=str(records_dir) if records_dir else None)
    if csv:
        from .api import write_history_csv
        write_history_csv(result.response, csv)
    if plot:
        from .report.plots import save, time_history_figure
        save(time_history_figure(result.response, proj.system.g, f"{proj.name} — {motion}"), plot)
    if as_json:
        sys.stdout.write(json.dumps(result.as_json(), indent=2) + "\n")
        return
    from .display import response_table
    response_table(result, console)


def _mount_command_modules():
    """Mount the commands that live in their own modules (records, check, spectrum, bench)."""
    from . import cli_bench, cli_check, cli_spectrum
    from .cli_records import app as records_app
    for command in records_app.registered_commands:
        command.callback = handle_errors(command.callback)
    app.add_typer(records_app, name="records", help="Ground-motion tools: list, show, spectrum, synth.")
    for module in (cli_check, cli_spectrum, cli_bench):
        module.register(app, handle_errors)


_mount_command_modules()


def main():  # console-script entry point
    app()


if __name__ == "__main__":
    main()
