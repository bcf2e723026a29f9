"""``quantities`` and ``simulate`` commands for a ``[cylinder]`` project (called from rockdesign.cli)."""
from __future__ import annotations

import json
import sys


def quantities_command(project, console, as_json: bool, units, curve) -> None:
    """Print the cylinder's quantities (or JSON); ``--pushover F`` writes the wobbling-period curve (Fig 5.2)."""
    from ..cylinder.commands import quantities_json, write_wobbling
    if curve is not None:
        write_wobbling(project, curve)
    if as_json:
        sys.stdout.write(json.dumps(quantities_json(project), indent=2) + "\n")
        return
    quantities_table(project, console, units)


def simulate_command(project, motion, model, as_json, plot, csv, t_end, rtol, records_dir, console) -> None:
    """Run one cylinder analysis; JSON, CSV and the time-history/orbit figure on request."""
    from ..cylinder.commands import simulate_project, write_history_csv
    from .inputs import compile_kernels
    result = simulate_project(project, motion, model=model, t_end=t_end, rtol=rtol,
                              records_dir=str(records_dir) if records_dir else None,
                              before_analysis=lambda: compile_kernels("cylinder"))
    if csv:
        write_history_csv(result.response, csv)
    if plot:
        from ..plots import save
        from ..cylinder.figures import cylinder_history_figure
        save(cylinder_history_figure(result.response, project.system.g, f"{project.name} — {motion}",
                                     result.pair), plot)
        from ..console import make_console
        make_console(stderr=True).print(f"wrote {plot}", highlight=False, soft_wrap=True)
    if as_json:
        sys.stdout.write(json.dumps(result.as_json(), indent=2) + "\n")
        return
    response_table(result, console)


def check_summary(data: dict, out_dir, console) -> None:
    """Print the checks of a cylinder check (results.json ``data``), the verdict and the output folder."""
    from rich.markup import escape
    from rich.table import Table
    table = Table(title=escape(f"{data['project']['name']} — cylinder check"), title_justify="left")
    from ..report.cylinder_report import check_rows
    for col in ("check", "utilisation or ratio", "result", "detail"):
        table.add_column(col)
    for c in check_rows(data["checks"]):          # the report's wording: informative checks are not failures
        result = ("PASS" if c["passed"] else "FAIL") if c["governs_verdict"] else f"{c['result_text']} (info)"
        table.add_row(escape(c["name"]), escape(c["value_text"]), result, escape(c["detail"]))
    console.print(table)
    colour = "green" if data["verdict"] == "PASS" else "red"
    console.print(f"verdict: [bold {colour}]{data['verdict']}[/]   output: {escape(str(out_dir))}", highlight=False)


def quantities_table(project, console, units: str | None = None) -> None:
    """Print the cylinder's quantities with their thesis equations."""
    from ..cylinder.quantities import cylinder_quantities
    from ..display import quantities_table as table
    table(cylinder_quantities(project.system), console, units, project.system.g,
          f"{project.name} — design quantities (cylinder, {project.system.contact} contact)", project.warnings)


def response_table(result, console) -> None:
    """Print the summary of one cylinder analysis."""
    from rich.markup import escape
    from rich.table import Table

    from ..cylinder.engine import SPIN_TILT_MIN
    from ..display import format_value
    r = result.response
    table = Table(title=escape(f"{result.project.name} — {result.motion_text}"), title_justify="left")
    for col in ("quantity", "value", "unit"):
        table.add_column(col, justify="right" if col == "value" else "left")
    table.caption = (f"φ̇ near θ = 0 is the contact point whirling round the rim (quasi-impact, unbounded as θ → 0), "
                     f"not a rotation of the body: it is reported where θ ≥ {SPIN_TILT_MIN:g}α")
    table.caption_justify = "left"
    j = r.as_json()
    rows = [("model", j["model"], "")]
    pair = getattr(result, "pair", None)
    if pair is not None and pair.is_record:
        pga = pair.resultant_pga
        g = result.project.system.g
        rows += [("resultant PGA as applied", f"{format_value(pga)} ({pga / g:.4g} g)", "m/s^2"),
                 ("scale (× the records as read)", format_value(pair.scale), "-")]
    rows += [("θ_max", format_value(r.theta_max), "rad"),
            ("θ_max/α", format_value(r.theta_max / r.alpha), "-"),
            ("first uplift", "none" if r.uplift_time is None else format_value(r.uplift_time), "s"),
            ("quasi-impacts", str(r.quasi_impacts), ""),
            (f"max |φ̇| where θ ≥ {SPIN_TILT_MIN:g}α", "—" if r.spin_max() is None else format_value(r.spin_max()),
             "rad/s"),
            ("φ at the end", format_value(j["phi_end"]), "rad"),
            (f"overturned (θ ≥ θ_ot = {r.theta_overturn:.4g} rad)", "YES" if r.overturned else "no", ""),
            ("analysed until", format_value(float(r.t[-1])), "s")]
    if r.damped:
        rows.append(("min contact force N/(m g)", format_value(r.min_contact_force_over_weight), "-"))
    s = r.solver
    rows.append(("solver", f"{s['steps']} steps, {s['rejected_steps']} rejected, {s['rhs_evaluations']} evaluations"
                           f" — {r.status}", ""))
    for row in rows:
        table.add_row(*row)
    console.print(table)
