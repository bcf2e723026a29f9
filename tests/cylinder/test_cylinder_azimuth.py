"""A planar motion along any azimuth: the 3D engine against the rotated single-component run (issue 49).

By the cylinder's symmetry, a record acting along the azimuth β — given as two components (a cosβ, a sinβ),
as ``files:X,Y`` reads them — is the record alone along x turned by β: θ(t) must be the same, the tilt must
stay on the motion's line (φ ≡ β or β + π, the planar crossings add π) and the outcome must be the same
(thesis Sec 5.2.6, Eq 5.26; ``rockdesign.cylinder.motion_line``).

The tolerance on θ(t) comes from the integrator's tolerances: DOP853 accepts a step when its error norm,
the RMS over the n state components of err_i/(atol + rtol |y_i|), is below 1, so each step commits at most
√n (atol + rtol θ_ot) on θ (θ ≤ θ_ot); a run of N steps, its errors added without amplification, is
within N times that of the exact solution, and two runs of the same equation are within the sum:
(N_β + N_x) √n (atol + rtol θ_ot).  The rotation changes the input by round-off only (≤ 1.05 ε of each
sample), so this bound holds unless the response itself is chaotic at round-off level; that is measured,
not assumed: the reference is run again on its input × (1 + 4ε), and where that alone moves θ(t) by more
than the bound (micro-rocking with thousands of crossings) θ(t) is not comparable and only the outcome,
the line and the counts are.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from rockdesign.cylinder.engine import simulate_cylinder
from rockdesign.cylinder.motion_line import LINE_TOLERANCE, one_directional
from rockdesign.cylinder.simulation import COMPLETED
from rockdesign.cylinder.system import cylinder
from rockdesign.motions.library import load_record
from rockdesign.motions.motion import record_motion
from rockdesign.cylinder.pairs import pair_of_records

AZIMUTHS_DEG = (0.0, 15.0, 30.0, 45.0, 60.0, 90.0, 135.0, 200.0)
AMPLITUDES = (0.9, 1.05, 1.2, 1.5, 2.0, 3.0)
"""Resultant PGA over the uplift acceleration g tan α: below uplift, micro-rocking, rocking, overturning."""
GRID = 0.01
EPS = np.finfo(float).eps


def along(record, beta: float):
    """The record along the azimuth β [rad] as a pair of two components, as two files would give it."""
    a = record.samples * record.scale
    return pair_of_records(f"{record.name} along {math.degrees(beta):g}°",
                           record_motion("x", math.cos(beta) * a, record.dt),
                           record_motion("y", math.sin(beta) * a, record.dt))


def on_grid(r) -> dict[int, float]:
    """θ at the dense-output rows k·GRID of a run (k → θ)."""
    k = np.round(r.t / GRID)
    rows = np.isclose(r.t, k * GRID, rtol=0.0, atol=1e-9)
    return dict(zip(k[rows].astype(int), r.theta[rows]))


def theta_difference(a, b) -> float:
    """max |θ_a − θ_b| [rad] on the grid times both runs reached."""
    ga, gb = on_grid(a), on_grid(b)
    common = sorted(set(ga) & set(gb))
    assert len(common) > 100
    return max(abs(ga[k] - gb[k]) for k in common)


def theta_tolerance(a, b, cyl) -> float:
    """(N_a + N_b) √n (atol + rtol θ_ot): the two runs' errors as the step control bounds them (docstring)."""
    n = 6 if cyl.damped else 4
    s = a.solver
    return (a.solver["steps"] + b.solver["steps"]) * math.sqrt(n) * (s["atol"] + s["rtol"] * cyl.theta_overturn)


def off_line(r, beta: float) -> float:
    """max distance [rad] of φ from the line of β (β or β + π), over the run from its first uplift."""
    rows = r.t >= (r.uplift_time if r.uplift_time is not None else np.inf)
    if not rows.any():
        return 0.0
    return float(np.max(np.abs(np.angle(np.exp(2j * (r.phi[rows] - beta))))) / 2.0)


def phi_tolerance(r) -> float:
    """φ gains π at every crossing in floating point: (crossings + 1) rounding errors of max(|φ|, π)."""
    crossings = r.times_of("planar-crossing").size
    return (crossings + 1) * 2.0 * EPS * max(float(np.max(np.abs(r.phi))), math.pi)


@pytest.fixture(scope="module")
def record():
    return load_record("p695-ff/11a")


@pytest.mark.parametrize("contact", ["rigid", "spring-dashpot"])
def test_every_azimuth_is_the_rotated_single_component(record, contact):
    cyl = cylinder(3.0, 0.6, contact=contact)
    up = cyl.g * math.tan(cyl.alpha)
    x_only = pair_of_records(record.name, record, None)
    outcomes, compared, chaotic = set(), 0, []
    for amplitude in AMPLITUDES:
        scale = amplitude * up / x_only.resultant_pga
        ref = simulate_cylinder(cyl, x_only.scaled(scale), output_dt=GRID)
        assert ref.status in COMPLETED
        nudged = simulate_cylinder(cyl, x_only.scaled(scale * (1.0 + 4.0 * EPS)), output_dt=GRID)
        outcomes.add("overturned" if ref.overturned else ("rocked" if ref.uplift_time is not None else "at rest"))
        for deg in AZIMUTHS_DEG:
            beta = math.radians(deg)
            run = simulate_cylinder(cyl, along(record, beta).scaled(scale), output_dt=GRID)
            where = f"{contact}, {amplitude} × g tan α, azimuth {deg:g}°"
            assert run.status in COMPLETED, where
            assert run.planar, where
            assert run.overturned == ref.overturned, where
            assert (run.uplift_time is None) == (ref.uplift_time is None), where
            if ref.uplift_time is not None:
                assert run.uplift_time == pytest.approx(ref.uplift_time, abs=1e-9), where
            assert off_line(run, beta) <= phi_tolerance(run), where
            tol = theta_tolerance(run, ref, cyl)
            if theta_difference(ref, nudged) > tol:
                chaotic.append((amplitude, theta_difference(ref, nudged)))
                assert run.quasi_impacts > 1000, where       # micro-rocking, the known chaotic regime
                continue
            assert theta_difference(run, ref) <= tol, where
            assert run.quasi_impacts == ref.quasi_impacts, where
            assert run.theta_max == pytest.approx(ref.theta_max, abs=tol), where
            compared += 1
    # the sweep spans no uplift, rocking and overturning, and θ(t) was compared almost everywhere
    assert outcomes == {"at rest", "rocked", "overturned"}
    assert {a for a, _ in chaotic} <= {1.05}
    assert compared >= (len(AMPLITUDES) - 1) * len(AZIMUTHS_DEG)


def test_the_3d_equations_alone_collapse_on_a_diagonal_motion(record):
    """What the planar reduction is for: without it the 3D equations (Eq 5.23) carry a round-off spin into the
    first return to θ = 0, a quasi-impact far below what the step control resolves."""
    cyl = cylinder(3.0, 0.6)
    pair = along(record, math.radians(45.0)).scaled(1.5 * cyl.g * math.tan(cyl.alpha) / record.pga)
    plain = simulate_cylinder(cyl, pair, planar_reduction=False)
    assert plain.status == "step size collapsed"
    assert plain.theta[-1] < 1e-12 and abs(plain.phidot[-1]) > 1e6
    reduced = simulate_cylinder(cyl, pair)
    assert reduced.status in COMPLETED and reduced.times_of("planar-crossing").size >= 1
    assert reduced.times_of("planar-crossing")[0] > plain.uplift_time


def test_proportional_components_are_one_directional(record):
    a = record.samples
    assert one_directional(0, np.array([1.0, record.dt]), a, a, 1.0, 1.0)                   # X, X
    assert one_directional(0, np.array([1.0, record.dt]), a, -0.37 * a, 1.0, 1.0)           # X, −0.37 X
    assert one_directional(0, np.array([1.0, record.dt]), a, np.zeros_like(a), 1.0, 1.0)    # X alone
    other = load_record("p695-ff/11b").samples[:a.size]
    assert not one_directional(0, np.array([1.0, record.dt]), a, a + 1e-9 * other, 1.0, 1.0)
    assert LINE_TOLERANCE < 1e-9


def test_a_component_that_ends_leaves_a_planar_tail(record):
    """y ends while x goes on: a rest in the two-component part, then uplifts on x alone.  From the rest on the
    run is the x-only run of the same record with everything before the rest removed (at rest a cylinder
    keeps no memory but φ, which a planar uplift sets anew)."""
    cyl = cylinder(3.0, 0.6)
    other = load_record("p695-ff/11b")
    dt, n = record.dt, record.samples.size
    x = record.samples * record.scale
    y = other.samples[:n] * other.scale
    full = simulate_cylinder(cyl, pair_of_records("x, y", record_motion("x", x, dt), record_motion("y", y, dt)))
    t_rest = full.times_of("rest")[0]
    cut = int(math.floor(t_rest / dt)) + 2                          # y ends after the piece of the rest
    y[cut:] = 0.0
    run = simulate_cylinder(cyl, pair_of_records("y ends", record_motion("x", x, dt), record_motion("y", y, dt)),
                            output_dt=GRID)
    assert run.status in COMPLETED and not run.planar
    assert run.times_of("rest")[0] == t_rest
    tail = run.times_of("uplift")[run.times_of("uplift") > t_rest]
    assert tail.size and tail[0] > cut * dt
    x_after = x.copy()
    x_after[:cut] = 0.0
    ref = simulate_cylinder(cyl, pair_of_records("x after the rest", record_motion("x", x_after, dt), None),
                            output_dt=GRID)
    assert ref.planar and ref.uplift_time == pytest.approx(tail[0], abs=1e-9)
    assert run.overturned == ref.overturned
    ga, gb = on_grid(run), on_grid(ref)
    after = [k for k in set(ga) & set(gb) if k * GRID > tail[0]]
    assert len(after) > 100
    assert max(abs(ga[k] - gb[k]) for k in after) <= theta_tolerance(run, ref, cyl)
    rocking = run.t >= tail[0]
    assert np.all(run.phidot[rocking] == 0.0)
    assert np.max(np.abs(np.sin(run.phi[rocking]))) <= phi_tolerance(run)   # on the x axis


def test_a_second_component_that_begins_turns_the_planar_motion_3d(record):
    """x alone first, then y too: the planar motion goes on with the 3D equations from its state where the first
    piece off the line begins — as a 3D run started there in that state does."""
    cyl = cylinder(3.0, 0.6)
    other = load_record("p695-ff/11b")
    dt, n = record.dt, record.samples.size
    scale = 1.5 * cyl.g * math.tan(cyl.alpha) / record.pga
    x = record.samples * record.scale * scale
    planar = simulate_cylinder(cyl, pair_of_records("x", record_motion("x", x, dt), None), output_dt=GRID)
    k = int(round((planar.uplift_time + 1.0) / dt))                 # a second of planar rocking first
    y = other.samples[:n] * other.scale * scale
    y[:k] = 0.0
    pair = pair_of_records("y begins", record_motion("x", x, dt), record_motion("y", y, dt))
    run = simulate_cylinder(cyl, pair, output_dt=GRID)
    assert run.status in COMPLETED and not run.planar
    t_switch = (k - 1) * dt                                          # the piece [k − 1, k] leaves the line
    i = int(np.argmin(np.abs(run.t - t_switch)))
    assert abs(run.t[i] - t_switch) < 1e-12 and run.theta[i] > 0 and run.phidot[i] == 0.0
    # up to there the planar run, to round-off (the same steps); from there on a spin
    ga, gp = on_grid(run), on_grid(planar)
    before = [g for g in set(ga) & set(gp) if g * GRID <= t_switch]
    assert max(abs(ga[g] - gp[g]) for g in before) <= 1e-14
    assert np.all(run.phidot[run.t <= t_switch] == 0.0) and np.any(run.phidot[run.t > t_switch] != 0.0)
    # from there, a 3D run started in the same state on the rest of the record
    rest = pair_of_records("rest", record_motion("x", x[k - 1:], dt), record_motion("y", y[k - 1:], dt))
    restart = simulate_cylinder(cyl, rest, theta0=run.theta[i], thetadot0=run.thetadot[i], phi0=run.phi[i],
                                t_end=run.t[-1] - t_switch + 1.0, output_dt=GRID)
    assert not restart.planar and restart.overturned == run.overturned
    offset = int(round(t_switch / GRID))
    gr = on_grid(restart)
    window = [g for g in gr if g * GRID < 2.0 and g + offset in ga]  # two seconds, before chaos takes over
    assert len(window) > 150
    assert max(abs(gr[g] - ga[g + offset]) for g in window) <= theta_tolerance(run, restart, cyl)


@pytest.mark.shared
def test_the_same_record_on_x_and_y_from_the_command_line(shared, tmp_path):
    """Issue 49: ``simulate cyl.toml --motion files:r01.AT2,r01.AT2`` on the template project ended "step size
    collapsed" (exit 2); it is the record × √2 along x, tilting along 45°."""
    import json

    from typer.testing import CliRunner

    from rockdesign.cli import app
    runner = CliRunner()
    project = tmp_path / "cyl.toml"
    assert runner.invoke(app, ["init", "cylinder", str(project)]).exit_code == 0
    x = shared / "ground_motions" / "records" / "FEMAP695_FF11a_RSN900_YER270.AT2"
    both = runner.invoke(app, ["simulate", str(project), "--motion", f"files:{x},{x}", "--json"])
    assert both.exit_code == 0, both.output
    alone = runner.invoke(app, ["simulate", str(project), "--motion", f"file:{x},scale={math.sqrt(2.0)!r}", "--json"])
    assert alone.exit_code == 0, alone.output
    d, a = json.loads(both.stdout), json.loads(alone.stdout)
    assert d["model"] == a["model"] == "cylinder-undamped-planar"
    assert d["solver"]["status"] == a["solver"]["status"] and d["overturned"] == a["overturned"]
    assert d["quasi_impacts"] == a["quasi_impacts"] > 0
    assert d["theta_max"] == pytest.approx(a["theta_max"], abs=1e-9)
    # the same overturning instant: 1e-7 s at θ̇ ≈ 0.28 rad/s is 3e-8 rad, inside the sweep's θ bound
    assert d["t_end"] == pytest.approx(a["t_end"], abs=1e-7)
    assert abs(math.remainder(d["phi_end"] - math.pi / 4.0, math.pi)) < 1e-9
    rotated = runner.invoke(app, ["simulate", str(project), "--motion", f"file:{x},scale={math.sqrt(2.0)!r},azimuth=45deg",
                                  "--json"])
    assert rotated.exit_code == 0 and json.loads(rotated.stdout)["theta_max"] == pytest.approx(a["theta_max"], abs=1e-9)


@pytest.mark.parametrize("contact", ["rigid", "spring-dashpot"])
def test_a_second_component_right_after_an_uplift_hands_over_through_the_seed_phase(contact):
    """x reaches the uplift level just before a sample, y begins at that sample: the planar start leaves the line
    at θ ≈ 1e-19 rad, below θ_seed, and goes on through the seed phase — which is what the 3D equations do from
    the uplift on (planar_reduction=False), the seed phase being the planar motion toward the force."""
    from rockdesign.cylinder.engine import uplift_level
    cyl = cylinder(3.0, 0.6, contact=contact)
    up = uplift_level(cyl.alpha, cyl.g)
    dt = 0.01
    t = np.arange(0.0, 6.0, dt)
    x = np.where(t < 1.0, t, 1.0 + 0.8 * np.sin(2.0 * np.pi * (t - 1.0) / 1.5)) * up * (1.0 + 1e-6)
    y = np.where(t >= 1.0, 0.9 * up * np.sin(2.0 * np.pi * (t - 1.0) / 0.9), 0.0)    # y = 0 up to t = 1.00 s
    pair = pair_of_records("y from 1 s", record_motion("x", x, dt), record_motion("y", y, dt))
    run = simulate_cylinder(cyl, pair, output_dt=GRID)
    plain = simulate_cylinder(cyl, pair, output_dt=GRID, planar_reduction=False)
    assert 0.99 < run.uplift_time < 1.0 and run.status in COMPLETED and not run.planar
    at_switch = run.theta[np.argmin(np.abs(run.t - 1.0))]
    assert 0.0 < at_switch < run.solver["theta_seed"]
    assert np.any(run.theta == run.solver["theta_seed"])              # the seed phase's hand-over
    assert run.overturned == plain.overturned
    assert theta_difference(run, plain) <= theta_tolerance(run, plain, cyl)
