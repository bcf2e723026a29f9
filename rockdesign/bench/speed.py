"""Summary of the speed benchmarks of ``benchmarks/`` (their JSON results), for ``rockdesign bench``.

Each script in ``benchmarks/`` writes ``benchmarks/results/<name>.json`` with ratios against a
baseline measured in the same run.  The schemas differ by benchmark; this module reads every file,
keeps its date/machine if given, and lists the headline numbers: the scalars of its ``summary``
object if it has one, otherwise every scalar whose key names a ratio, a speed-up or a time
(``ratio``, ``speedup``, ``ms``, ``seconds``…), with its JSON path.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

from ..paths import REPO_ROOT

RESULTS_DIR = REPO_ROOT / "benchmarks" / "results"
_HEADLINE_WORDS = ("ratio", "speedup", "speed_up", "faster", "ms_per", "per_record", "ms", "seconds", "wall")
MAX_ITEMS = 16


def results_dir() -> Path:
    """``benchmarks/results`` of the checkout (empty when rockdesign is installed without it)."""
    return RESULTS_DIR


def _leaves(obj, path=""):
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from _leaves(v, f"{path}.{k}" if path else str(k))
    elif isinstance(obj, list) and len(obj) <= 50:
        for i, v in enumerate(obj):
            name = v.get("name") if isinstance(v, dict) else None
            yield from _leaves(v, f"{path}[{name if name else i}]")
    elif isinstance(obj, (int, float)) and not isinstance(obj, bool):
        yield path, obj


def _headline(path: str) -> bool:
    last = path.split(".")[-1].lower()
    return any(w in last for w in _HEADLINE_WORDS)


def summarise_file(path: Path) -> dict:
    """{"file", "name", "date", "machine", "headline": {json path: number}} of one results file."""
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError) as exc:
        return {"file": str(path), "name": Path(path).stem, "error": f"unreadable: {exc}"}
    out = {"file": str(path), "name": Path(path).stem}
    if isinstance(data, dict):
        machine = data.get("machine") if isinstance(data.get("machine"), dict) else {}
        out["date"] = data.get("date") or machine.get("date")
        out["machine"] = machine.get("uname") or data.get("uname") or data.get("host")
        if isinstance(data.get("summary"), dict):
            out["summary"] = data["summary"]
    picked = {}
    summary = data.get("summary") if isinstance(data, dict) else None
    if isinstance(summary, dict):
        # a file with a summary: its scalars come first (goals as booleans included)
        for k, v in summary.items():
            if isinstance(v, bool) or (isinstance(v, (int, float)) and math.isfinite(float(v))):
                picked[f"summary.{k}"] = v
    for p, v in _leaves(data):
        if len(picked) >= MAX_ITEMS:
            break
        if not p.startswith("summary.") and _headline(p) and isinstance(v, (int, float)) and math.isfinite(float(v)):
            picked[p] = v
    out["headline"] = dict(list(picked.items())[:MAX_ITEMS])
    return out


def format_value(v) -> str:
    """A headline value as text (booleans as yes/no)."""
    if isinstance(v, bool):
        return "yes" if v else "no"
    return format(v, ".4g")


def speed_summary(directory: Path | None = None) -> list[dict]:
    """Summaries of every ``*.json`` in ``benchmarks/results`` (sorted by name); [] when absent."""
    d = Path(directory) if directory is not None else results_dir()
    if not d.is_dir():
        return []
    return [summarise_file(p) for p in sorted(d.glob("*.json"))]
