"""The building blocks of the check's criteria: roles, the typed :class:`CheckItem`, the
:class:`CheckContext` the criteria read and the :class:`Criterion` base class (docs/model.md §8).

The criteria themselves are in :mod:`rockdesign.acceptance.criteria` (completion, Polyakov's rules, the
lists and the verdict) and :mod:`rockdesign.acceptance.overturning_criteria` (the acceptance rules).
"""
from __future__ import annotations

import abc
import math
from dataclasses import dataclass, field

from .rule import AcceptanceRule, acceptance_rule

GOVERNS = "governs"
ROBUSTNESS = "robustness"
INFORMATIVE = "informative"

PASS, FAIL, NOT_DECIDED = "PASS", "FAIL", "NOT DECIDED"

UTILISATION_CAP = 1e9
"""Utilisations are capped here (a criterion that cannot pass, e.g. a zero probability limit)."""


@dataclass(frozen=True)
class CheckItem:
    """One evaluated criterion, as it appears in results.json's ``checks``.

    ``utilisation`` ≤ 1 exactly when ``passed`` (demand over capacity of that criterion).
    ``verdict_reason`` is the short phrase the verdict quotes ("overturning at 0.92× design (p695-ff/11a)").
    ``perturbations``: robustness items only — (label, the governing criterion holds) per perturbed run.
    """

    key: str
    name: str
    utilisation: float
    passed: bool
    role: str
    detail: str
    verdict_reason: str
    source: str
    perturbations: tuple[tuple[str, bool], ...] = ()
    evaluated: bool = True
    """False: the criterion could not be decided from this run (it then neither passes nor fails)."""

    @property
    def governs_verdict(self) -> bool:
        return self.role == GOVERNS

    def as_json(self) -> dict:
        return {"name": self.name, "utilisation": self.utilisation, "passed": self.passed,
                "governs_verdict": self.governs_verdict, "detail": self.detail,
                "verdict_reason": self.verdict_reason, "criterion": self.key, "role": self.role,
                "source": self.source, "evaluated": self.evaluated}


@dataclass
class CheckContext:
    """What the criteria read: the suite's record outcomes and the settings.

    Attributes:
        outcomes: :class:`~rockdesign.planar.checks.check.RecordOutcome` of every record analysed (failed ones too).
        analysis: the project's ``[analysis]`` settings.
        quantities: design quantities (``omega_s_over_p`` for Polyakov rule 1).
        sensitivity: the c_r ± variation runs ({"variation", "runs": {label: {"restitution_factor",
            "n_overturned", "n_records", "records", ...}}}).
        margins_run: the incremental analysis was run.
        extra: data of further criteria (e.g. perturbation ensembles), keyed by their name.
        rule: the acceptance rule (default: from ``analysis``, :func:`~rockdesign.acceptance.rule.acceptance_rule`).
    """

    outcomes: list
    analysis: object
    quantities: dict = field(default_factory=dict)
    sensitivity: dict = field(default_factory=dict)
    margins_run: bool = True
    extra: dict = field(default_factory=dict)
    rule: AcceptanceRule | None = None

    def __post_init__(self):
        if self.rule is None:
            self.rule = acceptance_rule(self.analysis)

    @property
    def valid(self) -> list:
        """Outcomes whose analysis ran to a conclusion."""
        return [o for o in self.outcomes if not o.run.failed]

    @property
    def failed(self) -> list:
        return [o for o in self.outcomes if o.run.failed]


class Criterion(abc.ABC):
    """A design criterion: subclasses set ``key``, ``name``, ``role``, ``source`` and implement evaluate."""

    key = "criterion"
    name = "criterion"
    role = INFORMATIVE
    source = ""
    optional = False
    """True: when it does not apply (switched off by the user), the verdict does not list it as not covered."""

    def applies(self, ctx: CheckContext) -> bool:
        """False when the criterion cannot be evaluated for this check (it is then left out)."""
        return True

    def required(self, ctx: CheckContext) -> bool:
        """True when leaving the criterion out leaves the verdict undecided (governing ones by default)."""
        return self.role != INFORMATIVE and not self.optional

    @abc.abstractmethod
    def evaluate(self, ctx: CheckContext) -> CheckItem:
        """The criterion's item for this check (utilisation, passed, detail, the verdict's phrase)."""

    def item(self, utilisation: float, passed: bool, detail: str, reason: str, **kw) -> CheckItem:
        u = float(utilisation)
        u = min(u, UTILISATION_CAP) if not math.isnan(u) else UTILISATION_CAP   # JSON has no ∞
        return CheckItem(self.key, kw.pop("name", self.name), u, bool(passed), self.role, detail,
                         reason, self.source, **kw)
