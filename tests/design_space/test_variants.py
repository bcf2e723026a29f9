"""``--vary`` parsing and the variants' project documents (rockdesign/design_space/variants.py)."""
from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from rockdesign.design_space.variants import parse_vary as parse_vary_of
from rockdesign.design_space.variants import variant_document, variant_toml, variants
from rockdesign.errors import RockdesignError
from rockdesign.kinds import parse_document as parse_project

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def parse_vary(spec, raw, **kw):
    """``--vary`` of a planar project, with the planar kind's alternative keys (radius/curvature, …)."""
    from rockdesign.planar.kind import Planar
    return parse_vary_of(spec, raw, alternatives=Planar.key_alternatives, **kw)


@pytest.fixture(scope="module")
def curved():
    return tomllib.loads((EXAMPLES / "podium_curved.toml").read_text(encoding="utf-8"))


def test_values_in_the_users_units_and_si(curved):
    v = parse_vary("podium.width=36cm:0.60m:7", curved)
    assert v.key == "podium.width" and v.unit == "m"
    assert v.values == pytest.approx([0.36, 0.40, 0.44, 0.48, 0.52, 0.56, 0.60], abs=1e-12)
    assert v.si == pytest.approx(v.values)
    t = parse_vary("superstructure.period=200ms:600ms:3", curved)
    assert t.values == pytest.approx([200, 400, 600]) and t.si == pytest.approx([0.2, 0.4, 0.6])
    assert t.toml_value(1) == "400 ms"


def test_integer_key_takes_whole_numbers(curved):
    v = parse_vary("podium.columns=6:10:3", curved)
    assert v.integer and [v.toml_value(k) for k in range(3)] == [6, 8, 10]
    with pytest.raises(RockdesignError, match="whole numbers"):
        parse_vary("podium.columns=6:10:4", curved)


@pytest.mark.parametrize("spec, message", [
    ("podium.width", "cannot read the variable"),
    ("column.width=0.3m:0.5m:3", "no such table"),
    ("analysis.model=1:2:2", "not a numeric key"),
    ("podium.width=0.3m:2s:3", "different dimensions"),
    ("podium.width=0.3m:0.5m:0", "out of range"),
])
def test_bad_vary_is_an_input_error_naming_the_option(curved, spec, message):
    with pytest.raises(RockdesignError, match=message) as info:
        parse_vary(spec, curved)
    assert "key 'vary'" in str(info.value)            # the library's parameter (the CLI says --vary)


def test_wrong_unit_for_the_key_is_an_input_error_not_an_invalid_cell(curved):
    v = parse_vary("podium.width=1s:2s:2", curved)
    with pytest.raises(RockdesignError, match="do not fit the key"):
        variants(curved, [v], file="p.toml")


def test_radius_replaces_curvature_and_the_loader_sees_the_value(curved):
    v = parse_vary("podium.radius=1m:6m:6", curved)
    doc, notes = variant_document(curved, [v], (2,))
    assert notes == ["podium.radius replaces podium.curvature"]
    assert "curvature" not in doc["podium"] and "curvature" in curved["podium"]     # the base is untouched
    proj = parse_project(doc, file="v.toml")
    assert proj.system.column.radius == pytest.approx(3.0)


def test_impossible_variant_is_an_invalid_cell_with_the_loaders_message(curved):
    w = parse_vary("podium.width=0.36m:0.60m:7", curved)     # 0.60 m = the extended width: no extension left
    cells = variants(curved, [w], file="p.toml")
    assert [c.invalid is None for c in cells] == [True] * 6 + [False]
    assert "extended_width" in cells[-1].invalid and cells[-1].project is None


def test_variant_toml_is_the_same_document(curved):
    """The variant's project file (what ``rockdesign check`` of that variant reads) parses back to the document."""
    v = parse_vary("podium.width=0.40m:0.50m:2", curved)
    doc, _ = variant_document(curved, [v], (1,))
    text = variant_toml(doc)
    assert tomllib.loads(text) == doc
    assert parse_project(tomllib.loads(text), file="v.toml").system.column.half_width == pytest.approx(0.25)


def test_percent_and_degrees_keep_their_units(curved):
    """superstructure.damping=0.5%:1%:2 ran ζ = 0.5 (50 %) and marked 1 INVALID."""
    v = parse_vary("superstructure.damping=0.5%:1%:2", curved)
    assert v.unit == "%" and v.values == (0.5, 1.0) and v.si == pytest.approx((0.005, 0.01))
    assert [v.toml_value(k) for k in range(2)] == [0.005, 0.01] and v.label(0) == "0.5 %"
    cells = variants(curved, [v], file="p.toml")
    assert [c.project.system.superstructure.damping for c in cells] == pytest.approx([0.005, 0.01])
    plain = parse_vary("superstructure.damping=0.005:0.01:2", curved)        # the same grid as plain numbers
    assert plain.si == pytest.approx(v.si)
    from_only = parse_vary("superstructure.damping=0.5:1%:2", curved)         # FROM takes TO's unit
    assert from_only.si == pytest.approx(v.si)
