"""``quantities`` and ``simulate`` commands for a ``[cylinder]`` project (called from rockdesign.cli)."""
from __future__ import annotations

import json
import sys


def quantities_command(project, console, as_json: bool, units, curve) -> None:
    """Print the cylinder's quantities (or JSON); ``--pushover F`` writes the wobbling-period curve (Fig 5.2)."""
    from .cylinder.commands import quantities_json, quantities_table, write_wobbling
    if curve is not None:
        write_wobbling(project, curve)
    if as_json:
        sys.stdout.write(json.dumps(quantities_json(project), indent=2) + "\n")
        return
    quantities_table(project, console, units)


def simulate_command(project, motion, model, as_json, plot, csv, t_end, rtol, records_dir, console) -> None:
    """Run one cylinder analysis; JSON, CSV and the time-history/orbit figure on request."""
    from .cylinder.commands import response_table, simulate_project, write_history_csv
    result = simulate_project(project, motion, model=model, t_end=t_end, rtol=rtol,
                              records_dir=str(records_dir) if records_dir else None)
    if csv:
        write_history_csv(result.response, csv)
    if plot:
        from .plots import save
        from .cylinder.figures import cylinder_history_figure
        save(cylinder_history_figure(result.response, project.system.g, f"{project.name} — {motion}",
                                     result.pair), plot)
    if as_json:
        sys.stdout.write(json.dumps(result.as_json(), indent=2) + "\n")
        return
    response_table(result, console)


def check_summary(data: dict, out_dir, console) -> None:
    """Print the checks of a cylinder check (results.json ``data``), the verdict and the output folder."""
    from rich.markup import escape
    from rich.table import Table
    table = Table(title=f"{data['project']['name']} — cylinder check", title_justify="left")
    for col in ("check", "utilisation", "result", "detail"):
        table.add_column(col)
    for c in data["checks"]:
        table.add_row(escape(c["name"]), f"{c['utilisation']:.3f}",
                      ("PASS" if c["passed"] else "FAIL") + ("" if c["governs_verdict"] else " (info)"),
                      escape(c["detail"]))
    console.print(table)
    colour = "green" if data["verdict"] == "PASS" else "red"
    console.print(f"verdict: [bold {colour}]{data['verdict']}[/]   output: {escape(str(out_dir))}", highlight=False)
