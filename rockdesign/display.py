"""Human-readable output: rich tables and display-unit conversion (pint at the boundary)."""
from __future__ import annotations

import math
import re

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from .errors import RockdesignError
from .units import registry



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
            raise RockdesignError("unknown display unit", key="units", expected="pint units such as mm, deg, kN, g",
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


_DOC_REFERENCE = re.compile(r"docs/[\w-]+\.md(?:\s*§\d+)?")


def with_report_names(text: str, cite) -> str:
    """``text`` with each reference to the documentation followed by the calculation report's name for the same
    section (``cite``: :func:`rockdesign.report.methods.cite`): "docs/model.md §7 (report: Appendix M4)" — the
    console cited docs/model.md §7 where the report says Appendix M4."""
    if cite is None or not text:
        return text

    def both(m):
        named = cite(m.group())
        return m.group() if named == m.group() else f"{m.group()} (report: {named})"
    return _DOC_REFERENCE.sub(both, str(text))


def quantities_table(quantities: dict, console: Console, units: str | None, gravity: float, title: str,
                     warnings=(), cite=None) -> None:
    """Print design quantities as a table: symbol, name, value, unit, equation (each documentation reference
    with the report's name for it, :func:`with_report_names`)."""
    targets = parse_display_units(units, gravity)
    table = Table(title=escape(title), title_justify="left")
    for col in ("symbol", "quantity", "value", "unit", "equation"):
        table.add_column(col, justify="right" if col == "value" else "left")
    for q in quantities.values():
        v, u = convert_for_display(q.value, q.unit, targets)
        table.add_row(q.symbol, with_report_names(q.description + (f" ({q.note})" if q.note else ""), cite),
                      format_value(v),
                      readable_units(u or "-"), with_report_names(q.equation, cite))
    console.print(table)
    for w in warnings:
        console.print(f"[yellow]warning:[/] {escape(w)}", highlight=False)


def response_table(result, console: Console) -> None:
    """Print the summary of one time-history analysis (``result.summary_rows()``: quantity, value, unit)."""
    table = Table(title=escape(f"{result.project.name} — {result.motion_text}"), title_justify="left")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_column("unit")
    caption = getattr(result, "summary_caption", None)
    if caption:
        table.caption, table.caption_justify = caption, "left"
    for row in result.summary_rows():
        table.add_row(*(readable_units(x) for x in row))
    console.print(table)
    for w in result.warnings:
        console.print(f"[yellow]warning:[/] {escape(w)}", highlight=False)


_POWER = re.compile(r"(?<=[A-Za-z])\^([23])\b")


def readable_units(text: str) -> str:
    """Units for a reader: "m/s^2" → "m/s²", "t/m^3" → "t/m³" (JSON keeps the ASCII names, CONTRACT §3); the
    report and the console print one form (a table had m/s^2 beside m/s²)."""
    return _POWER.sub(lambda m: "²" if m.group(1) == "2" else "³", str(text))


RATIO_HEADING = "demand vs limit (passes at ≤ 1 × limit)"
"""What a check's ``utilisation`` is, in the report's and the console's words: the criterion's demand over its
limit (a count over the allowance, a required over an achieved margin, θ_max over θc, a 95 % bound of P(overturn)
over its limit …), ≤ 1 when it passes.  Each value is written as a multiple of the limit ("1.98 × limit"): a bare
"1.98" beside a check about ground motions read as "1.98 ground motions"."""
CANNOT_PASS = 1e8
"""Utilisations at or above this are the criteria's cap (:data:`rockdesign.acceptance.criterion_base.UTILISATION_CAP`,
e.g. a zero limit): not a number to read."""


def utilisation_number(value) -> str:
    """A check's demand/limit as a number: three significant digits ("2.00", never a bare "2"), "—" when the
    criterion cannot pass (the cap) or has no number."""
    if value is None or not isinstance(value, (int, float)) or math.isnan(value) or value >= CANNOT_PASS:
        return "—"
    return f"{value:.3g}" if value >= 1e-3 or value == 0 else f"{value:.1e}"


def utilisation_text(value) -> str:
    """A check's demand/limit for a table, as a multiple of its limit: "1.98 × limit" (the 95 % bound 0.198 of
    P(overturn) against its limit 0.10), "0.67 × limit"; "— (cannot pass)" at the criteria's cap, "—" without a
    number."""
    if isinstance(value, (int, float)) and not math.isnan(value) and value >= CANNOT_PASS:
        return "— (cannot pass)"
    number = utilisation_number(value)
    return number if number == "—" else f"{number} × limit"


def check_order(checks: list[dict], governing: str | None = None) -> list[dict]:
    """The checks as the reports list them: the governing check first, then those that decide the verdict, those
    that qualify it (robustness) and those that inform it, each group by decreasing demand/limit."""
    rank = {"governs": 0, "robustness": 1}
    top = next((c for c in checks if governing is not None and c.get("criterion") == governing), None)
    rest = sorted((c for c in checks if c is not top),
                  key=lambda c: (rank.get(c.get("role") or ("governs" if c.get("governs_verdict") else ""), 2),
                                 -(c.get("utilisation") or 0.0)))
    return ([top] if top is not None else []) + rest


def check_summary(data: dict, out_dir, console: Console, hint: str | None = None) -> None:
    """Print the checks, what the run found (failed analyses, missing records), the verdict and its
    reason, after a FAIL the ``hint`` (:func:`rockdesign.design_space.hint.design_hint`: the parameter that
    governs and the ``rockdesign design`` command that varies it), and where the report went (``out_dir``;
    None: not yet, the caller says it).  Reads the sections every kind's results.json has (``project``,
    ``checks``, ``verdict``) and, where present, the summary of the records analysed."""
    s = data.get("summary")
    table = Table(title=escape(f"{data['project']['name']} — design check"), title_justify="left")
    for col in ("check", RATIO_HEADING, "result"):
        table.add_column(col, justify="right" if col == RATIO_HEADING else "left")
    for c in check_order(data["checks"], data.get("governing_check")):
        role = c.get("role", "governs" if c["governs_verdict"] else "")
        if not c.get("evaluated", True):
            res = "not evaluated"
        elif role in ("governs", "robustness"):
            res = ("PASS" if c["passed"] else "FAIL") + (" (robustness)" if role == "robustness" else "")
        elif "?" in c["name"]:     # a question ("Does a planar analysis suffice?"): answered yes or no
            res = ("yes" if c["passed"] else "no") + " (info)"
        else:       # informs, does not decide: not a failure of the design
            res = ("met" if c["passed"] else "not met") + " (info)"
        table.add_row(escape(readable_units(c["name"])), utilisation_text(c["utilisation"]), res)
    console.print(table)
    exc = data.get("excitation", {})
    for m in exc.get("missing", []):
        console.print(f"[yellow]warning:[/] record {escape(m['id'])} not analysed: {escape(str(m['reason']))}",
                      highlight=False)
    for w in exc.get("record_warnings", []):
        console.print(f"[yellow]warning:[/] {escape(w)}", highlight=False)
    for f in data.get("failed_records", []):
        console.print(f"[bold red]analysis failed:[/] {escape(f['id'])} — {escape(f['status'])} (not counted as "
                      "safe)", highlight=False)
    if s is not None:
        _suite_line(data, s, exc, console)
    if exc.get("intensity_analysed"):
        console.print(f"intensity analysed: {escape(readable_units(exc['intensity_analysed']))}", highlight=False)
    colour = "green" if data["verdict"] == "PASS" and data.get("verdict_robust", True) else (
        "yellow" if data["verdict"] in ("PASS", "NOT DECIDED") else "red")
    reason = readable_units(data.get('verdict_reason') or data['verdict'])
    console.print(f"verdict: [bold {colour}]{escape(reason)}[/]", highlight=False)
    flip = (data.get("acceptance") or {}).get("flip") or {}
    if flip.get("value") is not None:
        console.print(f"distance to the flip: λ = {'≥ ' if flip.get('lower_bound') else ''}{flip['value']:.3g} × the "
                      f"design intensity ({flip.get('governing')}; > 1 passes)", highlight=False, soft_wrap=True)
    if hint:
        console.print(f"next: {escape(hint)}", highlight=False, soft_wrap=True)
    if out_dir is not None:
        console.print(f"output: {escape(str(out_dir))}", highlight=False)


def _suite_line(data: dict, s: dict, exc: dict, console: Console) -> None:
    """The line of what the suite found: model, records, overturned, P(overturn)."""
    prob = "P(overturn) not estimated"
    if s["n_records"]:
        ci = s["p_overturn_ci90"]
        prob = f"P(overturn) = {s['p_overturn']:.3f}, 90 % interval [{ci[0]:.3f}, {ci[1]:.3f}]"
    console.print(f"model: {escape(data['model']['chosen'])} — records analysed: {s['n_records']}"
                  + (f" (+{s.get('n_failed')} failed)" if s.get("n_failed") else "")
                  + (f", missing: {len(exc.get('missing', []))}" if exc.get("missing") else "")
                  + (f" from {s['n_ground_motions']} ground motions" if s.get("n_ground_motions") else "")
                  + f", overturned: {s['n_overturned']} ({s['overturn_criterion']} criterion)"
                  + (f", false negatives (class b): {s['n_false_negative']}" if "n_false_negative" in s else "")
                  + f", {prob}", highlight=False)


def verdict_words(cell: dict) -> str:
    """A design-grid cell's words (design.json ``cells``): "PASS (robust)", "PASS (not robust: fails in k of n draws)", "FAIL", …, or
    "not analysed" (no verdict word)."""
    if not cell.get("analysed", True):
        return "not analysed"
    if cell.get("verdict") == "PASS" and cell.get("robust") is not None:
        if cell["robust"]:
            return "PASS (robust)"
        d = cell.get("draws") or {}
        if d.get("failed"):
            return f"PASS (not robust: fails in {d['failed']} of {d['n']} draws)"
        return "PASS (not robust: margin at its requirement)" if d.get("n") == 0 and cell.get("acmr") else \
            "PASS (not robust)"
    return cell.get("verdict") or "not analysed"
