"""The report renders what the library computed: the reports' context and figure modules import no
physics (design, dynamics, motions, checks) — only names that describe results (types, labels).

Imports are read with ast, including those inside functions.
"""
from __future__ import annotations

import ast

import pytest

from rockdesign.paths import REPO_ROOT

PHYSICS = ("rockdesign.planar.design", "rockdesign.planar.dynamics", "rockdesign.planar.checks", "rockdesign.planar.spectra",
           "rockdesign.motions", "rockdesign.acceptance", "rockdesign.cylinder.engine", "rockdesign.cylinder.kernel",
           "rockdesign.cylinder.eom", "rockdesign.cylinder.check", "rockdesign.cylinder.quantities",
           "rockdesign.cylinder.spectrum", "rockdesign.cylinder.margins", "rockdesign.cylinder.ensemble")
"""The modules that compute: engines, closed-form quantities, spectra, the checks (docs/architecture.md, "Rules that
follow from the layers")."""

ALLOWED = {
    ("rockdesign.planar.checks.polyakov", "CLASSES"),          # the names of the Fig 4.9 classes (labels)
    ("rockdesign.planar.checks.polyakov", "CLASS_MEANING"),    # their meaning (legend text)
    ("rockdesign.cylinder.engine", "SPIN_TILT_MIN"),           # where the spin is reported (a label)
    ("rockdesign.cylinder.check", "CSV_COLUMNS"),              # the column names of results.csv
    ("rockdesign.cylinder.check", "governing_ids"),            # which pairs' histories results.json holds
    ("rockdesign.acceptance.flip", "FAR"),                     # the design chart's "far from the flip" level (a constant)
    ("rockdesign.acceptance.rule", "first_overturn_scale"),    # which of a record's stored factors is its first
    ("rockdesign.planar.design.geometry", "rocking_geometry"),  # the drawing's shape of the extensions (r, β): the
                                                               # structure as drawn to scale, not a response
}
"""Names that the report may take from the physics layers: labels and shapes, not computations.  The figure data
(the pushover curve, the elastic spectra, the wobbling curve, the cylinder's quantities) is computed by the check
and kept on its result (``result.figure_data``, ``result.quantities``)."""

REPORT_MODULES = sorted(
    [str(p.relative_to(REPO_ROOT / "rockdesign")) for p in (REPO_ROOT / "rockdesign" / "planar" / "report").glob("*.py")]
    + [str(p.relative_to(REPO_ROOT / "rockdesign")) for p in (REPO_ROOT / "rockdesign" / "report").glob("*.py")]
    + ["cylinder/report.py", "cylinder/figures.py", "cylinder/methods.py"])
"""Every module of the report layer (docs/architecture.md): the shared report/, the planar report/ and the cylinder's
report modules."""


def physics_imports(path, package: str = "rockdesign.planar.report") -> set[tuple[str, str]]:
    """(module, name) of every import of ``path`` (a module of ``package``) from the physics layers (relative
    imports resolved)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(parts + ([base] if base else []))
            if base.startswith(PHYSICS):
                found |= {(base, alias.name) for alias in node.names}
        elif isinstance(node, ast.Import):
            found |= {(alias.name, "*") for alias in node.names if alias.name.startswith(PHYSICS)}
    return found


def test_physics_imports_resolves_relative_imports(tmp_path):
    """The reader sees relative, absolute and in-function imports (the test below is not vacuous)."""
    probe = tmp_path / "probe.py"
    probe.write_text("from ..design.quantities import design_quantities\nimport rockdesign.planar.dynamics.engine\n"
                     "def f():\n    from ..checks import criteria\n", encoding="utf-8")
    assert physics_imports(probe) == {("rockdesign.planar.design.quantities", "design_quantities"),
                                      ("rockdesign.planar.dynamics.engine", "*"), ("rockdesign.planar.checks", "criteria")}


@pytest.mark.parametrize("name", REPORT_MODULES)
def test_report_module_imports_no_physics(name):
    package = "rockdesign." + name.rpartition("/")[0].replace("/", ".")
    found = physics_imports(REPO_ROOT / "rockdesign" / name, package)
    assert found - ALLOWED == set(), f"{name} computes instead of rendering"


def test_every_report_module_is_read():
    assert {"planar/report/figures.py", "planar/report/drawing.py", "cylinder/report.py", "cylinder/figures.py",
            "report/document.py", "report/results.py"} <= set(REPORT_MODULES)
