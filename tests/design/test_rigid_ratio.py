"""The rigid-superstructure ratio: one default (design.quantities.RIGID_SUPERSTRUCTURE_RATIO), and the
project's ``[analysis] rigid_superstructure_ratio`` honoured by every place that decides or words it."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

import rockdesign as rd
from rockdesign.planar.design.quantities import RIGID_SUPERSTRUCTURE_RATIO
from rockdesign.planar.dynamics.model import default_structure
from rockdesign.project_tables import DEFAULTS

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "podium_flat.toml"   # ω_s/p = 7.5


def _project(ratio: float | None):
    text = EXAMPLE.read_text()
    if ratio is not None:
        text = re.sub(r"^\[analysis\]$", f"[analysis]\nrigid_superstructure_ratio = {ratio}", text, flags=re.M)
    return rd.parse_project(text, name="podium.toml")


def test_one_default():
    assert DEFAULTS.rigid_superstructure_ratio == RIGID_SUPERSTRUCTURE_RATIO == 10.0
    assert _project(None).analysis.rigid_superstructure_ratio == RIGID_SUPERSTRUCTURE_RATIO


@pytest.mark.parametrize("ratio, rigid", [(5.0, True), (10.0, False), (8.0, False), (7.0, True)])
def test_every_place_honours_the_projects_ratio(ratio, rigid):
    project = _project(ratio)
    q = rd.design_quantities(project)
    assert q["omega_s_over_p"].value == pytest.approx(7.5074, rel=1e-4)
    note = q["omega_s_over_p"].note
    assert f"switch at {ratio:g}" in note
    assert ("rigid superstructure adequate" in note) == rigid
    structure, _ = default_structure(project.system, project.analysis.rigid_superstructure_ratio)
    assert structure == ("rigid-superstructure" if rigid else "podium-2dof")
    r = rd.simulate(project, "ricker-anti:ap=1m/s^2,Tp=0.5s")
    assert r.model.startswith("rigid-superstructure" if rigid else "podium-2dof")
