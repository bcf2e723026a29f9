"""`rockdesign init` offers ASCE 7-22 §16.2 scaling (issue 50: the templates listed factor | pga | sdmax | uplift |
spectrum only): the podium and column templates name `asce7-22` and carry a worked example that loads as written;
the cylinder's says plainly that its pairs are not §16.2-scaled."""
from __future__ import annotations

import re

import pytest

import rockdesign as rd
from rockdesign.templates import template_text


def with_asce7_22(text: str) -> str:
    """The template with its worked ASCE 7-22 example switched on, as its comment says: the example's scale line
    uncommented, the design_pga and the pga scale line deleted."""
    example = re.search(r"^# (scale = \{ method = \"asce7-22\".*?\})", text, flags=re.M).group(1)
    lines = [line for line in text.splitlines()
             if not line.startswith("design_pga") and not line.startswith('scale = { method = "pga"')]
    return "\n".join(lines).replace('suites = ["p695-farfield"]', 'suites = ["p695-farfield"]\n' + example, 1)


@pytest.mark.parametrize("kind", ["podium", "column"])
def test_the_template_offers_asce7_22_with_an_example_that_loads(kind):
    text = template_text(kind)
    assert "| asce7-22" in text and "examples/podium_asce7_22.toml" in text
    project = rd.parse_project(with_asce7_22(text), name=f"{kind}.toml")
    rule = project.excitation.scale
    assert rule.method == "asce7-22"


def test_the_cylinder_template_says_its_pairs_are_not_16_2_scaled():
    assert "neither is ASCE 7-22 §16.2 scaling" in template_text("cylinder")


def test_the_project_file_reference_lists_asce7_22_with_a_worked_example():
    from rockdesign.paths import REPO_ROOT
    row = next(line for line in (REPO_ROOT / "docs" / "project-file.md").read_text().splitlines()
               if line.startswith("| `scale` |"))
    assert '"asce7-22"' in row and 'scale = { method = "asce7-22", SMS = "0.30 g"' in row
