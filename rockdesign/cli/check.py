"""``rockdesign check``: the design check and its calculation report (CONTRACT §2, §4)."""
from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console


def register(app: typer.Typer, handle_errors) -> None:
    @app.command()
    @handle_errors
    def check(project: Path = typer.Argument(..., help="Project file (TOML)"),
              out: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder (default: <project>_check)"),
              as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print results.json to stdout."),
              no_pdf: bool = typer.Option(False, "--no-pdf", metavar=" ", help="Skip the PDF (results.json/csv and HTML only)."),
              html: bool = typer.Option(False, "--html", metavar=" ", help="Write report.html even with --no-pdf."),
              no_margins: bool = typer.Option(False, "--no-margins", metavar=" ", help="Skip the incremental margin analysis."),
              records_dir: Optional[Path] = typer.Option(None, "--records-dir", help="Folder of PEER AT2 files."),
              dask: Optional[str] = typer.Option(None, "--dask", help="Run the analyses on dask.distributed: "
                                                 "'local:N' (a local cluster of N workers) or a scheduler address.")):
        """Polyakov design check over record suites, with a PDF calculation report (exit 0 = PASS,
        1 = FAIL, 2 = input error or failed analyses, 4 = not decided: a governing criterion was not
        evaluated, e.g. --no-margins; 130 = interrupted)."""
        # a second process loads WeasyPrint on the core this one leaves idle while it starts, and writes
        # the PDF at the end (report.pdf_worker)
        pdf_worker = None
        if not no_pdf and not os.environ.get("ROCKDESIGN_NO_PDF_WORKER"):
            from ..report.pdf_worker import PdfWorker
            pdf_worker = PdfWorker.start()
        try:
            _check(project, out, as_json, no_pdf, html, no_margins, records_dir, dask, pdf_worker)
        finally:
            if pdf_worker is not None:
                pdf_worker.close()


def _check(project, out, as_json, no_pdf, html, no_margins, records_dir, dask, pdf_worker) -> None:
    from ..library import check as run_check
    from ..library import write_report
    from ..outdir import OutputFolder
    from ..project import load_project
    from ..report.results import json_text
    proj = load_project(project)
    target = out if out is not None else Path(f"{Path(project).stem}_check")
    if proj.system.kind == "cylinder":                  # the 3D cylinder (thesis Ch. 5)
        from .cylinder import check_summary as cylinder_summary
        from ..report.cylinder_report import cylinder_output_folder
        from ..errors import RockdesignError
        for flag, value in (("--dask", dask), ("--records-dir", records_dir)):
            if value is not None:
                raise RockdesignError("not used by the check of a cylinder (built-in suites of record pairs, "
                                      "analysed in this process)", key=flag, expected="no " + flag,
                                      found=repr(str(value)))
        if pdf_worker is not None:
            pdf_worker.close()    # (the cylinder's report is written here)
        folder = cylinder_output_folder(target, key="-o/--out")
        with folder.locked():   # before the analyses, as below
            from .inputs import compile_kernels
            compile_kernels("cylinder-check")
            result = run_check(proj, progress=not as_json or Console(stderr=True).is_terminal)
            _report(write_report, result, folder, no_pdf, html)
        if as_json:
            sys.stdout.write(json_text(result.as_json()))
        else:
            cylinder_summary(result.as_json(), folder.target, Console())
        raise typer.Exit(_exit_code(result.verdict))
    folder = OutputFolder(target, key="-o/--out")
    with folder.locked():   # before the analyses: a file, a read-only or busy folder stops here (exit 2)
        from ..dynamics.compilation import missing_kernels, prepare
        if missing_kernels("check"):       # a first run: an input error in the records stops it before compiling
            from ..checks.check import check_records
            check_records(proj, records_dir)
        # the engine finishes compiling in a helper while the check reads its records (run_check waits)
        prepare("check", Console(stderr=True).print, background=True)
        from ..dynamics.compilation import compilation_pending
        if compilation_pending() and not no_pdf:    # this process would wait: load the report's libraries
            from ..report.render import warm_up
            warm_up(pdf=pdf_worker is None)
        executor = None
        if dask:
            from ..execution.executor import make_executor
            executor = make_executor(dask)
            executor.start()
        try:
            result = run_check(proj, records_dir=records_dir, margins=not no_margins,
                               progress=not as_json or Console(stderr=True).is_terminal, executor=executor)
        finally:
            if executor is not None:
                executor.close()
        _report(write_report, result, folder, no_pdf, html, pdf_worker)
    data = result.as_json()
    if as_json:
        sys.stdout.write(json_text(data))
    else:
        from ..display import check_summary
        check_summary(data, folder.target, Console())
    # failed analyses: the check is incomplete (exit 2), whatever the other records say
    raise typer.Exit(2 if data.get("failed_records") else _exit_code(data["verdict"]))


def _exit_code(verdict: str) -> int:
    """0 PASS, 1 FAIL, 4 not decided (a governing criterion was not evaluated; CONTRACT §6.1)."""
    return {"PASS": 0, "FAIL": 1}.get(verdict, 4)


def _report(write_report, result, folder, no_pdf: bool, html: bool, pdf_worker=None) -> None:
    """Write the output folder (results.json/csv and the report), with a spinner on a terminal: the
    figures and the PDF take seconds after the analyses' progress bars have ended."""
    what = ("results and calculation report (figures, PDF)" if not no_pdf
            else "results and HTML report" if html else "results")
    with Console(stderr=True).status(f"writing the {what}"):
        write_report(result, folder, pdf=not no_pdf, html=html or not no_pdf, pdf_worker=pdf_worker)
