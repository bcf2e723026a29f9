"""The commands whose outputs are pinned by :mod:`test_outputs_unchanged` (issue "one-way architecture":
a restructuring must not change a number a user sees).

``CHECKS``: ``rockdesign check EXAMPLE --no-pdf`` → ``results.json``;
``SIMULATIONS``: ``rockdesign simulate EXAMPLE --motion M [--model X] --json`` → stdout.
Run ``python tests/golden/regenerate.py`` only for a deliberate change of the numbers, and say why in the
commit message.
"""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parent / "data"

CHECKS = ("podium_flat", "podium_curved", "podium_asce7_22", "bridge_pier", "shake_table_F02", "cylinder")

SIMULATIONS = {
    "podium_flat_ricker": ("podium_flat", "ricker-anti:ap=3m/s^2,Tp=0.8s", None),
    "podium_flat_record": ("podium_flat", "record:p695-ff/11a", None),
    "podium_curved_record": ("podium_curved", "record:p695-ff/19b,scale=0.8", None),
    "bridge_pier_linear": ("bridge_pier", "ricker-sym:ap=4m/s^2,Tp=1.0s", "linear"),
    "bridge_pier_linear_exact": ("bridge_pier", "ricker-anti:ap=5m/s^2,Tp=1.2s", "linear-exact"),
    "cylinder_record": ("cylinder", "record:p695-ff/1,resultant_pga=0.3g", None),
}

VOLATILE = {("project", "tool_version"), ("project", "kernels_sha256")}
"""The only keys allowed to differ (timings are not in the files): the version, and the digest of the kernel
sources, which changes with any edit of a kernel (rockdesign.kernel_cache)."""


def _cli(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "rockdesign.cli", *args], cwd=cwd, capture_output=True,
                          text=True, timeout=900)


def run_check(name: str, out: Path) -> dict:
    proc = _cli("check", f"examples/{name}.toml", "--no-pdf", "-o", str(out), cwd=ROOT)
    if proc.returncode not in (0, 1):
        raise RuntimeError(f"check {name} exited {proc.returncode}: {proc.stderr[-2000:]}")
    return normalised(json.loads((out / "results.json").read_text()))


def run_simulation(key: str) -> dict:
    example, motion, model = SIMULATIONS[key]
    args = ["simulate", f"examples/{example}.toml", "--motion", motion, "--json"]
    if model:
        args += ["--model", model]
    proc = _cli(*args, cwd=ROOT)
    if proc.returncode != 0:
        raise RuntimeError(f"simulate {key} exited {proc.returncode}: {proc.stderr[-2000:]}")
    return normalised(json.loads(proc.stdout))


def normalised(doc: dict) -> dict:
    for path in VOLATILE:
        node = doc
        for key in path[:-1]:
            node = node.get(key, {}) if isinstance(node, dict) else {}
        if isinstance(node, dict):
            node.pop(path[-1], None)
    return doc


def differences(expected, found, path: str = "", rel: float = 1e-9) -> list[str]:
    """Where ``found`` differs from ``expected``: keys, types, strings and integers exactly; floats to a
    relative 1e-9 (the last bits of a float may differ between CPUs; a real change moves far more)."""
    if isinstance(expected, dict) and isinstance(found, dict):
        out = [f"{path}.{k}: missing" for k in expected if k not in found]
        out += [f"{path}.{k}: new key" for k in found if k not in expected]
        for k in expected:
            if k in found:
                out += differences(expected[k], found[k], f"{path}.{k}", rel)
        return out
    if isinstance(expected, list) and isinstance(found, list):
        if len(expected) != len(found):
            return [f"{path}: {len(expected)} items expected, {len(found)} found"]
        return [d for i, (a, b) in enumerate(zip(expected, found)) for d in differences(a, b, f"{path}[{i}]", rel)]
    if isinstance(expected, float) and isinstance(found, float):
        same = (math.isnan(expected) and math.isnan(found)) or math.isclose(expected, found, rel_tol=rel,
                                                                            abs_tol=1e-300)
        return [] if same else [f"{path}: {expected!r} expected, {found!r} found"]
    if type(expected) is not type(found) or expected != found:
        return [f"{path}: {expected!r} expected, {found!r} found"]
    return []
