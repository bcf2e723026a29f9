"""``rockdesign design`` on the command line: input errors (exit 2, one message) and a grid of impossible
variants (named INVALID cells, no crash, exit 1 — no variant passes)."""
from __future__ import annotations

import json
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


def test_impossible_variants_are_invalid_cells_not_a_crash(tmp_path):
    # a contact width at or beyond the extended base (0.60 m) leaves no extension: the loader refuses it
    out = tmp_path / "d"
    res = CliRunner().invoke(app, ["design", str(CURVED), "--vary", "podium.width=0.60m:0.70m:2", "-o", str(out),
                                   "--no-pdf"])
    assert res.exit_code == 1, res.output          # none passes
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert [c["verdict"] for c in data["cells"]] == ["INVALID", "INVALID"]
    assert all("extended_width" in c["reason"] for c in data["cells"])
    assert data["recommended"] is None and data["analyses_run"] == 0
    assert data["variables"] == [{"key": "podium.width", "unit": "m", "values": [0.6, 0.7], "values_si": [0.6, 0.7]}]
    rows = (out / "design.csv").read_text(encoding="utf-8").splitlines()
    assert rows[0].startswith("podium.width [m],verdict,") and rows[1].startswith("0.6,INVALID,")
