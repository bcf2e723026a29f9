"""The calculation report (issue item 5, 9): the PDF renders, contains the sections, and every key number
of results.json appears in it exactly as the report formats it (one formatting function,
rockdesign.report.formatting.fmt, used by the template and by these tests)."""
from __future__ import annotations

import re

import pytest

from rockdesign.report.formatting import fmt
from rockdesign.report.methods import cite

pytestmark = pytest.mark.slow   # full design checks with their PDF reports (session fixtures)

SECTIONS = [
    "Verdict",
    "Basis of design and assumptions",
    "Input",
    "Structure",
    "Design quantities",
    "Pushover curve",
    "Model selection",
    "Ground motions",
    "Suite results",
    "Time histories of the governing records",
    "Overturning margins",
    "Sensitivity to the coefficient of restitution",
    "Summary of checks",
    "Solver settings and verification",
    "Software",
]

RECORD_NUMBERS = ("scale", "pga", "sd_max", "sd_max_period", "polyakov_ratio", "theta_max_over_alpha",
                  "theta_max_over_theta_c", "u_B_max_over_2B", "impacts", "uplift_time", "polyakov_scale",
                  "overturn_scale")
SUMMARY_NUMBERS = ("n_records", "n_overturned", "n_overturned_dynamic", "n_exceeded_capacity", "n_false_negative",
                   "p_overturn", "median_theta_max_over_alpha", "max_polyakov_ratio", "max_theta_max_over_theta_c",
                   "median_margin", "min_margin", "median_polyakov_scale", "n_polyakov_unconservative_margin",
                   "n_margin_above_scan", "n_nonmonotonic")
SETTINGS_NUMBERS = ("rtol", "atol", "g", "rest_velocity", "free_vibration", "linearization_tolerance",
                    "margin_precision", "margin_max_scale", "margin_scan_ratio", "margin_rtol",
                    "rigid_superstructure_ratio")


def key_numbers(data: dict, *, margins: bool):
    """(where, value) of the numbers of results.json the report must show."""
    for name, q in data["quantities"].items():
        yield f"quantities.{name}", q["value"]
    s = data["summary"]
    for k in SUMMARY_NUMBERS:
        if k in s and s[k] is not None and (margins or "margin" not in k and "nonmonotonic" not in k):
            yield f"summary.{k}", s[k]
    yield "summary.p_overturn_ci90[0]", s["p_overturn_ci90"][0]
    yield "summary.p_overturn_ci90[1]", s["p_overturn_ci90"][1]
    for k, n in s["classes"].items():
        yield f"summary.classes.{k}", n
    for c in data["checks"]:
        yield f"checks[{c['name']}].utilisation", c["utilisation"]
    m = data["model"]
    yield "model.max_difference_theta_over_theta_c", m["max_difference_theta_over_theta_c"]
    yield "model.verdict_changes", m["verdict_changes"]
    for v in m["verification"]:
        yield f"model.verification[{v['record']}]", v["theta_max_over_theta_c"]
        yield f"model.verification[{v['record']}].full", v["theta_max_over_theta_c_full"]
        yield f"model.verification[{v['record']}].difference", v["difference"]
    yield "excitation.capacity", data["excitation"]["capacity"]
    for r in data["records"]:
        for k in RECORD_NUMBERS:
            if r.get(k) is not None and (margins or k != "overturn_scale"):
                yield f"records[{r['id']}].{k}", r[k]
    for k in SETTINGS_NUMBERS:
        if k in data["settings"]:
            yield f"settings.{k}", data["settings"][k]
    for key, run in data["sensitivity"]["runs"].items():
        yield f"sensitivity.runs[{key}].restitution_factor", run["restitution_factor"]
        yield f"sensitivity.runs[{key}].n_overturned", run["n_overturned"]
        yield f"sensitivity.runs[{key}].verdict_changes", run["verdict_changes"]
    yield "sensitivity.verdict_flips", data["sensitivity"]["verdict_flips"]


def printed(where: str, value) -> str:
    """How the report prints a number of results.json: a check's demand/limit by the checks table's own
    format (the number of rockdesign.display.utilisation_text, "1.98" of "1.98 × limit"), every other number by
    ``fmt``."""
    from rockdesign.display import utilisation_number
    return utilisation_number(value) if where.startswith("checks[") else fmt(value)


def missing_numbers(written, *, margins: bool) -> list[str]:
    tokens = written.tokens
    return [f"{where} = {value!r} printed as {printed(where, value)!r}"
            for where, value in key_numbers(written.data, margins=margins)
            if printed(where, value) not in tokens]


# ---------------------------------------------------------------------------------------------- podium

def test_podium_pdf_renders(podium_out):
    pdf = podium_out.out / "report.pdf"
    assert pdf.exists() and pdf.stat().st_size > 50_000
    assert pdf.read_bytes()[:5] == b"%PDF-"
    assert podium_out.pages >= 8


@pytest.mark.parametrize("title", SECTIONS)
def test_podium_pdf_has_section(podium_out, title):
    numbered = re.compile(r"\b\d{1,2}\s+" + re.escape(title) + r"\b")
    assert numbered.search(podium_out.flat_text), f"section '{title}' not found in the PDF text"


def test_podium_pdf_title_block(podium_out):
    text = podium_out.flat_text
    data = podium_out.data
    assert data["project"]["name"].split("(")[0].strip() in text
    assert data["project"]["sha256"] in text.replace(" ", "")
    assert data["project"]["tool_version"] in text
    assert data["project"]["kernels_sha256"][:12] in text.replace(" ", "")   # the Software table
    assert data["project"]["engineer"] in text
    assert re.search(r"\b\d{4}-\d{2}-\d{2}\b", text), "no date"
    assert "podium_flat.toml" in text


def test_podium_pdf_verdict_and_criterion(podium_out):
    text = podium_out.flat_text
    data = podium_out.data
    assert data["verdict"] in text
    first_page = podium_out.pdf_text.split("page 1 of")[0]
    assert data["verdict"] in first_page, "the verdict must be on the first page"
    assert "Overturning criterion" in first_page
    crit = data["settings"]["overturn_criterion"]
    assert f'overturn = "{crit}"' in re.sub(r"\s+", " ", first_page)
    assert "dynamic overturning" in re.sub(r"\s+", " ", first_page)
    governing = next(c for c in data["checks"] if c["governs_verdict"])
    assert "(governing)" in text
    assert printed("checks[", governing["utilisation"]) in podium_out.tokens


def test_podium_pdf_numbers_equal_results_json(podium_out):
    missing = missing_numbers(podium_out, margins=False)
    assert not missing, "numbers of results.json missing from the PDF:\n" + "\n".join(missing[:40])


def test_podium_pdf_record_ids_and_classes(podium_out):
    text = podium_out.flat_text
    for r in podium_out.data["records"]:
        assert r["id"] in text, r["id"]


def test_podium_html_contains_every_record_id(podium_out):
    for r in podium_out.data["records"]:
        assert r["id"] in podium_out.html


def test_podium_html_has_svg_figures(podium_out):
    import base64
    import re
    html = podium_out.html
    # drawing, pushover, spectra, scatter, ECDF, margins and one per governing record: every figure is
    # an SVG (as an <img> data URI, which WeasyPrint renders ≈ 3× faster than inline SVG markup)
    n_expected = 6 + len(podium_out.result.histories)
    images = re.findall(r'<img class="figure"[^>]*src="data:([^;]+);base64,([^"]+)"', html)
    assert len(images) >= n_expected
    for mime, data in images:
        assert mime == "image/svg+xml"
        assert base64.b64decode(data).lstrip().startswith(b"<svg")


def test_podium_input_echo_verbatim(podium_out):
    from html import unescape
    source = podium_out.result.project.source_text
    assert source.strip() in unescape(podium_out.html)
    # units exactly as written
    assert 'cap_beam_mass = "290 t"' in podium_out.flat_text.replace("\u00a0", " ")


def test_podium_basis_of_design(podium_out):
    text = podium_out.flat_text
    for phrase in ("Rigid bodies", "No sliding", "conservation of angular momentum", "Planar (2D)",
                   "§8.3.2", "vertical ground acceleration", "soil–structure interaction", "Polyakov's rule 2"):
        assert phrase in text, phrase


def test_podium_design_quantities_formula_substituted_result(podium_out):
    html = podium_out.html
    for name, q in podium_out.data["quantities"].items():
        assert fmt(q["value"]) in html
        equation = cite(q["equation"])          # "docs/model.md §7" is printed as its appendix section
        assert equation.replace("'", "&#39;") in html or equation in html
    # each quantity row shows "= substituted"
    assert html.count('<span class="subst">= ') >= len(podium_out.data["quantities"]) - 1


def test_podium_records_section(podium_out):
    text = podium_out.flat_text
    assert "PEER NGA" in text and "FEMA P695" in text
    assert podium_out.data["excitation"]["intensity_analysed"].split("(")[0].strip() in text
    for r in podium_out.data["records"][:5]:
        assert str(r["rsn"]) in podium_out.tokens


def test_page_one_states_the_ground_motion_scaling_in_one_line(podium_out):
    """Page 1 says how the suite was scaled and that PGA scaling is not ASCE 7-22 §16.2 (one line of the
    verdict box, from results.json ``excitation.scaling``)."""
    from rockdesign.motions.scaling_report import scaling_sentence
    block = podium_out.data["excitation"]["scaling"]
    assert block["standard"] is None and block["method"] == "pga" and block["conformant"] is None
    assert "not ASCE 7-22 §16.2 scaling" in block["note"]
    sentence = podium_out.data["excitation"]["scaling_sentence"]
    assert sentence == scaling_sentence(block, podium_out.data["settings"]["g"])
    assert sentence.startswith("Records scaled to PGA 0.2 g") and "not ASCE 7-22 §16.2 scaling" in sentence
    from rockdesign.report.render import symbols
    assert symbols(sentence) in podium_out.html.split("Basis of design")[0]
    pypdf = pytest.importorskip("pypdf")
    page_one = " ".join(pypdf.PdfReader(str(podium_out.out / "report.pdf")).pages[0].extract_text().split())
    assert "Records scaled to PGA 0.2 g" in page_one and "not ASCE 7-22 §16.2 scaling" in page_one


def test_demand_section_against_the_fixed_base_at_the_damping_given(podium_out):
    """The fixed base is the building at ζ_s = 2 % (not ζ_s/S_r); records with a force ratio above 1 are
    named in results.json and in the report, with the damping-correction sentence (Eq 4.27)."""
    sd = podium_out.data["summary"]["superstructure"]
    assert sd["fixed_base_damping"] == pytest.approx(0.02)
    assert sd["model_damping_before_uplift"] == pytest.approx(0.02 / podium_out.data["quantities"]["S_r"]["value"])
    above = sd["force_ratio_above_one"]
    rows = {r["id"]: r for r in podium_out.data["records"]}
    listed = [rid for rid, r in rows.items() if r["superstructure"] and not r["overturned"]
              and r["superstructure"]["force_ratio"] > 1.0]
    assert above["records"] == listed and above["n_records"] == len(listed)
    assert above["ground_motions"] == list(dict.fromkeys(rows[i]["ground_motion"] for i in listed))
    html = podium_out.html
    assert "What the rocking storey buys.</b>" in html and "(ζ<sub>s</sub> = 2 %)" in html
    assert "damping correction, Eq 4.27" in html
    buys = html.split("What the rocking storey buys.</b>")[1].split("</p>")[0]
    for gm in above["ground_motions"]:
        assert gm in buys
    assert "design_spectrum_acceleration" not in sd        # PGA scaling: no target spectrum is known


def test_podium_solver_and_versions(podium_out):
    text = podium_out.flat_text
    for name in ("python", "numpy", "scipy", "numba", "matplotlib", "weasyprint", "jinja2"):
        assert re.search(rf"\b{name}\b \d", text), name
    assert "closed-form" in text
    assert "impact times" in text
    from rockdesign.planar.report.report import verification_statement
    v = verification_statement(podium_out.result)
    assert v["rtol"] == podium_out.data["settings"]["rtol"]
    for key in ("theta_error", "impact_time_error", "impacts"):
        assert fmt(v[key]) in podium_out.tokens, key


def test_report_leaves_results_json_unchanged(podium_out):
    """Rendering reads the result only: results.json written before equals as_json() afterwards."""
    import json
    again = json.loads(json.dumps(podium_out.result.as_json(), ensure_ascii=False))
    assert again == podium_out.data


# ---------------------------------------------------------------------------------------------- curved

def test_curved_column_renders(curved_out):
    assert (curved_out.out / "report.pdf").exists()
    assert curved_out.pages >= 8
    text = curved_out.flat_text
    assert "generalisation is rockdesign's (Appendix M3)" in text
    assert "u" in text and "(θc)" in text


def test_curved_column_numbers_equal_results_json(curved_out):
    missing = missing_numbers(curved_out, margins=True)
    assert not missing, "numbers of results.json missing from the PDF:\n" + "\n".join(missing[:40])


def test_curved_column_drawing_and_pushover_marks(curved_out):
    q = curved_out.data["quantities"]
    text = curved_out.flat_text
    assert "beta" in q and "theta_c" in q
    # the figure captions state β and θc with the numbers of results.json
    assert f"β = {fmt(q['beta']['value'], 'rad')}" in text
    assert f"θc = {fmt(q['theta_c']['value'], 'rad')}" in text
    assert "true radius r" in text


def test_curved_margins_section(curved_out):
    text = curved_out.flat_text
    assert "Median RHA overturning factor" in text
    assert fmt(curved_out.data["summary"]["min_margin"]) in curved_out.tokens


# ---------------------------------------------------------------------------------------------- default

def test_default_excitation_note(default_out):
    assert default_out.data["excitation"]["default_used"] is True
    html = default_out.html
    assert "Default excitation." in html
    assert "FEMA P695 far-field suite" in html
    assert 'design_pga = &#34;0.2 g&#34;' in html or 'design_pga = "0.2 g"' in html
    assert len(default_out.data["records"]) == 44


def test_no_default_note_with_explicit_suites(podium_out):
    assert podium_out.data["excitation"]["default_used"] is False
    assert "Default excitation." not in podium_out.html


SUITE_COLUMNS = ("scale", "pga", "sd_max", "sd_max_period", "polyakov_ratio", "theta_max_over_alpha",
                 "theta_max_over_theta_c", "u_B_max_over_2B", "impacts", "uplift_time", "overturn_mode", "class",
                 "overturn_scale", "polyakov_scale")


def suite_row(r: dict, theta_c_is_alpha: bool = False) -> str:
    """The suite-table row of one record as the PDF text shows it (without the θ_max/θc column where
    θc = α: it would repeat θ_max/α)."""
    keys = [k for k in SUITE_COLUMNS if not (theta_c_is_alpha and k == "theta_max_over_theta_c")]
    cells = [r["id"]] + [r[k] if isinstance(r[k], str) else fmt(r[k]) for k in keys]
    return " ".join(cells)


@pytest.mark.parametrize("which", ["podium_out", "curved_out"])
def test_suite_table_rows_equal_results_json(which, request):
    """Each record's row of the suite table, cell by cell, is results.json formatted by fmt."""
    written = request.getfixturevalue(which)
    text = written.flat_text
    q = written.data["quantities"]
    same = q["theta_c"]["value"] == q["alpha"]["value"]
    assert same == (which == "podium_out")          # flat columns: θc = α; the curved pier's θc ≠ α
    missing = [suite_row(r, same) for r in written.data["records"] if suite_row(r, same) not in text]
    assert not missing, "rows not found in the PDF:\n" + "\n".join(missing[:10])


def test_html_is_deterministic(curved_out):
    """Same result, same date → byte-identical HTML (no randomness, no timestamps in the figures)."""
    from rockdesign.planar.report.report import render_html
    first = render_html(curved_out.result, date="2000-01-01")
    assert first == render_html(curved_out.result, date="2000-01-01")
    assert "2000-01-01" in first


def test_missing_records_listed_with_reasons(curved_out):
    from dataclasses import replace

    from rockdesign.planar.report.report import render_html
    result = replace(curved_out.result, missing=[("rsn:1602:BOL090", "no AT2 file for RSN 1602 in ~/peer",
                                                  "thesis-table-4.2")])
    html = render_html(result, figures={}, date="2000-01-01")
    assert "Records not found (1)" in html
    assert "rsn:1602:BOL090" in html and "no AT2 file for RSN 1602 in ~/peer" in html
