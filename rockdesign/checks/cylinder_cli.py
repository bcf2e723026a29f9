"""``rockdesign check`` for a cylinder project: progress bar, results files, summary, exit code."""
from __future__ import annotations

import json
import sys
from pathlib import Path

import typer
from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn


def cylinder_check_command(project, project_path, out, as_json: bool, err: Console) -> None:
    """Run :func:`run_cylinder_check`, write results.json/csv and the figure, print the verdict; exit 0/1."""
    from rich.markup import escape
    from rich.table import Table

    from .cylinder_check import run_cylinder_check, write_cylinder_results
    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                  console=err, disable=as_json and not err.is_terminal) as bar:
        tasks = {}

        def progress(stage, done, total):
            if stage not in tasks:
                tasks[stage] = bar.add_task(stage, total=total)
            bar.update(tasks[stage], completed=done, total=total)

        data = run_cylinder_check(project, progress=progress)
    out_dir = out if out is not None else Path(f"{Path(project_path).stem}_check")
    write_cylinder_results(data, out_dir)
    from ..cylinder.figures import wobbling_figure
    from ..report.plots import save
    save(wobbling_figure(project.system), Path(out_dir) / "wobbling_period.png")   # Fig 5.2 for this cylinder
    if as_json:
        sys.stdout.write(json.dumps(data, indent=2, ensure_ascii=False) + "\n")
    else:
        console = Console()
        table = Table(title=f"{data['project']['name']} — cylinder check", title_justify="left")
        for col in ("check", "utilisation", "result", "detail"):
            table.add_column(col)
        for c in data["checks"]:
            table.add_row(escape(c["name"]), f"{c['utilisation']:.3f}",
                          ("PASS" if c["passed"] else "FAIL") + ("" if c["governs_verdict"] else " (info)"),
                          escape(c["detail"]))
        console.print(table)
        colour = "green" if data["verdict"] == "PASS" else "red"
        console.print(f"verdict: [bold {colour}]{data['verdict']}[/]   output: {escape(str(out_dir))}",
                      highlight=False)
    raise typer.Exit(0 if data["verdict"] == "PASS" else 1)
