"""``rockdesign design`` on the command line: input errors (exit 2, one message; more in
test_design_inputs.py)."""
from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app

CURVED = Path(__file__).resolve().parents[2] / "examples" / "podium_curved.toml"


@pytest.mark.parametrize("vary, message", [
    ("podium.width=0.36m:0.60m", "cannot read the variable"),
    ("podium.width=0.3s:0.5s:2", "do not fit the key"),
    ("cylinder.diameter=1m:2m:2", "no such table"),
])
def test_bad_vary_exits_2_with_one_message(tmp_path, vary, message):
    res = CliRunner().invoke(app, ["design", str(CURVED), "--vary", vary, "-o", str(tmp_path / "d"), "--no-pdf"])
    assert res.exit_code == 2, res.output
    assert message in res.output and "--vary" in res.output and "Traceback" not in res.output


def test_three_keys_are_refused(tmp_path):
    res = CliRunner().invoke(app, ["design", str(CURVED), "--vary", "podium.width=0.4m:0.5m:2", "--vary",
                                   "podium.curvature=0.2:0.3:2", "--vary", "podium.columns=30:40:2", "-o",
                                   str(tmp_path / "d"), "--no-pdf"])
    assert res.exit_code == 2 and "one or two variables" in res.output
