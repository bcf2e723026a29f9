"""``rockdesign check``: the design check and its calculation report (CONTRACT §2, §4)."""
from __future__ import annotations

import sys
from pathlib import Path
from typing import Optional

import typer

from ..console import make_console


def register(app: typer.Typer, handle_errors) -> None:
    @app.command()
    @handle_errors(executor="--dask", out_dir="-o/--out")
    def check(project: Path = typer.Argument(..., help="Project file (TOML)"),
              out: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder (default: <project>_check)"),
              as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print results.json to stdout."),
              no_pdf: bool = typer.Option(False, "--no-pdf", metavar=" ", help="Skip the report: results.json/csv only (add --html for report.html)."),
              html: bool = typer.Option(False, "--html", metavar=" ", help="Write report.html even with --no-pdf."),
              no_margins: bool = typer.Option(False, "--no-margins", metavar=" ", help="Skip the incremental margin analysis."),
              records_dir: Optional[Path] = typer.Option(None, "--records-dir", help="Folder of PEER AT2 files."),
              dask: Optional[str] = typer.Option(None, "--dask", help="Run the analyses on dask.distributed: "
                                                 "'local:N' (a local cluster of N workers) or a scheduler address.")):
        """Polyakov design check over record suites, with a PDF calculation report (exit 0 = PASS, 1 = FAIL, 2 = input error or failed analyses, 3 = internal error, 4 = not decided: a governing criterion was not evaluated, e.g. --no-margins; 130 = interrupted)."""  # noqa: E501
        from .. import library as rd      # (lazy: mounting the commands loads no numerical library)
        _check(rd, project, out, as_json, no_pdf, html, no_margins, records_dir, dask)


def _check(rd, project, out, as_json, no_pdf, html, no_margins, records_dir, dask) -> None:
    from rich.markup import escape

    from .. import design_hint
    from ..display import check_summary
    proj = rd.load_project(project)
    rd.check_options(proj, records_dir=records_dir, executor=dask)
    folder = rd.check_output_folder(proj, out if out is not None else Path(f"{Path(project).stem}_check"),
                                    key="-o/--out")
    with folder.locked():   # before the analyses: a file, a read-only or busy folder stops here (exit 2)
        rd.prepare_check(proj, records_dir=records_dir, say=make_console(stderr=True).print)
        result = rd.run_check(proj, records_dir=records_dir, margins=not no_margins,
                              progress=not as_json or make_console(stderr=True).is_terminal, executor=dask)
        data = result.as_json()
        if not as_json:     # the verdict first: the engineer reads it while the report is being written
            check_summary(data, None, make_console(), hint=_command(design_hint(proj, data)))
        _report(rd.write_report, result, folder, no_pdf, html)
    if as_json:
        sys.stdout.write(rd.json_text(data))
    else:
        make_console().print(f"output: {escape(str(folder.target))}", highlight=False)
    # failed analyses: the check is incomplete (exit 2), whatever the other records say
    raise typer.Exit(2 if data.get("failed_records") else _exit_code(data["verdict"]))


def _exit_code(verdict: str) -> int:
    """0 PASS, 1 FAIL, 4 not decided (a governing criterion was not evaluated; CONTRACT §6.1)."""
    return {"PASS": 0, "FAIL": 1}.get(verdict, 4)


def _report(write_report, result, folder, no_pdf: bool, html: bool) -> None:
    """Write the output folder (results.json/csv and the report), with a spinner on a terminal (plain lines
    elsewhere): the figures and the PDF take seconds after the analyses' progress bars have ended."""
    what = ("results and calculation report (figures, PDF)" if not no_pdf
            else "results and HTML report" if html else "results")
    from .. import working
    with working(f"writing the {what}"):
        write_report(result, folder, pdf=not no_pdf, html=html or not no_pdf)


def _command(hint) -> str | None:
    """A failed check's hint as the ``rockdesign design`` command to run."""
    if hint is None:
        return None
    first = "give the project an [excitation] table, then " if hint.needs_excitation else ""
    return (f"to find a design that passes, vary what governs the rocking demand ({hint.why}): {first}"
            f"rockdesign design {hint.file} " + " ".join(f"--vary {v}" for v in hint.vary))
