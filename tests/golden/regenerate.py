"""Rewrite the pinned outputs (``python tests/golden/regenerate.py [NAME ...]``): only for a deliberate
change of the numbers a user sees, explained in the commit message.  NAMEs (``podium_flat``,
``cylinder_record``, ...) restrict it to those checks and simulations; without any, all are rewritten."""
from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from golden_cases import CHECKS, DATA, SIMULATIONS, run_check, run_simulation  # noqa: E402 (not a package)


def main(names: list[str]) -> None:
    unknown = set(names) - set(CHECKS) - set(SIMULATIONS)
    if unknown:
        raise SystemExit(f"unknown golden case(s): {', '.join(sorted(unknown))}; known: "
                         + ", ".join((*CHECKS, *SIMULATIONS)))
    with tempfile.TemporaryDirectory() as tmp:
        for name in (n for n in CHECKS if not names or n in names):
            doc = run_check(name, Path(tmp) / name)
            (DATA / "check" / f"{name}.json").write_text(json.dumps(doc, indent=1, sort_keys=True) + "\n")
            print("check", name)
    for key in (k for k in SIMULATIONS if not names or k in names):
        (DATA / "simulate" / f"{key}.json").write_text(json.dumps(run_simulation(key), indent=1, sort_keys=True)
                                                       + "\n")
        print("simulate", key)


if __name__ == "__main__":
    main(sys.argv[1:])
