"""``rockdesign check``: the design check and its calculation report (CONTRACT §2, §4)."""
from __future__ import annotations

import csv
import json
import sys
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

CSV_COLUMNS = ["id", "suite", "event", "station", "rsn", "component", "scale", "pga", "sd_max", "sd_max_period",
               "polyakov_ratio", "theta_max_over_alpha", "theta_max_over_theta_c", "u_B_max", "u_B_max_over_2B",
               "impacts", "uplift_time", "overturned", "overturn_mode", "class", "overturn_scale", "polyakov_scale"]


def write_results(result, out_dir: Path, *, pdf: bool = True, html: bool = True) -> dict:
    """Write results.json, results.csv and (optionally) report.html / report.pdf into ``out_dir``."""
    out_dir.mkdir(parents=True, exist_ok=True)
    data = result.as_json()
    (out_dir / "results.json").write_text(json.dumps(data, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    with open(out_dir / "results.csv", "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(CSV_COLUMNS)
        for row in data["records"]:
            w.writerow(["" if row.get(c) is None else row.get(c) for c in CSV_COLUMNS])
    if pdf or html:
        from .report.render import write_report
        write_report(result, out_dir, pdf=pdf, html=True)
    return data


def register(app: typer.Typer, handle_errors) -> None:
    @app.command()
    @handle_errors
    def check(project: Path = typer.Argument(..., help="Project file (TOML)"),
              out: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder (default: <project>_check)"),
              as_json: bool = typer.Option(False, "--json", help="Print results.json to stdout."),
              no_pdf: bool = typer.Option(False, "--no-pdf", help="Skip the PDF (results.json/csv and HTML only)."),
              html: bool = typer.Option(False, "--html", help="Write report.html even with --no-pdf."),
              no_margins: bool = typer.Option(False, "--no-margins", help="Skip the incremental margin analysis."),
              records_dir: Optional[Path] = typer.Option(None, "--records-dir", help="Folder of PEER AT2 files."),
              dask: Optional[str] = typer.Option(None, "--dask", help="Run the analyses on dask.distributed: "
                                                 "'local:N' (a local cluster of N workers) or a scheduler address.")):
        """Polyakov design check over record suites, with a PDF calculation report (exit 1 = FAIL)."""
        from .checks.check import run_check
        from .project import load_project
        err = Console(stderr=True)
        proj = load_project(project)
        from .dynamics.compilation import prepare
        prepare("check", err.print)
        with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                      console=err, transient=False, disable=as_json and not err.is_terminal) as bar:
            tasks = {}

            def progress(stage, done, total):
                if stage not in tasks:
                    tasks[stage] = bar.add_task(stage, total=total)
                bar.update(tasks[stage], completed=min(done, total), total=total)

            executor = None
            if dask:
                from .spectra.executor import make_executor
                executor = make_executor(dask)
                executor.start()
            try:
                result = run_check(proj, records_dir=str(records_dir) if records_dir else None,
                                   margins=not no_margins, progress=progress, executor=executor)
            finally:
                if executor is not None:
                    executor.close()
            for t in tasks.values():
                bar.update(t, completed=bar.tasks[t].total)
        out_dir = out if out is not None else Path(f"{Path(project).stem}_check")
        data = write_results(result, out_dir, pdf=not no_pdf, html=html or not no_pdf)
        if as_json:
            sys.stdout.write(json.dumps(data, indent=2, ensure_ascii=False) + "\n")
        else:
            from .display import check_summary
            check_summary(data, out_dir, Console())
        raise typer.Exit(0 if data["verdict"] == "PASS" else 1)
