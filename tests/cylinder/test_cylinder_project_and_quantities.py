"""``[cylinder]`` project files (keys, errors) and the cylinder's closed-form quantities (thesis Ch. 5)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from casedata import assert_case, expected
from rockdesign.cylinder.quantities import (angle_of_turn, cylinder_quantities, frequency_parameter,
                                            inertia_axial, inertia_transverse, restitution_root, wobbling_curve,
                                            wobbling_period, wobbling_spin)
from rockdesign.cylinder.system import Cylinder, cylinder
from rockdesign.errors import ProjectError
from rockdesign.kinds import parse_document as parse_project

BASE = {"project": {"name": "museum column"}, "cylinder": {"height": "3.0 m", "diameter": "0.6 m", "mass": "2 t"}}


def project(**changes):
    raw = {k: dict(v) for k, v in BASE.items()}
    for section, table in changes.items():
        raw.setdefault(section, {})
        for key, value in table.items():
            if value is None:
                raw[section].pop(key, None)
            else:
                raw[section][key] = value
    return parse_project(raw, file="cyl.toml")


def test_cylinder_section_in_si():
    p = project(analysis={"overturn_tilt": 1.2})
    c = p.system
    assert isinstance(c, Cylinder) and c.kind == "cylinder"
    assert (c.half_height, c.base_radius, c.mass) == (1.5, 0.3, 2000.0)
    assert c.contact == "rigid" and c.overturn_tilt == 1.2
    assert c.theta_overturn == pytest.approx(1.2 * math.atan(0.2))


def test_alternatives_density_and_spring_dashpot():
    p = project(cylinder={"height": None, "half_height": "1.5 m", "diameter": None, "slenderness": 0.2,
                          "mass": None, "density": "2.5 t/m^3", "contact": "spring-dashpot",
                          "contact_frequency": "200 rad/s", "contact_damping": 0.5})
    c = p.system
    assert c.base_radius == pytest.approx(0.3)
    assert c.mass == pytest.approx(2500 * math.pi * 0.09 * 3.0)
    assert c.damped and c.contact_frequency == 200.0 and c.contact_damping == 0.5
    assert project(cylinder={"contact": "spring-dashpot", "contact_frequency": "10 Hz"}).system.contact_frequency \
        == pytest.approx(20 * math.pi)
    assert project(cylinder={"contact": "spring-dashpot"}).system.contact_frequency == 200.0
    assert project().system.overturn_tilt == 1.5


@pytest.mark.parametrize("changes, key, words", [
    ({"column": {"height": "3 m"}}, "column", "[cylinder] and [column]"),
    ({"podium": {"columns": 4}}, "podium", "[podium]"),
    ({"cylinder": {"contact_damping": 0.5}}, "cylinder.contact_damping", "spring-dashpot"),
    ({"cylinder": {"contact_frequency": "200 rad/s"}}, "cylinder.contact_frequency", "spring-dashpot"),
    ({"cylinder": {"extended_width": "0.8 m"}}, "cylinder.extended_width", "planar"),
    ({"cylinder": {"mass_distribution": 0.33}}, "cylinder.mass_distribution", "planar"),
    ({"cylinder": {"radius": "2 m"}}, "cylinder.radius", "planar"),
    ({"cylinder": {"width": "0.6 m"}}, "cylinder.width", "planar"),
    ({"cylinder": {"density": "2.5 t/m^3"}}, "cylinder.density", "conflicting"),
    ({"cylinder": {"slenderness": 0.2}}, "cylinder.slenderness", "conflicting"),
    ({"cylinder": {"diameter": "4 m"}}, "cylinder.diameter", "squat"),
    ({"cylinder": {"contact": "soft"}}, "cylinder.contact", "invalid"),
    ({"cylinder": {"hieght": "3 m"}}, "cylinder.hieght", "unknown"),
    ({"analysis": {"overturn_tilt": 0.8}}, "analysis.overturn_tilt", "out of range"),
    ({"analysis": {"overturn_tilt": 9.0}}, "analysis.overturn_tilt", "π/2"),
    ({"analysis": {"overturn_tilt": "1.5"}}, "analysis.overturn_tilt", "wrong type"),
    ({"analysis": {"model": "block"}}, "analysis.model", "planar"),
    ({"cylindre": {}}, "cylindre", "unknown section"),
])
def test_errors_name_file_key_expected_found(changes, key, words):
    with pytest.raises(ProjectError) as err:
        project(**changes)
    e = err.value
    assert e.file == "cyl.toml" and e.key == key
    assert words in str(e)
    assert e.expected or e.found


def test_overturn_tilt_without_cylinder_is_refused():
    raw = {"project": {"name": "x"}, "column": {"height": "3 m", "width": "0.6 m", "mass": "1 t",
                                                "mass_distribution": 1 / 3}, "analysis": {"overturn_tilt": 1.5}}
    with pytest.raises(ProjectError) as err:
        parse_project(raw, file="col.toml")
    assert err.value.key == "analysis.overturn_tilt" and "[cylinder]" in str(err.value)


def test_reference_quantities():
    # reference values for 2H = 3 m, tan α = 0.2 (tests/validation/data/cases.json; assert_case widens 1e-5 to
    # half the last printed digit where the data file prints fewer digits: T_w, φ̇0 of Eqs 5.39, 5.40)
    c = cylinder(3.0, 0.6)
    assert_case("eq5.27_p", frequency_parameter(c.R, c.alpha), tol=1e-5)
    assert_case("eq5.41", restitution_root(c.alpha), tol=1e-5)
    assert_case("eq5.39_5.40", [float(wobbling_period(0.1, c.R, c.alpha)), float(wobbling_spin(0.1, c.R, c.alpha))],
                tol=1e-5)
    assert_case("eq5.38", angle_of_turn(c.alpha), tol=1e-5)
    # inertias of a solid cylinder: I1 = B²/4 + H²/3 (about the centre), I2 = B²/2
    assert inertia_transverse(c.R, c.alpha) == pytest.approx(0.3 ** 2 / 4 + 1.5 ** 2 / 3, rel=1e-14)
    assert inertia_axial(c.R, c.alpha) == pytest.approx(0.3 ** 2 / 2, rel=1e-14)
    q = cylinder_quantities(c)
    assert {"alpha", "R", "p", "c_r", "uplift_acceleration", "angle_of_turn"} <= set(q)
    assert q["c_r"].value == pytest.approx(expected("eq5.41") ** 2, abs=2e-5)
    assert q["uplift_acceleration"].value == pytest.approx(9.81 * 0.2)
    assert q["p"].equation == "Eq 5.27" and q["angle_of_turn"].equation == "Eq 5.38"


def test_wobbling_period_grows_without_bound_toward_alpha():
    # Fig 5.2: T_w p grows without bound as θ → α (no spin can hold the cylinder at θ = α)
    c = cylinder(3.0, 0.6)
    ratio, tw_p, housner_p = wobbling_curve(c, n=49)
    assert np.all(np.diff(tw_p[ratio > 0.5]) > 0)
    assert tw_p[-1] > 3 * tw_p[len(tw_p) // 2]
    assert np.all(np.isfinite(tw_p)) and np.all(tw_p > 0)
