"""Project files (CONTRACT §1): every alternative form works, every error class is caught cleanly
through the CLI (message names file, key, expected and found; exit code 2; no traceback)."""
from __future__ import annotations

import json
import math
import textwrap

import pytest

from casedata import expected
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.library import load_project

runner = CliRunner()

BASE_COLUMN = """
[project]
name = "test column"

[column]
height = "3.0 m"
width = "0.3 m"
mass = "1.5 t"
mass_distribution = 0.3333
"""


def write(tmp_path, text, name="p.toml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return p


def run_error(path):
    result = runner.invoke(app, ["quantities", str(path)])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    return result.output


def test_alternative_geometry_inputs_agree(tmp_path):
    a = load_project(write(tmp_path, BASE_COLUMN, "a.toml")).system.column
    b = load_project(write(tmp_path, BASE_COLUMN.replace('height = "3.0 m"', 'half_height = "1500 mm"')
                           .replace('width = "0.3 m"', "slenderness = 0.1"), "b.toml")).system.column
    assert a.half_height == b.half_height == 1.5
    assert a.half_width == pytest.approx(b.half_width, rel=1e-15)


def test_radius_and_curvature_are_equivalent(tmp_path):
    base = BASE_COLUMN + 'extended_width = "0.6 m"\n'
    a = load_project(write(tmp_path, base + 'radius = "0.75 m"\n', "a.toml")).system.column
    b = load_project(write(tmp_path, base + "curvature = 0.25\n", "b.toml")).system.column
    assert a.extension == b.extension == "curved"
    assert a.radius == pytest.approx(b.radius, rel=1e-15)
    c = load_project(write(tmp_path, base, "c.toml")).system.column
    assert c.extension == "flat" and c.half_width_ext == 0.3


def test_mass_from_density_and_lambda_from_end_plates(tmp_path):
    text = BASE_COLUMN.replace('mass = "1.5 t"', 'density = "2.5 t/m^3"\ndepth = "0.3 m"').replace(
        "mass_distribution = 0.3333", 'end_plate_thickness = "0.06 m"')
    col = load_project(write(tmp_path, text)).system.column
    # Table 3.1 (b), tan α = 0.1, d_s/2H = 0.02: λ = 0.385 (ρ_steel = 3.25 ρ_concrete)
    assert col.mass_distribution == pytest.approx(0.385, abs=5e-4)
    # m = ρ A (2H − 2d_s) + 3.25 ρ A 2 d_s
    assert col.mass == pytest.approx(2500 * 0.09 * (3.0 - 0.12) + 3.25 * 2500 * 0.09 * 0.12, rel=1e-12)


def test_lambda_table_3_1_and_figure_3_6():
    from rockdesign.planar.design.mass import composite_column
    # Table 3.1 (b): rectangles 0.385/0.383 (d_s/2H = 0.02), 0.422/0.420 (0.04) for tan α = 0.1/0.2
    for tan_a, ds, lam in ((0.1, 0.02, 0.385), (0.2, 0.02, 0.383), (0.1, 0.04, 0.422), (0.2, 0.04, 0.420)):
        assert composite_column("rectangular", tan_a, 1.0, ds * 2.0)[0] == pytest.approx(lam, abs=6e-4)
    # uniform: 1/3 (rectangle, Eq 3.4), 0.333/0.330 cylinder; Fig 3.6: λ_max ≈ 0.49 at d_s = 0.30H
    assert composite_column("rectangular", 0.1, 1.0, 0.0)[0] == pytest.approx(1 / 3, abs=1e-12)
    assert composite_column("circular", 0.2, 1.0, 0.0)[0] == pytest.approx(0.330, abs=5e-4)
    for section in ("rectangular", "circular"):
        assert composite_column(section, 0.1, 1.0, 0.30)[0] == pytest.approx(0.49, abs=5e-3)


def test_podium_with_superstructure(tmp_path):
    proj = load_project("examples/podium_flat.toml")
    s = proj.system
    assert s.kind == "podium" and s.n_columns == 36
    assert s.superstructure.omega_s == pytest.approx(2 * math.pi / 0.38)
    assert s.superstructure.damping == pytest.approx(0.02)
    assert proj.sha256 and len(proj.sha256) == 64


@pytest.mark.parametrize("example", ["podium_flat", "podium_curved", "podium_asce7_22", "bridge_pier",
                                     "shake_table_F02"])
def test_examples_load_and_print_quantities(example):
    result = runner.invoke(app, ["quantities", f"examples/{example}.toml", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert {"alpha", "R", "p", "lambda", "c_r", "theta_c", "u_capacity"} <= set(data["quantities"])
    for q in data["quantities"].values():
        assert set(q) == {"value", "unit", "equation"}


def test_quantities_table_and_display_units():
    result = runner.invoke(app, ["quantities", "examples/bridge_pier.toml", "--units", "mm,deg"])
    assert result.exit_code == 0, result.output
    assert "deg" in result.output and "mm" in result.output


def test_f02_example_reproduces_table_6_5():
    data = json.loads(runner.invoke(app, ["quantities", "examples/shake_table_F02.toml", "--json"]).output)
    assert data["quantities"]["beta"]["value"] == pytest.approx(expected("tab6.5_F02")[0], abs=5e-4)
    assert data["quantities"]["theta_c"]["value"] == pytest.approx(expected("tab6.5_F02")[1], abs=5e-4)


# ------------------------------------------------------------------------------------ errors
def test_unknown_key_suggests_nearest(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN + 'hieght = "3 m"\n'))
    assert "column.hieght" in out and "height" in out and "p.toml" in out


def test_wrong_dimension(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN.replace('height = "3.0 m"', 'height = "3 kg"')))
    assert "column.height" in out and "length" in out and "3 kg" in out and "mass" in out


def test_plain_number_for_dimensional_key(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN.replace('height = "3.0 m"', "height = 3.0")))
    assert "column.height" in out and "units" in out


def test_missing_required_value(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN.replace('mass = "1.5 t"\n', "")))
    assert "column.mass" in out and "missing" in out


def test_missing_project_name(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN.replace('name = "test column"', 'engineer = "x"')))
    assert "project.name" in out


@pytest.mark.parametrize("old,new,key", [
    ('width = "0.3 m"', 'width = "-0.3 m"', "column.width"),
    ("mass_distribution = 0.3333", "mass_distribution = 1.5", "column.mass_distribution"),
    ('width = "0.3 m"', 'width = "4 m"', "column.width"),
])
def test_out_of_range(tmp_path, old, new, key):
    out = run_error(write(tmp_path, BASE_COLUMN.replace(old, new)))
    assert key in out and "expected" in out and "found" in out


def test_restitution_out_of_range(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN + "restitution = 1.2\n"))
    assert "column.restitution" in out


def test_geometrically_impossible_extension(tmp_path):
    # Eq 3.44 needs 2ρ ≥ tan α' − tan α = 0.1 → ρ = 0.04 is impossible
    out = run_error(write(tmp_path, BASE_COLUMN + 'extended_width = "0.6 m"\ncurvature = 0.04\n'))
    assert "column.curvature" in out and "Eq 3.44" in out and "0.05" in out


def test_conflicting_alternatives(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN + 'extended_width = "0.6 m"\nradius = "1 m"\ncurvature = 0.2\n'))
    assert "conflicting" in out and "radius" in out and "curvature" in out


def test_malformed_toml_reports_line(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN + 'depth = "0.3 m\n'))
    assert "malformed TOML" in out and ":10" in out


def test_missing_file():
    out = run_error("does/not/exist.toml")
    assert "not found" in out


def test_both_column_and_podium(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN + '[podium]\ncolumns = 2\n'))
    assert "exactly one of [column] or [podium]" in out


def test_unknown_section(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN + '[analysys]\nrtol = 1e-9\n'))
    assert "[analysis]" in out


def test_model_that_does_not_fit(tmp_path):
    out = run_error(write(tmp_path, BASE_COLUMN + '[analysis]\nmodel = "podium-2dof"\n'))
    assert "analysis.model" in out


def test_superstructure_needs_damping(tmp_path):
    text = open("examples/podium_flat.toml").read().replace('damping = "2 %"\n', "")
    out = run_error(write(tmp_path, text))
    assert "superstructure.damping" in out


def test_validity_warnings(tmp_path):
    text = open("examples/podium_flat.toml").read().replace('width = "0.45 m"', 'width = "0.75 m"')
    result = runner.invoke(app, ["quantities", str(write(tmp_path, text)), "--json"])
    assert result.exit_code == 0
    warnings = json.loads(result.output)["warnings"]
    assert any("0.2" in w and "podia" in w for w in warnings)


def test_init_writes_loadable_templates(tmp_path):
    for kind in ("podium", "column"):
        out = tmp_path / f"{kind}.toml"
        result = runner.invoke(app, ["init", kind, str(out)])
        assert result.exit_code == 0, result.output
        proj = load_project(out)
        assert proj.system.kind == kind
        again = runner.invoke(app, ["init", kind, str(out)])
        assert again.exit_code == 2 and "exists" in again.output


def test_quantities_pushover_curve_file(tmp_path):
    # Fig 3.15 through both phases: F_R/(m g) = tan α at uplift, 0 at θc; β is a grid point
    import numpy as np
    out = tmp_path / "pushover.csv"
    result = runner.invoke(app, ["quantities", "examples/bridge_pier.toml", "--pushover", str(out)])
    assert result.exit_code == 0, result.output
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    q = json.loads(runner.invoke(app, ["quantities", "examples/bridge_pier.toml", "--json"]).output)["quantities"]
    assert data[0, 1] == pytest.approx(0.16, rel=1e-12)
    assert data[-1, 0] == pytest.approx(q["theta_c"]["value"], rel=1e-12) and abs(data[-1, 1]) < 1e-12
    assert np.any(np.isclose(data[:, 0], q["beta"]["value"], rtol=1e-12))
    assert set(np.unique(data[:, 2])) == {1.0, 2.0}
