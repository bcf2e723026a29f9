"""The registry proves itself: a kind of structure written outside ``rockdesign/`` (Newmark's sliding
block, ``tests/kinds/sliding_block``) is registered with :func:`rockdesign.kinds.register` and goes through
the front door — ``rockdesign quantities``, ``simulate``, ``check`` to results.json and a PDF report — with
no file of the package naming it (docs/architecture.md, "Adding a kind of structure")."""
from __future__ import annotations

import json
import math

import numpy as np
import pypdf
import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.kinds import register, registered, unregister
from rockdesign.motions.grouping import ground_motion_id
from rockdesign.motions.suites import load_suite
from rockdesign.paths import REPO_ROOT
from sliding_block import SlidingBlock, sliding_displacement

PROJECT = """
[project]
name = "dam block"
[sliding_block]
friction = 0.2
allowed_displacement = "0.05 m"
design_pga = "0.4 g"
"""


@pytest.fixture
def sliding_kind():
    kind = register(SlidingBlock())
    yield kind
    unregister(kind.name)


def test_newmark_rectangular_pulse():
    """Newmark (1965): a rectangular pulse A over t0 slides a block of critical acceleration a_c by
    A t0² (A − a_c)/(2 a_c).  The record ramps up and down within one sample (dt = 1e-4 s): that changes
    the closed form by O(dt/t0) = 2e-4, inside the 1e-3 asked for (a wrong sign of friction or a stop
    missed changes it by tens of per cent)."""
    g, mu, A, t0, dt = 9.81, 0.2, 0.5 * 9.81, 0.5, 1e-4
    n = int(round(t0 / dt))
    accel = np.concatenate([[0.0], -A * np.ones(n), np.zeros(20000)])
    peak, _ = sliding_displacement(accel, dt, mu * g)
    a_c = mu * g
    assert peak == pytest.approx(A * t0 ** 2 * (A - a_c) / (2 * a_c), rel=1e-3)
    assert sliding_displacement(0.9 * a_c * np.sin(np.linspace(0, 20, 2000)), 0.01, a_c)[0] == 0.0  # never slides


def test_the_kind_is_registered_outside_the_package(sliding_kind):
    names = [k.name for k in registered()]
    assert names[0] == "sliding_block" and names[-1] == "planar"    # offered documents first
    assert not any("sliding_block" in p.read_text(encoding="utf-8") or "SlidingBlock" in p.read_text(encoding="utf-8")
                   for p in (REPO_ROOT / "rockdesign").rglob("*.py"))


def test_front_door_check_and_report(sliding_kind, tmp_path):
    path = tmp_path / "dam.toml"
    path.write_text(PROJECT)
    runner = CliRunner()
    q = runner.invoke(app, ["quantities", str(path), "--json"])
    assert q.exit_code == 0, q.output
    assert json.loads(q.output)["quantities"]["critical_acceleration"]["value"] == pytest.approx(0.2 * 9.81)
    s = runner.invoke(app, ["simulate", str(path), "--motion", "record:p695-ff/11a", "--json"])
    assert s.exit_code == 0, s.output
    out = tmp_path / "out"
    res = runner.invoke(app, ["check", str(path), "-o", str(out)])
    data = json.loads((out / "results.json").read_text())
    # the verdict, recounted here: a ground motion is unacceptable when a component slides more than allowed
    g = 9.81
    worst: dict[str, float] = {}
    for rid, motion, meta in load_suite("p695-farfield", gravity=g).records:
        accel = motion.samples * (0.4 * g / np.max(np.abs(motion.samples)))
        gm = ground_motion_id(rid, meta)
        worst[gm] = max(worst.get(gm, 0.0), sliding_displacement(accel, motion.dt, 0.2 * g)[0])
    unacceptable = sum(d > 0.05 for d in worst.values())
    assert len(worst) == 22 and 0 < unacceptable < 22
    assert data["verdict"] == ("PASS" if unacceptable <= 1 else "FAIL")
    assert res.exit_code == (0 if unacceptable <= 1 else 1), res.output
    assert f"{unacceptable} of 22 ground motions unacceptable" in data["verdict_reason"]
    text = "".join(page.extract_text() for page in pypdf.PdfReader(str(out / "report.pdf")).pages)
    assert "Sliding block" in text and data["verdict"] in text
    assert sorted(p.name for p in out.iterdir()) == ["report.html", "report.pdf", "results.csv", "results.json"]
    assert math.isfinite(max(r["displacement_max"] for r in data["records"]))


def test_front_door_design_chart(sliding_kind, tmp_path):
    """The kind charts its design with ``rockdesign design`` through the shared grid, tolerance neighbourhood and
    report, adding only its hooks and its own cell column (``critical_acceleration``) and response name: each
    cell's verdict and count equal a recount by Newmark's closed-form integration here, the recommendation is the
    least-friction robust PASS (no demand or material to rank by: the first in grid order) and its two tolerance
    neighbours (friction ± 2 %, a dimensionless key) are checked."""
    path = tmp_path / "dam.toml"
    path.write_text(PROJECT + '[excitation]\nsuite = "p695-farfield"\n')
    out = tmp_path / "chart"
    res = CliRunner().invoke(app, ["design", str(path), "--vary", "sliding_block.friction=0.15:0.35:3", "-o", str(out)])
    data = json.loads((out / "design.json").read_text())
    g = 9.81
    suite = load_suite("p695-farfield", gravity=g).records

    def unacceptable(mu: float) -> int:
        worst: dict[str, float] = {}
        for rid, motion, meta in suite:
            accel = motion.samples * (0.4 * g / np.max(np.abs(motion.samples)))
            gm = ground_motion_id(rid, meta)
            worst[gm] = max(worst.get(gm, 0.0), sliding_displacement(accel, motion.dt, mu * g)[0])
        return sum(d > 0.05 for d in worst.values())

    counts = [unacceptable(mu) for mu in (0.15, 0.25, 0.35)]
    assert [c["n_unacceptable"] for c in data["cells"]] == counts
    assert [c["verdict"] for c in data["cells"]] == ["PASS" if k <= 1 else "FAIL" for k in counts]
    assert "PASS" in {c["verdict"] for c in data["cells"]} and "FAIL" in {c["verdict"] for c in data["cells"]}
    assert res.exit_code == 0, res.output
    first = next(c for c in data["cells"] if c["verdict"] == "PASS" and c["robust"])
    assert data["recommended"]["values"] == first["values"]
    neighbours = data["recommended"]["neighbourhood"]
    assert data["recommended"]["tolerance_robust"] is True
    mu = first["values"]["sliding_block.friction"]
    assert sorted(n["values"]["sliding_block.friction"] for n in neighbours) == pytest.approx([0.98 * mu, 1.02 * mu])
    assert all(n["verdict"] == ("PASS" if unacceptable(n["values"]["sliding_block.friction"]) <= 1 else "FAIL")
               for n in neighbours)
    # the kind's own column and response, in its words; no planar column in a file of this kind
    assert data["columns"] == [{"key": "critical_acceleration", "heading": "a_c", "unit": "m/s^2"}]
    header = (out / "design.csv").read_text().splitlines()[0]
    assert "critical_acceleration [m/s^2]" in header and "theta_c" not in header.replace("theta_c [-]", "")
    assert not {"column_material", "uplift_acceleration", "theta_c"} & set(data["cells"][0])
    assert "(the amplitude × (1 ± 0.1 %))" in data["settings"]["robustness"] and "c_r" not in data["settings"]["robustness"]
    text = "".join(page.extract_text() for page in pypdf.PdfReader(str(out / "design.pdf")).pages)
    a_c = f"{first['critical_acceleration']:.4g} m/s²"             # the kind's column, with its unit
    assert "median umax/u" in text and a_c in text            # (the report sets "_max" as a subscript)
