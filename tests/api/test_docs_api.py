"""docs/api.md is a notebook session that works: every ``python`` block runs, in order, in one namespace."""
from __future__ import annotations

import re
from pathlib import Path

DOC = Path(__file__).resolve().parents[2] / "docs" / "api.md"
BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def test_every_code_block_of_docs_api_runs(tmp_path, monkeypatch, capsys):
    blocks = BLOCK.findall(DOC.read_text(encoding="utf-8"))
    assert len(blocks) >= 6
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__docs_api__"}
    for k, code in enumerate(blocks):
        exec(compile(code, f"{DOC.name} block {k + 1}", "exec"), namespace)
    out = capsys.readouterr().out
    assert "motion" in out and "podium.height" in out           # the two error examples printed their keys
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["report.html", "results.csv", "results.json"]
    assert (tmp_path / "pushover.svg").read_text(encoding="utf-8").lstrip().startswith("<?xml")
    assert namespace["c"].verdict in ("PASS", "FAIL")
