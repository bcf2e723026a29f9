"""A FAIL points to ``rockdesign design`` and to the parameter that governs (issue 42)."""
from __future__ import annotations

import shlex

import pytest

import rockdesign as rd
from rockdesign.paths import REPO_ROOT


@pytest.mark.parametrize("example, keys", [
    ("podium_curved.toml", ["podium.width", "podium.curvature"]),
    ("podium_flat.toml", ["podium.width"]),
    ("cylinder.toml", ["cylinder.diameter"]),
])
def test_a_fail_names_the_governing_keys_and_a_command_that_runs(example, keys):
    project = rd.load_project(REPO_ROOT / "examples" / example)
    from rockdesign.cli.check import _command
    hint = rd.design_hint(project, {"verdict": "FAIL"})
    assert hint is not None and "tan α" in str(hint) and "--" not in str(hint)     # library words, no flags
    text = _command(hint)          # the command line writes the command to run
    command = text.split(": rockdesign design ", 1)[1] if "then " not in text else text.split("then rockdesign design ")[1]
    words = shlex.split(command)
    vary = [words[k + 1] for k, w in enumerate(words) if w == "--vary"]
    assert vary == list(hint.vary) and [v.split("=")[0] for v in vary] == keys
    if project.excitation_raw is not None:       # the suggested grid is valid input (some variants may be INVALID)
        plan = rd.plan_design(project, vary)
        assert any(v.project is not None for v in plan.variants)
    else:
        assert "[excitation]" in str(hint)


def test_no_hint_for_a_pass_or_failed_analyses():
    project = rd.load_project(REPO_ROOT / "examples" / "podium_flat.toml")
    assert rd.design_hint(project, {"verdict": "PASS"}) is None
    assert rd.design_hint(project, {"verdict": "FAIL", "failed_records": [{"id": "x"}]}) is None


def test_the_check_summary_prints_the_hint():
    import json

    from rockdesign.console import make_console
    from rockdesign.display import check_summary
    data = json.loads((REPO_ROOT / "tests" / "golden" / "data" / "check" / "bridge_pier.json").read_text())
    assert data["verdict"] == "FAIL"
    console = make_console(record=True, width=200)
    check_summary(data, None, console, hint="to find a design that passes: rockdesign design x.toml --vary a.b=1:2:2")
    assert "next: to find a design that passes: rockdesign design x.toml" in console.export_text()
