"""The design chart's figures, laid out by matplotlib and read back (tests/report/figure_layout.py): no two texts
collide, no legend or note sits on the data, nothing is cut off, and every variant of the thesis-plane chart has
a mark of its own.

Drawn from a synthetic design.json of the shape ``rockdesign design`` writes (no analysis): a 10 × 10 grid of
a podium's curvature (x, whose four-digit values printed "0.33330.3667" as ticks) and column width (y), with
a FAIL band, fragile and robust PASS cells, cells left unanalysed, an ACMR field whose contour labels fell on the
cell values, and two FAIL cells of one width (one tan α) whose θc is capped at the same value — drawn as one dot.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from figure_layout import draw, layout_problems, marker_centres
from rockdesign.planar.kind import Planar
from rockdesign.report.design_figures import design_figures
from rockdesign.report.design_results import presentation

CURVATURES = [0.2 + k * (0.5 - 0.2) / 9 for k in range(10)]
WIDTHS = [0.36 + k * (0.60 - 0.36) / 9 for k in range(10)]
HEIGHT = 3.0


def _cell(i: int, j: int, rng) -> dict:
    rho, width = CURVATURES[i], WIDTHS[j]
    tan_alpha = width / HEIGHT
    theta_c = min(math.atan(tan_alpha / (1 - 2 * rho * 0.9)), 0.2)       # capped: equal θc at large ρ
    acmr = 1.2 + 4.0 * (width - 0.36) + 0.6 * rho + rng.normal(0.0, 0.05)
    fail = width < 0.40 or (j == 1 and i >= 8)          # the last two curvatures of one width: one θc, two FAILs
    cell = {"index": [i, j], "values": {"podium.curvature": rho, "podium.width": width},
            "labels": {"podium.curvature": f"{rho:.4g}", "podium.width": f"{width:.4g} m"},
            "verdict": "FAIL" if fail else "PASS", "analysed": True, "acceptance": "asce7",
            "n_unacceptable": 3 if fail else int(rng.integers(0, 2)), "allowed_unacceptable": 1, "n_ground_motions": 22,
            "acmr": None if fail else acmr, "acmr_required": None if fail else 1.96,
            "p_collapse_design": None if fail else 0.05, "superstructure_shear_p84": None if fail else 0.45 + 0.2 * width,
            "superstructure_drift_p84": None if fail else 0.018, "median_theta_max_over_theta_c": 0.1 + 0.05 * rho,
            "uplift_shear_coefficient": tan_alpha, "uplift_acceleration": 9.81 * tan_alpha, "theta_c": theta_c,
            "column_material": 40000.0 * width, "robust": None, "draws": {"n": 0, "failed": 0}}
    cell["flip_margin"] = 0.8 + 0.15 * rng.random() if fail else min(acmr / 1.96, 1.1 + 0.05 * rho + rng.random() / 4)
    if not fail:
        fragile = (i + j) % 7 == 0
        cell.update(robust=not fragile, draws={"n": 10, "failed": 1 if fragile else 0})
    if 3 <= i <= 6 and 5 <= j <= 8 and (i + j) % 2:       # left between agreeing neighbours
        cell.update(analysed=False, verdict=None, robust=None, acmr=None, acmr_required=None, flip_margin=None)
    return cell


def chart_data() -> dict:
    """A design.json of a 10 × 10 grid (see the module docstring)."""
    rng = np.random.default_rng(7)
    cells = [_cell(i, j, rng) for i in range(len(CURVATURES)) for j in range(len(WIDTHS))]
    best = next(c for c in cells if c["index"] == [4, 4])
    return {"project": {"name": "synthetic podium", "file": "podium.toml", "sha256": "0" * 64, "kind": "podium"},
            "variables": [{"key": "podium.curvature", "unit": "1", "values": CURVATURES, "values_si": CURVATURES},
                          {"key": "podium.width", "unit": "m", "values": WIDTHS, "values_si": WIDTHS}],
            "cells": cells, "recommended": {"index": best["index"], "values": best["values"], "labels": best["labels"],
                                            "robust": True, "reason": "robust PASS"},
            "analyses_run": 1000, "analyses_saved": 100, "settings": {}, **presentation(Planar())}


def test_the_data_reproduce_what_the_chart_drew_wrong():
    """The synthetic grid holds the cases: four-digit values one tick apart, and two FAIL cells at one point."""
    assert f"{CURVATURES[4]:.4g}" == "0.3333" and f"{CURVATURES[5]:.4g}" == "0.3667"
    fails = [c for c in chart_data()["cells"] if c["index"][1] == 1 and c["index"][0] >= 8]
    assert {c["verdict"] for c in fails} == {"FAIL"}
    assert len({(c["uplift_shear_coefficient"], c["theta_c"]) for c in fails}) == 1


@pytest.mark.parametrize("name", ["verdict", "acmr", "flip", "shear", "rotation", "thesis_plane"])
def test_no_text_collides_covers_the_data_or_is_cut_off(name):
    fig = design_figures(chart_data())[name]
    assert fig is not None
    assert layout_problems(fig) == []


@pytest.mark.parametrize("transpose", [False, True])
def test_the_charts_of_a_one_by_n_and_a_three_by_three_grid_are_clean(transpose):
    """Small grids (the README's 3 × 3 design run) and one variable keep their texts apart too."""
    data = chart_data()
    keep = {0, 4, 9}
    data["cells"] = [c for c in data["cells"] if c["index"][0] in keep and c["index"][1] in keep]
    for c in data["cells"]:
        c["index"] = [sorted(keep).index(c["index"][0]), sorted(keep).index(c["index"][1])]
    for v in data["variables"]:
        v["values"] = [v["values"][k] for k in sorted(keep)]
    data["recommended"]["index"] = [1, 1]
    if transpose:
        data["variables"] = data["variables"][:1]
        data["cells"] = [dict(c, index=[c["index"][0]]) for c in data["cells"] if c["index"][1] == 2]
        data["recommended"]["index"] = [1]
    for name, fig in design_figures(data).items():
        if fig is not None:
            assert layout_problems(fig) == [], name


def test_every_variant_of_the_thesis_plane_has_a_mark_of_its_own():
    """Variants at one (tan α, θc) — equal width, θc capped — are drawn side by side, not as one dot."""
    data = chart_data()
    fig = design_figures(data)["thesis_plane"]
    draw(fig)
    ax = fig.axes[0]
    points = [(p, r) for p, r in marker_centres(ax)]
    centres = np.vstack([p for p, _ in points])
    radius = max(r for _, r in points)
    analysed = [c for c in data["cells"] if c.get("analysed", True)]
    assert len(centres) >= len(analysed)
    distance = np.hypot(*(centres[:, None, :] - centres[None, :, :]).transpose(2, 0, 1))
    np.fill_diagonal(distance, np.inf)
    assert distance.min() >= radius, "two variants share one mark"


@pytest.mark.slow       # the design report to PDF (≈ 14–30 s)
def test_the_design_report_keeps_headers_whole_and_captions_with_their_figures(tmp_path):
    """design.pdf of the 10 × 10 chart: no header broken inside a word ("podium.widt|h"), no caption on a page
    without its figure (Figure 5's caption stood alone on a blank page), no heading left at a page foot, and the
    stylesheet applied (it was escaped: a serif font and no page numbers)."""
    from types import SimpleNamespace

    from page_layout import broken_headers, captions_apart, pages_text, stranded_headings
    from rockdesign.report.design_report import write_design_report
    written = write_design_report(SimpleNamespace(project=SimpleNamespace(name="synthetic podium")), chart_data(),
                                  tmp_path, pdf=True)
    html = written["html"].read_text(encoding="utf-8")
    assert "&#34;DejaVu Sans&#34;" not in html and '"DejaVu Sans"' in html
    assert broken_headers(html, written["pdf"]) == []
    assert captions_apart(html, written["pdf"]) == []
    assert stranded_headings(html, written["pdf"]) == []
    pages = pages_text(written["pdf"])
    assert all(f"page {k} of {len(pages)}" in text for k, text in enumerate(pages, 1))
