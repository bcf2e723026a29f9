"""Governing records and the governing check: each decided in one place (checks/governing.py,
criteria.decide)."""
from __future__ import annotations

from rockdesign.acceptance.criteria import CheckItem, decide
from rockdesign.planar.checks.governing import capped_ratio, history_records, model_check_records


def test_history_records_are_the_closest_to_capacity_with_overturning_ties_in_suite_order():
    ratios = [0.2, 9.0, 0.95, 1.3, 10.5, 0.5]
    assert history_records(ratios) == [1, 4, 3]          # 9.0 and 10.5 both cap at 2: suite order
    assert history_records(ratios, 5) == [1, 4, 3, 2, 5]


def test_model_check_prefers_near_capacity_records_that_do_not_overturn():
    ratios = [0.2, 9.0, 0.95, 1.3, 10.5, 0.5]
    overturned = [False, True, False, False, True, False]
    assert model_check_records(ratios, overturned) == [3, 1, 4, 2]
    assert capped_ratio(9.0, True) == 1.0 and capped_ratio(1.7, False) == 1.5 and capped_ratio(0.4, False) == 0.4


def _item(key, utilisation, governs, passed=True):
    return CheckItem(key=key, name=key, role="governs" if governs else "informative", utilisation=utilisation,
                     passed=passed, detail="", verdict_reason=key, source="")


def test_decide_names_the_governing_check_once():
    items = [_item("a", 0.4, True), _item("b", 0.9, False), _item("c", 0.7, True)]
    assert decide(items).governing == "c"        # the largest utilisation among the deciding checks
    assert decide([_item("b", 0.9, False)]).governing is None
