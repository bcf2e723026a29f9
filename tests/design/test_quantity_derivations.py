"""Every design quantity carries its formula, the formula with the numbers substituted and its value,
computed where the value is computed (the report only renders them; it adds where λ came from).

The c_r and p̂ substitutions are evaluated as arithmetic here (an independent check that the printed
line gives the printed result), for each restitution variant: measured, flat (CoAM and as printed),
curved, 2DOF podium; the values equal the ones pinned in tests/golden (results.json of each example).
"""
from __future__ import annotations

import dataclasses
import json
import math
import re

import pytest

from rockdesign.planar.design.quantities import design_quantities
from rockdesign.paths import REPO_ROOT
from rockdesign.library import load_project

EXAMPLES = [p for p in sorted((REPO_ROOT / "examples").glob("*.toml"))
            if "[cylinder]" not in p.read_text(encoding="utf-8")]
GOLDEN = REPO_ROOT / "tests" / "golden" / "data" / "check"


def evaluate(substituted: str) -> float:
    """The number a substituted formula of the report evaluates to (5-digit inputs)."""
    text = substituted.replace("−", "-").replace("·", "*").replace(" ", "")
    text = re.sub(r"sin²([0-9.e+-]+?)(?=[/)*]|$)", r"(math.sin(\1)**2)", text)
    text = text.replace(")²", ")**2").replace("√(", "math.sqrt(")
    text = re.sub(r"(\d)\(", r"\1*(", text)
    return eval(text, {"math": math})  # noqa: S307 (our own formula text, arithmetic only)


def variants(system):
    """The restitution variants of an example's system: as given, measured c_r, and for flat
    extensions Eq 3.39 as printed."""
    out = {"as given": system, "measured": dataclasses.replace(system, restitution=0.83)}
    if system.column.extension == "none":   # the same body on flat extensions B' = 1.5 B
        c = system.column
        flat = dataclasses.replace(system, column=dataclasses.replace(
            c, extension="flat", half_width_ext=1.5 * c.half_width, radius=math.inf))
        out["flat extensions"] = flat
        out["Eq 3.39 as printed"] = dataclasses.replace(flat, restitution_rule="thesis-eq-3.39")
    return out


def test_examples_cover_every_restitution_variant():
    """The examples exercise flat, curved and the 2DOF podium (plus measured via the variants)."""
    systems = [load_project(p).system for p in EXAMPLES]
    assert {v.column.extension for s in systems for v in variants(s).values()} >= {"flat", "curved", "none"}
    assert any(s.has_elastic_superstructure for s in systems)
    equations = {design_quantities(v)["c_r"].equation for s in systems for v in variants(s).values()}
    assert {"measured (project file)", "Eq 4.20"} <= equations
    assert any(e.startswith("Eq 3.39 corrected") for e in equations)
    assert any(e.startswith("Eq 3.39 as printed") for e in equations)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_quantity_has_formula_substitution_and_the_results_value(path):
    system = load_project(path).system
    golden = json.loads((GOLDEN / f"{path.stem}.json").read_text(encoding="utf-8"))["quantities"]
    for label, variant in variants(system).items():
        q = design_quantities(variant)
        for name, quantity in q.items():
            assert quantity.formula, f"{path.stem} ({label}): {name} has no formula"
            assert quantity.substituted or name == "lambda", f"{path.stem} ({label}): {name} has no substitution"
            assert math.isfinite(quantity.value) or name == "omega_s_over_p", name
            assert "value" not in quantity.as_json() or quantity.as_json()["value"] == quantity.value
            assert set(quantity.as_json()) == {"value", "unit", "equation"}   # results.json unchanged
        if label == "as given":
            assert set(q) == set(golden)
            for name, quantity in q.items():
                assert quantity.value == golden[name]["value"], name
                assert (quantity.unit, quantity.equation) == (golden[name]["unit"], golden[name]["equation"])
        if label == "measured":
            assert q["c_r"].value == 0.83 and q["c_r"].substituted == "0.83 (project file)"
            continue
        assert evaluate(q["c_r"].substituted) == pytest.approx(q["c_r"].value, rel=2e-4), label
        if "p_hat" in q:
            assert evaluate(q["p_hat"].substituted) == pytest.approx(q["p_hat"].value, rel=2e-4), label


def test_evaluate_is_not_vacuous():
    """The evaluator reads the formulas as written: Housner's block c_r for α = 0.2, λ = 1/3."""
    assert evaluate("(1 − 2·sin²0.2/(1+0.33333))²") == pytest.approx(
        (1 - 2 * math.sin(0.2) ** 2 / (4 / 3)) ** 2, rel=1e-5)
    assert evaluate("√((1+2·0)/(1+0.33333+4·0) · 9.81/2)") == pytest.approx(math.sqrt(9.81 / 2 / (4 / 3)), rel=1e-5)
