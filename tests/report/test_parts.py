"""Parts of the report that need no design check: number formatting, formula substitutions, the
verification statement, the drawings and the SVG export."""
from __future__ import annotations

import math

import pytest

from rockdesign.planar.design.quantities import design_quantities
from rockdesign.paths import REPO_ROOT
from rockdesign.library import load_project
from rockdesign.planar.design.substitutions import substitution
from rockdesign.report.context import pretty_exponents
from rockdesign.report.formatting import fmt, number

EXAMPLES = [p for p in sorted((REPO_ROOT / "examples").glob("*.toml"))
            if "[cylinder]" not in p.read_text(encoding="utf-8")]   # planar report parts (cylinders: tests/cylinder)


@pytest.mark.parametrize("value, text", [
    (0.14888994760949725, "0.1489"),
    (0.45, "0.45"),
    (2.943, "2.943"),
    (10.550049563552268, "10.55"),
    (1.0, "1"),
    (9.99996, "10"),
    (123456.7, "123500"),
    (7290804.26, "7.291·10⁶"),
    (1e-10, "1·10⁻¹⁰"),
    (0.000123, "1.23·10⁻⁴"),
    (-0.5, "−0.5"),
    (44, "44"),
    (0, "0"),
    (None, "—"),
    (math.inf, "∞"),
    (True, "yes"),
])
def test_number(value, text):
    assert number(value) == text


def test_fmt_units():
    assert fmt(1.4715, "m/s^2") == "1.472 m/s²"
    assert fmt(0.3333, "-") == "0.3333"
    assert fmt(2.2024654553865433, "1/s") == "2.202 1/s"
    assert fmt(None, "m") == "—"


def test_pretty_exponents():
    assert pretty_exponents("2.9e+05 kg/(36·1518.8 kg)") == "2.9·10⁵ kg/(36·1518.8 kg)"
    assert pretty_exponents("rtol 1e-10") == "rtol 1·10⁻¹⁰"


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_quantity_carries_formula_and_substitution_that_evaluate_to_the_result(path):
    """design_quantities gives every quantity its formula and substituted numbers (the report only
    renders them); where the substitution is written by design/substitutions.py it recomputes the value."""
    project = load_project(path)
    for name, q in design_quantities(project.system).items():
        assert q.formula or name == "k_phase2", name
        assert q.substituted or name == "lambda", f"{path.stem}: {name} has no substituted values"
        formula, substituted, value = substitution(name, q, project.system)
        assert (formula, substituted) == (q.formula, q.substituted), name
        if value is not None:
            assert value == pytest.approx(q.value, rel=1e-12, abs=1e-15), name


def test_verification_statement():
    """The report's statement: the engine against the closed form at the check's tolerance (SPEC §3.8)."""
    from rockdesign.planar.dynamics.accuracy import engine_accuracy
    from rockdesign.planar.report.verification import normalise

    def engine_accuracy_statement(rtol):     # what the check records and the report words
        return normalise({k: v for k, v in engine_accuracy(rtol).items() if k != "seconds"})
    s = engine_accuracy_statement(1e-10)
    for key in ("theta_error", "impact_time_error", "impacts", "impacts_engine", "theta_error_over_alpha", "rtol"):
        assert key in s, key
    assert s["impacts"] == s["impacts_engine"] > 3
    assert s["theta_error"] < 1e-8
    assert s["impact_time_error"] < 1e-9
    assert "seconds" not in s
    loose = engine_accuracy_statement(1e-6)
    assert loose["theta_error"] > s["theta_error"]


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_structure_drawing_svg(path):
    from rockdesign.planar.report.drawing import structure_drawing
    from rockdesign.report.svg import svg
    project = load_project(path)
    text = svg(structure_drawing(project.system), "d")
    assert text.startswith("<svg")
    assert "<dc:date>" not in text
    assert 'id="d-' in text and 'id="' + "DejaVu" not in text


def test_curved_extension_outline_is_true_arc():
    """The drawn extension lies on the circle of radius r tangent to the ground at x = B, ends at B'."""
    from rockdesign.planar.design.geometry import rocking_geometry
    from rockdesign.planar.report.drawing import extension_outline
    project = load_project(REPO_ROOT / "examples" / "bridge_pier.toml")
    c = project.system.column
    geo = rocking_geometry(c)
    pts = extension_outline(c, 1.0, n=50)[:50]
    dist = ((pts[:, 0] - c.half_width) ** 2 + (pts[:, 1] - geo.radius) ** 2) ** 0.5
    assert dist == pytest.approx(geo.radius, rel=1e-12)
    assert pts[-1, 0] == pytest.approx(c.half_width_ext, rel=1e-12)
    assert pts[-1, 1] == pytest.approx(geo.radius * (1 - math.cos(geo.beta)), rel=1e-12)


def test_svg_is_deterministic():
    from rockdesign.planar.report.drawing import structure_drawing
    from rockdesign.report.svg import svg
    system = load_project(REPO_ROOT / "examples" / "podium_curved.toml").system
    assert svg(structure_drawing(system), "a") == svg(structure_drawing(system), "a")


def test_slim_svg_draws_the_same_pdf():
    """slim_svg (style declarations as presentation attributes, no metadata, matplotlib's ``*`` rule on
    the root) changes nothing WeasyPrint draws: the PDF drawing operators of the figure are identical."""
    from weasyprint import HTML
    from rockdesign.planar.report.drawing import structure_drawing
    from rockdesign.report import svg as figures
    from rockdesign.report.render import svg_image
    system = load_project(REPO_ROOT / "examples" / "podium_curved.toml").system
    slim = figures.svg(structure_drawing(system), "a")
    original = figures.slim_svg
    try:
        figures.slim_svg = lambda text: text
        fat = figures.svg(structure_drawing(system), "a")
    finally:
        figures.slim_svg = original
    assert " style=\"" in fat and "<metadata>" in fat and "*{stroke-linejoin" in fat
    assert " style=\"" not in slim and "<metadata>" not in slim and "<style" not in slim
    assert len(slim) < len(fat)

    def drawing(text):
        raw = HTML(string=f"<html><body>{svg_image(text)}</body></html>").write_pdf(uncompressed_pdf=True)
        # text lines of the PDF (drawing operators, objects), without dates, ids and binary font data
        return [ln for ln in raw.split(b"\n") if all(32 <= c < 127 for c in ln)
                and b"CreationDate" not in ln and b"/ID" not in ln]

    ops = drawing(fat)
    assert len(ops) > 1000
    assert drawing(slim) == ops


def test_symbols_subscripts():
    from rockdesign.report.render import symbols
    assert symbols("SD_max < u_B(θc)") == "SD<sub>max</sub> &lt; u<sub>B</sub>(θc)"
    assert symbols("u_B,max/2B") == "u<sub>B,max</sub>/2B"
    assert symbols("project input (mass_distribution)") == "project input (mass_distribution)"
    assert symbols(None) == ""


@pytest.mark.parametrize("example", ["podium_flat.toml", "podium_curved.toml"])
def test_the_width_label_of_the_podium_drawing_overlaps_no_column(example):
    """The structure drawing's "2B = 0.45 m" label was centred on a slender column and overlapped it."""
    from matplotlib.patches import Rectangle

    import rockdesign as rd
    from rockdesign.paths import REPO_ROOT
    from rockdesign.planar.report.drawing import structure_drawing
    project = rd.load_project(REPO_ROOT / "examples" / example)
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    fig = structure_drawing(project.system)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    ax = fig.axes[0]
    label = next(t for t in ax.texts if t.get_text().startswith("2B ="))
    box = label.get_window_extent(renderer)
    shafts = [p.get_window_extent(renderer) for p in ax.patches if isinstance(p, Rectangle)
              and abs(p.get_width() - project.system.column.half_width * 2) < 1e-9]
    assert shafts, "no column drawn"
    assert not any(box.overlaps(s) for s in shafts), (box, shafts)


def test_the_demand_figures_legend_hides_no_marker():
    """The legend of the superstructure-demand figure sat on two of its markers."""
    from types import SimpleNamespace

    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from rockdesign.planar.report.demand_figures import demand_figure
    rng = np.random.default_rng(1)
    records = [SimpleNamespace(id=f"p695-ff/{k}a", run=SimpleNamespace(overturned=False),
                               superstructure={"shear_coefficient_max": float(s), "fixed_base_acceleration_max": float(f)})
               for k, (s, f) in enumerate(zip(rng.uniform(0.3, 0.62, 22), rng.uniform(3.0, 6.1, 22)), 1)]
    records[-1].superstructure["shear_coefficient_max"] = 0.62      # top right, where the legend used to sit
    result = SimpleNamespace(records=records, project=SimpleNamespace(system=SimpleNamespace(g=9.81)),
                             statistics={"superstructure": {"uplift_base_shear_coefficient": 0.15}})
    fig = demand_figure(result)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    ax = fig.axes[0]
    legend = ax.get_legend().get_window_extent(renderer)
    points = np.vstack([ax.transData.transform(np.column_stack(line.get_data())) for line in ax.get_lines()
                        if line.get_marker() not in (None, "None", "")])
    inside = [p for p in points if legend.x0 <= p[0] <= legend.x1 and legend.y0 <= p[1] <= legend.y1]
    assert len(points) == 44 and not inside, inside
