"""README's numbers that come from a measurement are the measurement (scripts/readme_numbers.py writes them):
the README promised 1,652 fast tests when the loop ran 1,651, and a 22-page PDF of 23 pages."""
from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import readme_numbers  # noqa: E402  (a script, not a package)

TEXT = ("the fast loop (1,652 tests) takes about 3 minutes and the whole suite (1,742 tests) about 9 minutes; "
        "an 22-page PDF report; ensembles, 22-page PDF) |")


def test_stale_numbers_are_named_and_rewritten():
    numbers = {"fast tests": (re.compile(r"the fast loop \(([\d,]+) tests\)"), "1,651"),
               "all tests": (re.compile(r"the whole suite \(([\d,]+) tests\)"), "1,742"),
               "pages": (re.compile(r"ensembles, (\d+)-page PDF\)"), "25")}
    assert readme_numbers.stale(TEXT, numbers) == ["fast tests: README says 1,652, measured 1,651",
                                                   "pages: README says 22, measured 25"]
    fixed = readme_numbers.rewrite(TEXT, numbers)
    assert "the fast loop (1,651 tests)" in fixed and "ensembles, 25-page PDF)" in fixed
    assert readme_numbers.stale(fixed, numbers) == []


def test_a_missing_phrase_is_stale_too():
    numbers = {"pages": (re.compile(r"an (\d+)-page PDF report"), "25")}
    assert readme_numbers.stale("no such phrase", numbers) == ["pages: phrase 'an (\\\\d+)-page PDF report' not in README.md"]


@pytest.mark.slow       # two pytest --collect-only runs (≈ 30 s)
def test_the_readme_states_the_test_counts_pytest_collects():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert readme_numbers.stale(text, readme_numbers.measured(tests_only=True)) == [], \
        "run python scripts/readme_numbers.py"
