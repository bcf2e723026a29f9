"""What the solver stability study records: per failure condition (:class:`StabilityCase`), one
:class:`Outcome` per method.  The cases (:mod:`.stability_cases`) produce them, :mod:`.stability` runs
and tabulates them."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

ALL_METHODS = ("rockdesign", "scipy RK45", "scipy DOP853", "scipy LSODA", "scipy Radau")
VERDICTS = ("ok", "degrades", "fails")


@dataclass
class Outcome:
    """How one method fares in one case.

    Attributes:
        method: method name (:data:`ALL_METHODS`).
        verdict: ``ok`` | ``degrades`` (right answer at a higher cost or lower accuracy than asked)
            | ``fails`` (wrong answer, crash, hang guard tripped) | ``n/a``.
        detail: the measured evidence in one sentence.
        data: the numbers behind it.
    """

    method: str
    verdict: str
    detail: str
    data: dict = field(default_factory=dict)


@dataclass
class StabilityCase:
    """One failure condition of the study.

    Attributes:
        key: short identifier (file names).
        condition: the failure condition (table row title).
        setup: how it is provoked (system, excitation, tolerances).
        outcomes: one :class:`Outcome` per method run.
        engine: diagnosed result of our engine (status, counters, the run it comes from).
        engine_behaviour: what our engine does in this case (mechanism and measured effect).
        plot: callable returning the evidence figure (``plot(case)``), or None.
        data: arrays and numbers for the plot.
        seconds: wall time of the case [s].
    """

    key: str
    condition: str
    setup: str
    outcomes: list[Outcome]
    engine: dict
    engine_behaviour: str
    plot: Callable | None = None
    data: dict = field(default_factory=dict)
    seconds: float = 0.0

    def outcome(self, method: str) -> Outcome | None:
        return next((o for o in self.outcomes if o.method == method), None)

    @property
    def diagnosed(self) -> bool:
        """True when our engine's result carries a status and its counters."""
        return bool(self.engine) and "status" in self.engine

    def as_json(self) -> dict:
        return {"key": self.key, "condition": self.condition, "setup": self.setup,
                "outcomes": [{"method": o.method, "verdict": o.verdict, "detail": o.detail} for o in self.outcomes],
                "engine": self.engine, "engine_behaviour": self.engine_behaviour, "seconds": self.seconds}
