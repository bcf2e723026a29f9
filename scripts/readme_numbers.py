"""Rewrite the numbers README.md states from a measurement on this code, or check them (``--check``).

    python scripts/readme_numbers.py            measure, then rewrite README.md where a number moved
    python scripts/readme_numbers.py --check    measure, exit 1 naming every stale number (README untouched)
    python scripts/readme_numbers.py --tests    only the test counts (no check is run)

What it measures, each with the README phrase it writes:

* the tests the fast loop runs (``pytest --collect-only -m 'not slow'``) — "the fast loop (N tests)";
* the tests of the whole suite (``pytest --collect-only``) — "the whole suite (N tests)";
* the pages of the main job's calculation report and of ``examples/podium_flat.toml``'s (``rockdesign check``
  into a temporary folder, pages of report.pdf by pypdf) — "a PDF report of N pages" and the speed table's
  "N-page PDF".

Times are not rewritten here: they depend on the machine's load and are stated with it (benchmarks/).
"""
from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
MAIN_JOB = "examples/podium_asce7_22.toml"
"""The project of README's first command (its records follow ASCE 7-22 §16.2, the standard its verdict cites)."""


def test_count(*marks: str) -> int:
    """Tests pytest collects (``marks``: its ``-m`` expression, e.g. ``not slow``)."""
    args = [sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider"]
    if marks:
        args += ["-m", " and ".join(marks)]
    out = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, check=True).stdout
    found = re.search(r"(\d+)(?:/\d+)? tests? (?:collected|selected)", out)
    if not found:
        raise RuntimeError(f"pytest did not say how many tests it collected:\n{out[-2000:]}")
    return int(found.group(1))


def report_pages(project: str) -> int:
    """Pages of ``rockdesign check PROJECT``'s report.pdf."""
    import pypdf
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "check"
        done = subprocess.run([sys.executable, "-m", "rockdesign.cli", "check", project, "-o", str(out)], cwd=ROOT,
                              capture_output=True, text=True)
        if done.returncode not in (0, 1):
            raise RuntimeError(f"rockdesign check {project} exited {done.returncode}: {done.stderr[-2000:]}")
        return len(pypdf.PdfReader(str(out / "report.pdf")).pages)


def _thousands(n: int) -> str:
    return f"{n:,}"


def measured(tests_only: bool = False) -> dict[str, tuple[re.Pattern, str]]:
    """README pattern (one group: the number) → the measured text, for every number this script owns."""
    out = {"fast tests": (re.compile(r"the fast loop \(([\d,]+) tests\)"), _thousands(test_count("not slow"))),
           "all tests": (re.compile(r"the whole suite \(([\d,]+) tests\)"), _thousands(test_count()))}
    if not tests_only:
        out["main job pages"] = (re.compile(r"a PDF report of (\d+) pages"), str(report_pages(MAIN_JOB)))
        out["podium_flat pages"] = (re.compile(r"ensembles, (\d+)-page PDF\)"),
                                    str(report_pages("examples/podium_flat.toml")))
    return out


def stale(text: str, numbers: dict) -> list[str]:
    """The README numbers that differ from ``numbers`` (or whose phrase is missing)."""
    found = []
    for name, (pattern, value) in numbers.items():
        hits = pattern.findall(text)
        if not hits:
            found.append(f"{name}: phrase {pattern.pattern!r} not in README.md")
        found += [f"{name}: README says {hit}, measured {value}" for hit in hits if hit != value]
    return found


def rewrite(text: str, numbers: dict) -> str:
    """``text`` with every number of ``numbers`` written as measured."""
    for pattern, value in numbers.values():
        text = pattern.sub(lambda m: m.group(0).replace(m.group(1), value), text)
    return text


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 when a number is stale; README untouched")
    parser.add_argument("--tests", action="store_true", help="only the test counts")
    args = parser.parse_args()
    numbers = measured(tests_only=args.tests)
    text = README.read_text(encoding="utf-8")
    problems = stale(text, numbers)
    for line in problems:
        print(line)
    if args.check:
        return 1 if problems else 0
    if problems:
        README.write_text(rewrite(text, numbers), encoding="utf-8")
        print("README.md rewritten")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
