"""A check's demand/limit reads as what it is (issue 50: the console's "demand/limit (≤ 1 passes)" column showed
1.98 for a 95 % bound of 0.198 against 0.10, read as "1.98 ground motions")."""
from __future__ import annotations

import io

from rich.console import Console

from rockdesign.display import RATIO_HEADING, check_summary, utilisation_text


def test_a_utilisation_is_written_as_a_multiple_of_its_limit():
    assert utilisation_text(1.9812213163688157) == "1.98 × limit"
    assert utilisation_text(0.0) == "0 × limit" and utilisation_text(0.67) == "0.67 × limit"
    assert utilisation_text(1e9) == "— (cannot pass)" and utilisation_text(None) == "—"


def test_the_console_table_prints_the_multiple_under_its_heading():
    data = {"project": {"name": "p"}, "verdict": "PASS", "verdict_reason": "PASS", "checks": [
        {"criterion": "overturning_probability", "name": "RHA: P(overturn) ≤ 10 % at 95 % confidence over ground "
         "motions", "utilisation": 1.98122, "passed": False, "governs_verdict": False, "role": "informative"}]}
    out = io.StringIO()
    check_summary(data, None, Console(file=out, width=200, color_system=None))
    text = out.getvalue()
    assert RATIO_HEADING in text and "1.98 × limit" in text
    assert " 1.98 " not in text.replace("1.98 × limit", "")
