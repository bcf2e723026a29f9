"""Project keys whose units or form changed their meaning (issue 42): a superstructure ``frequency`` in rad/s
or rpm was multiplied by 2π again, ``overturn_probability_limit`` was range-checked only as a plain number,
and a NUL byte in a text was written raw into the report and results.json."""
from __future__ import annotations

import math

import pytest

import rockdesign as rd
from rockdesign.paths import REPO_ROOT

PODIUM = (REPO_ROOT / "examples" / "podium_curved.toml").read_text(encoding="utf-8")
CYLINDER = (REPO_ROOT / "examples" / "cylinder.toml").read_text(encoding="utf-8")


def podium(superstructure_period_line: str) -> rd.Project:
    text = PODIUM.replace('period = "0.38 s"', superstructure_period_line)
    assert text != PODIUM or superstructure_period_line == 'period = "0.38 s"'
    return rd.parse_project(text, name="p.toml")


@pytest.mark.parametrize("line, omega", [
    ('period = "0.38 s"', 2 * math.pi / 0.38),
    ('frequency = "2.5 Hz"', 2 * math.pi * 2.5),
    ('frequency = "16.5347 rad/s"', 16.5347),                # angular already: not × 2π again
    ('frequency = "157.9 rpm"', 157.9 * 2 * math.pi / 60),
    ('frequency = "947.4 deg/s"', math.radians(947.4)),
    ('frequency = "2.5 1/s"', 2 * math.pi * 2.5),            # no angle unit: cyclic, as Hz
])
def test_superstructure_frequency_keeps_its_units(line, omega):
    s = podium(line).system.superstructure
    assert s.omega_s == pytest.approx(omega, rel=1e-12)


def test_rad_per_s_and_hz_give_the_same_model():
    """16.5347 rad/s = 2.6316 Hz = 1/0.38 s: the same superstructure (the bug made ω_s 6.28× too high, enough
    to switch the model to a rigid superstructure)."""
    a = podium('frequency = "16.5347 rad/s"')
    b = podium(f'frequency = "{16.5347 / (2 * math.pi)!r} Hz"')
    assert a.system.superstructure.omega_s == pytest.approx(b.system.superstructure.omega_s, rel=1e-12)
    assert rd.design_quantities(a)["omega_s_over_p"].value == pytest.approx(
        rd.design_quantities(b)["omega_s_over_p"].value, rel=1e-12)


@pytest.mark.parametrize("text, omega", [('"200 rad/s"', 200.0), ('"30 Hz"', 60 * math.pi), ('"1910 rpm"', 1910 * math.pi / 30)])
def test_cylinder_contact_frequency_keeps_its_units(text, omega):
    t = CYLINDER.replace('contact_frequency = "200 rad/s"', f"contact_frequency = {text}")
    assert rd.parse_project(t, name="c.toml").system.contact_frequency == pytest.approx(omega, rel=1e-12)


@pytest.mark.parametrize("value", ["1", "1.0", '"100 %"', '"150 %"', "0", '"0 %"', "-0.1", '"nan"', '"2 m"'])
def test_overturn_probability_limit_is_range_checked_in_every_form(value):
    """A limit of 1 or "150 %" passed a suite where 11 of 11 ground motions overturn."""
    text = PODIUM.replace("[analysis]", f"[analysis]\nacceptance = \"binomial\"\noverturn_probability_limit = {value}")
    with pytest.raises(rd.ProjectError, match="analysis.overturn_probability_limit") as info:
        rd.parse_project(text, name="p.toml")
    assert "found" in str(info.value) or "got" in str(info.value)


@pytest.mark.parametrize("value, limit", [("0.05", 0.05), ('"5 %"', 0.05), ('"0.2"', 0.2)])
def test_overturn_probability_limit_forms_that_hold(value, limit):
    text = PODIUM.replace("[analysis]", f"[analysis]\nacceptance = \"binomial\"\noverturn_probability_limit = {value}")
    assert rd.parse_project(text, name="p.toml").analysis.overturn_probability_limit == pytest.approx(limit)


@pytest.mark.parametrize("where, old, new", [
    ("project.name", 'name = "', 'name = "a\\u0000'),
    ("project.engineer", 'engineer = "', 'engineer = "\\u001b[31m'),
    ("excitation.suites[0]", 'suites = ["p695-farfield"]', 'suites = ["p695-farfield\\u0000"]'),
])
def test_control_characters_in_text_are_refused(where, old, new):
    text = PODIUM.replace(old, new, 1)
    assert text != PODIUM
    with pytest.raises(rd.ProjectError, match="control character") as info:
        rd.parse_project(text, name="p.toml")
    assert f"key '{where}'" in str(info.value) and "p.toml" in str(info.value)


def test_tabs_and_line_breaks_are_text():
    text = PODIUM.replace('notes = "', 'notes = "line one\\nline\\ttwo ', 1)
    assert "line one\nline\ttwo" in rd.parse_project(text, name="p.toml").info["notes"]
