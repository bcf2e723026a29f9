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
            err_console.print(f"[bold red]error:[/] {exc}", highlight=False, markup=True, soft_wrap=True)
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
                                                   help="Display units, comma separated, e.g. 'mm,deg,kN,g'.")):
    """Closed-form design quantities (SPEC §2)."""
    from .api import quantities_json, quantities_table
    from .project import load_project
    proj = load_project(project)
    if as_json:
        sys.stdout.write(json.dumps(quantities_json(proj), indent=2) + "\n")
        return
    quantities_table(proj, console, units)


def _mount_optional_apps():
    try:
        from .cli_records import app as records_app
    except ImportError:  # the ground-motion tools are an optional part during development
        return
    app.add_typer(records_app, name="records", help="Ground-motion tools: list, show, spectrum, synth.")


_mount_optional_apps()


def main():  # console-script entry point
    app()


if __name__ == "__main__":
    main()
