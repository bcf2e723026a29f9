"""``rockdesign design``: the check over a grid of one or two project keys, with design charts (CONTRACT §6.3)."""
from __future__ import annotations

import sys
from pathlib import Path
from typing import List, Optional

import typer
from ..console import make_console


def register(app: typer.Typer, handle_errors) -> None:
    @app.command()
    @handle_errors(executor="--dask")
    def design(project: Path = typer.Argument(..., help="Project file (TOML)"),
               vary: List[str] = typer.Option(..., "--vary", metavar="TABLE.KEY=FROM:TO:N", help="In the key's units, e.g. "
                                              "podium.width=0.36m:0.60m:7 (once or twice)."),
               out: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder (default: <project>_design)"),
               as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print design.json to stdout."),
               no_pdf: bool = typer.Option(False, "--no-pdf", metavar=" ", help="Skip the PDF and HTML report."),
               records_dir: Optional[Path] = typer.Option(None, "--records-dir", help="Folder of PEER AT2 files."),
               dask: Optional[str] = typer.Option(None, "--dask", help="Run the analyses on dask.distributed: "
                                                  "'local:N' or a scheduler address.")):
        """Design chart: the check of every variant of one or two keys, the pass/fail region, contours of
        ACMR and of the superstructure's shear coefficient (a cylinder: of its overturning record pairs),
        and the recommended design (exit 0 = at least one variant passes, 1 = none does, 2 = input error)."""
        # the heavy modules (numpy, numba, pint, scipy) are imported here, not at module level: the CLI
        # mounts this command at every start-up (tests/cli/test_startup.py)
        from .. import design_command
        code = design_command(project, vary, out, as_json=as_json, no_pdf=no_pdf,
                              records_dir=str(records_dir) if records_dir else None, dask=dask,
                              console=make_console(stderr=True), stdout=sys.stdout)
        raise typer.Exit(code)
