"""The verdict's headline names how the records were scaled when they do not follow the standard its rule cites
(issue 50: podium_flat read "PASS (ASCE 7-22 §16.4, risk category II)" on records scaled to PGA)."""
from __future__ import annotations

import pytest

from rockdesign.acceptance.criteria import decide
from rockdesign.acceptance.rule import AcceptanceRule
from rockdesign.motions.scaling_report import headline_basis


@pytest.mark.parametrize("block, words", [
    ({"standard": None, "method": "pga"}, "records scaled to PGA, not per ASCE 7-22 §16.2"),
    ({"standard": None, "method": "resultant_pga"}, "record pairs scaled to a resultant PGA, not per ASCE 7-22 §16.2"),
    ({"standard": None, "method": "per suite: factor, pga"},
     "records scaled per suite (factor, pga), not per ASCE 7-22 §16.2"),
    ({"standard": "ASCE 7-22 §16.2.3", "conformant": False},
     "records scaled per ASCE 7-22 §16.2.3, not conformant"),
    ({"standard": "ASCE 7-22 §16.2.3", "conformant": True}, ""),
    (None, ""),
])
def test_the_basis_a_headline_names(block, words):
    assert headline_basis(block) == words


def test_the_headline_names_the_rule_and_the_records_basis():
    verdict = decide([], (), AcceptanceRule(), basis=headline_basis({"standard": None, "method": "pga"}))
    assert verdict.reason.startswith("PASS (ASCE 7-22 §16.4, risk category II; records scaled to PGA, not per "
                                     "ASCE 7-22 §16.2)")
    assert decide([], (), AcceptanceRule()).reason.startswith("PASS (ASCE 7-22 §16.4, risk category II)")
