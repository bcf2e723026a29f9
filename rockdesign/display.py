"""Human-readable output: rich tables and display-unit conversion (pint at the boundary)."""
from __future__ import annotations

import math

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from .errors import RockdesignError
from .units import registry

_SI_UNITS = {"m": "m", "rad": "rad", "1/s": "1/s", "m/s^2": "m/s^2", "N": "N", "s": "s", "kg": "kg", "-": ""}


def parse_display_units(spec: str | None, gravity: float) -> list[tuple[str, object]]:
    """Parse ``--units 'mm,deg,kN,g'`` into (label, pint unit) pairs; 'g' means the project's g."""
    if not spec:
        return []
    ureg = registry()
    out = []
    for token in (t.strip() for t in spec.split(",")):
        if not token:
            continue
        if token == "g":
            out.append(("g", ureg.Quantity(gravity, "m/s^2")))
            continue
        try:
            out.append((token, ureg.Quantity(1.0, ureg.parse_units(token.replace("^", "**")))))
        except Exception:
            raise RockdesignError("unknown display unit", key="--units", expected="pint units such as mm, deg, kN, g",
                                  found=f"'{token}'") from None
    return out


def convert_for_display(value: float, unit: str, targets) -> tuple[float, str]:
    """Convert an SI value to the first matching display unit of ``targets`` (else keep SI)."""
    if not targets or unit in ("-", "") or math.isinf(value):
        return value, unit
    ureg = registry()
    q = ureg.Quantity(value, ureg.parse_units(unit.replace("^", "**")))
    for label, ref in targets:
        if q.dimensionality == ref.dimensionality:
            return float((q / ref).to("").magnitude), label
    return value, unit


def format_value(value: float) -> str:
    if math.isinf(value):
        return "∞"
    if value == 0:
        return "0"
    a = abs(value)
    if 1e-3 <= a < 1e5:
        return f"{value:.5g}"
    return f"{value:.4e}"


def quantities_table(quantities: dict, console: Console, units: str | None, gravity: float, title: str,
                     warnings=()) -> None:
    """Print design quantities as a table: symbol, name, value, unit, equation."""
    targets = parse_display_units(units, gravity)
    table = Table(title=title, title_justify="left")
    for col in ("symbol", "quantity", "value", "unit", "equation"):
        table.add_column(col, justify="right" if col == "value" else "left")
    for q in quantities.values():
        v, u = convert_for_display(q.value, q.unit, targets)
        table.add_row(q.symbol, q.description + (f" ({q.note})" if q.note else ""), format_value(v), u or "-",
                      q.equation)
    console.print(table)
    for w in warnings:
        console.print(f"[yellow]warning:[/] {escape(w)}", highlight=False)


def response_table(result, console: Console) -> None:
    """Print the summary of one time-history analysis."""
    r = result.response
    table = Table(title=f"{result.project.name} — {result.motion_text}", title_justify="left")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_column("unit")
    rows = [
        ("model", r.model, ""),
        ("θ_max", format_value(r.theta_max), "rad"),
        ("θ_max/α", format_value(r.theta_max_over_alpha), "-"),
        ("θ_max/θc", format_value(r.theta_max_over_theta_c), "-"),
        ("u_B,max (column top)", format_value(r.u_B_max), "m"),
        ("u_B,max / capacity", format_value(r.u_B_max_over_capacity), "-"),
        ("first uplift", "none" if r.uplift_time is None else format_value(r.uplift_time), "s"),
        ("time uplifted", format_value(r.time_uplifted), "s"),
        ("impacts", str(r.impacts), ""),
        ("overturn mode", r.overturn_mode, ""),
        (f"overturned ({r.overturn_criterion} criterion)", "YES" if r.overturned else "no", ""),
        ("analysed until", format_value(r.t_end), "s"),
        ("solver", f"{r.diagnostics['steps']} steps, {r.diagnostics['rejected_steps']} rejected, "
                   f"{r.diagnostics['function_evaluations']} evaluations, {r.diagnostics['events']} events — "
                   f"{r.status}", ""),
    ]
    if r.drift_max:
        rows.insert(5, ("max |u_T − u_B| (sampled)", format_value(r.drift_max), "m"))
    at = next(i for i, row in enumerate(rows) if row[0] == "u_B,max / capacity") + 1
    rows[at:at] = demand_rows(r, result.project.system.g)
    params = getattr(result, "motion_parameters", None)
    if params:
        g = result.project.system.g
        extra = [("pulse amplitude a_p", f"{format_value(params['a_p'])} ({params['a_p'] / g:.4g} g)", "m/s^2"),
                 ("pulse period T_p", format_value(params["T_p"]), "s")]
        if "t_m" in params:
            extra.append(("wavelet centre t_m", format_value(params["t_m"]), "s"))
        rows[1:1] = extra
    for row in rows:
        table.add_row(*row)
    console.print(table)
    for w in getattr(result, "warnings", result.project.warnings):
        console.print(f"[yellow]warning:[/] {escape(w)}", highlight=False)


def demand_rows(r, g: float) -> list[tuple[str, str, str]]:
    """Rows of the superstructure demand of a simulate response (2DOF podium: peak absolute acceleration of
    the superstructure, the fixed-base reference and their ratio; rigid masses: the cap beam), SPEC §13."""
    rows = []
    until = " (until overturning)" if r.overturned else ""
    if r.superstructure_acceleration_max is not None:
        a = r.superstructure_acceleration_max
        rows.append(("superstructure max |a_T| (abs.)" + until, f"{format_value(a)} ({a / g:.4g} g)", "m/s^2"))
        if r.fixed_base_acceleration_max:
            f = r.fixed_base_acceleration_max
            rows.append(("same on a fixed base", f"{format_value(f)} ({f / g:.4g} g)", "m/s^2"))
            rows.append(("force ratio rocking / fixed base", format_value(a / f), "-"))
    elif r.cap_acceleration_max is not None:
        rows.append(("cap beam max |a| between impacts" + until, format_value(r.cap_acceleration_max), "m/s^2"))
        rows.append(("cap beam max velocity jump (impact)", format_value(r.cap_velocity_jump_max), "m/s"))
    return rows


def check_summary(data: dict, out_dir, console: Console) -> None:
    """Print the checks, what the run found (failed analyses, missing records), the verdict and its
    reason, and where the report went."""
    s = data["summary"]
    table = Table(title=f"{data['project']['name']} — design check", title_justify="left")
    for col in ("check", "utilisation", "result"):
        table.add_column(col, justify="right" if col == "utilisation" else "left")
    for c in data["checks"]:
        res = ("not evaluated" if not c.get("evaluated", True) else "PASS" if c["passed"] else "FAIL") + {
            "governs": "", "robustness": " (robustness)"}.get(
            c.get("role", "governs" if c["governs_verdict"] else ""), " (info)")
        table.add_row(escape(c["name"]), format_value(c["utilisation"]), res)
    console.print(table)
    exc = data["excitation"]
    for m in exc.get("missing", []):
        console.print(f"[yellow]warning:[/] record {escape(m['id'])} not analysed: {escape(str(m['reason']))}",
                      highlight=False)
    for w in exc.get("record_warnings", []):
        console.print(f"[yellow]warning:[/] {escape(w)}", highlight=False)
    for f in data.get("failed_records", []):
        console.print(f"[bold red]analysis failed:[/] {escape(f['id'])} — {escape(f['status'])} (not counted as "
                      "safe)", highlight=False)
    if s["n_records"]:
        ci = s["p_overturn_ci90"]
        prob = f"P(overturn) = {s['p_overturn']:.3f}, 90 % interval [{ci[0]:.3f}, {ci[1]:.3f}]"
    else:
        prob = "P(overturn) not estimated"
    console.print(f"model: {escape(data['model']['chosen'])} — records analysed: {s['n_records']}"
                  + (f" (+{s.get('n_failed')} failed)" if s.get("n_failed") else "")
                  + (f", missing: {len(exc.get('missing', []))}" if exc.get("missing") else "")
                  + (f" from {s['n_ground_motions']} ground motions" if s.get("n_ground_motions") else "")
                  + f", overturned: {s['n_overturned']} ({s['overturn_criterion']} criterion), false negatives "
                  f"(class b): {s['n_false_negative']}, {prob}", highlight=False)
    if exc.get("intensity_analysed"):
        console.print(f"intensity analysed: {escape(exc['intensity_analysed'])}", highlight=False)
    colour = "green" if data["verdict"] == "PASS" and data.get("verdict_robust", True) else (
        "yellow" if data["verdict"] in ("PASS", "NOT DECIDED") else "red")
    console.print(f"verdict: [bold {colour}]{escape(data.get('verdict_reason') or data['verdict'])}[/]", highlight=False)
    console.print(f"output: {escape(str(out_dir))}", highlight=False)
