"""Response status: success, message and typed solver statistics, and the engine's array layout used by
name only (issue "one-way architecture")."""
from __future__ import annotations

import ast
from pathlib import Path

from support import G, table34_column
from rockdesign.planar.dynamics.layout import ST_OK, ST_OVERTURNED, ST_TOO_MANY_STEPS
from rockdesign.planar.dynamics.simulate import simulate
from rockdesign.motions.motion import pulse_motion

PACKAGE = Path(__file__).resolve().parents[2] / "rockdesign"


def test_a_completed_run_reports_success_and_its_counters():
    r = simulate(table34_column("B1"), pulse_motion("ricker-anti", 0.12 * G, 0.95), t_end=6.0)
    assert not r.overturned and r.impacts > 0
    assert r.status_code == ST_OK and r.success
    assert r.message.startswith("the analysis ran to t = 6 s")
    s = r.solver
    assert (s.steps, s.rejected_steps, s.function_evaluations, s.events, s.events_stored, s.rest_entries,
            s.event_refinements) == tuple(r.as_json()["solver"][k] for k in (
                "steps", "rejected_steps", "function_evaluations", "events", "events_stored", "rest_entries",
                "event_refinements"))
    assert s.events == len(r.events) and s.steps > 0 and s.function_evaluations >= 6 * s.steps


def test_an_overturning_run_is_a_successful_analysis_that_says_so():
    r = simulate(table34_column("B1"), pulse_motion("ricker-anti", 0.6 * G, 0.95), t_end=6.0, overturn="dynamic")
    assert r.overturned and r.overturn_mode == "dynamic"
    assert r.status_code == ST_OVERTURNED and r.success
    assert "overturned" in r.message and f"{r.t_end:.6g} s" in r.message


def test_a_run_stopped_by_the_step_limit_fails_loudly():
    from rockdesign.planar.dynamics import simulate as sim_module
    system, motion = table34_column("B1"), pulse_motion("ricker-anti", 0.3 * G, 0.95)
    r = sim_module.simulate(system, motion, t_end=6.0, max_steps=20)
    assert r.status_code == ST_TOO_MANY_STEPS and not r.success
    assert r.message.startswith("FAILED: step limit reached")


def _literal_index_uses(path: Path) -> list[str]:
    """``name[<int literal>]`` for the engine's arrays (parameters, summary, diagnostics, options)."""
    arrays = {"sp", "summary", "summ", "diag", "opts", "o"}
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in arrays
                and isinstance(node.slice, ast.Constant) and isinstance(node.slice.value, int)):
            out.append(f"{path.name}:{node.lineno} {node.value.id}[{node.slice.value}]")
    return out


def test_engine_arrays_are_read_by_name_only():
    # the layouts live in dynamics/layout.py (results, options, events, status) and dynamics/eom.py (P_*);
    # the independent scipy baseline (bench/baseline) has its own parameter tuple
    found = [u for p in sorted(PACKAGE.rglob("*.py")) if "baseline" not in p.parts for u in _literal_index_uses(p)]
    assert not found, found


def test_the_literal_index_check_sees_one(tmp_path):
    f = tmp_path / "probe.py"
    f.write_text("def g(sp, y):\n    return sp[12] + y[0] + sp[P_THETA_C]\n")
    assert _literal_index_uses(f) == ["probe.py:2 sp[12]"]


def test_events_made_in_bulk_are_ordinary_frozen_events():
    """Event.many (used by simulate for its ~900 podium events) makes the same objects as Event(...)."""
    import dataclasses

    import pytest
    from rockdesign.planar.dynamics.response import Event
    bulk = Event.many(["impact", "uplift"], [1.5, 2.0], [[0.0, -0.1, 0.01, 0.2], (0.001, 0.0, 0.0, 0.0)])
    one_by_one = [Event("impact", 1.5, (0.0, -0.1, 0.01, 0.2)), Event("uplift", 2.0, (0.001, 0.0, 0.0, 0.0))]
    assert bulk == one_by_one and [hash(e) for e in bulk] == [hash(e) for e in one_by_one]
    assert [repr(e) for e in bulk] == [repr(e) for e in one_by_one]
    assert isinstance(bulk[0].state, tuple) and dataclasses.asdict(bulk[0])["time"] == 1.5
    with pytest.raises(dataclasses.FrozenInstanceError):
        bulk[0].time = 3.0
    r = simulate(table34_column("B1"), pulse_motion("ricker-anti", 0.12 * G, 0.95), t_end=6.0)
    assert r.events and all(type(e) is Event and e == Event(e.kind, e.time, tuple(e.state)) for e in r.events)
