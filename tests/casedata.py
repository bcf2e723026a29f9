"""The published and independently recomputed reference numbers the tests compare with.

``tests/validation/data/cases.json`` (a copy of the project's validation cases: numbers from the
thesis with their inputs, expected value, tolerance, source and how each was obtained — no
third-party text) is the only place a published number lives.  Tests read it with
:func:`expected` / :func:`case` or compare with :func:`assert_case`; a case id written as a literal in
one of these calls (or as a key of a validation module's ``COMPUTE``) counts as compared in
``tests/validation/test_coverage.py``.
"""
from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

DATA = Path(__file__).resolve().parent / "validation" / "data"


@lru_cache(maxsize=1)
def all_cases() -> dict[str, dict]:
    """Every case of cases.json by id."""
    return {c["id"]: c for c in json.loads((DATA / "cases.json").read_text(encoding="utf-8"))}


def case(case_id: str) -> dict:
    """One case: ``source``, ``inputs``, ``quantity``, ``expected``, ``tolerance``, ``notes``..."""
    return all_cases()[case_id]


def expected(case_id: str):
    """The ``expected`` value of a case (a number, a bool or a list)."""
    return case(case_id)["expected"]


def tolerance(case_id: str):
    """The absolute ``tolerance`` of a case (a number or a list matching ``expected``)."""
    return case(case_id)["tolerance"]


def printed_precision(value) -> float:
    """Half a unit of the last printed decimal of a reference value (cases.json rounds to ~6 digits
    while some tolerances are 1e-9: the comparison cannot be tighter than the printed number)."""
    text = repr(float(value))
    if "e" in text or "." not in text or text.endswith(".0"):
        return 0.0                  # a whole number (0.0, 1.0, a count) is exact, not rounded to 0.1
    return 0.5 * 10.0 ** -len(text.split(".")[1])


def assert_case(case_id: str, got, *, tol=None) -> None:
    """Assert that ``got`` matches the case's expected value within its tolerance (per element for lists;
    booleans exactly; ``None`` tolerances in a list mean an exact comparison)."""
    want = expected(case_id)
    tol = tolerance(case_id) if tol is None else tol
    if isinstance(want, list):
        tols = tol if isinstance(tol, list) else [tol] * len(want)
        got = list(got)
        assert len(got) == len(want), (case_id, got, want)
        for g, e, t in zip(got, want, tols):
            _compare(case_id, g, e, t)
    else:
        _compare(case_id, got, want, tol)


def _compare(case_id, got, want, tol):
    if isinstance(want, bool) or tol is None:
        assert got == want, (case_id, got, want)
    else:
        assert abs(got - want) <= max(tol, printed_precision(want)), (case_id, got, want, tol)


def case_tests(compute: dict):
    """A test parametrized over ``compute`` (case id → function computing the case's quantity)."""
    import pytest

    @pytest.mark.parametrize("case_id", sorted(compute))
    def test_case(case_id):
        assert_case(case_id, compute[case_id]())

    return test_case
