"""Acceptance of a rocking design: the rule an engineer recognises (SPEC §14, docs/model.md "Verdict").

``[analysis] risk_category`` (I–IV) and ``acceptance`` choose the rule:

- ``asce7`` (default) — ASCE 7-22 Ch. 16 with a FEMA P695 collapse margin.  The project's design
  intensity is taken as the MCE_R level.  Governing: (1) every analysis completed; (2) at most
  :data:`ALLOWED_UNACCEPTABLE` ground motions with an unacceptable response (§16.4.1.1: one for risk
  category I/II, none for III/IV), overturning being the unacceptable response and a ground motion
  (a station's pair) unacceptable when any analysed component overturns; (3) the collapse margin at
  the category's target probability of collapse x (Table 1.3-2: 10 %, 10 %, 5 %, 2.5 %):
  ACMR ≥ ACMR_x = exp(−β_TOT Φ⁻¹(x)) (FEMA P695 Eq 7-4 adapted, SPEC §11).  A suite needs at least
  :data:`MIN_GROUND_MOTIONS_ASCE7` ground motions (§16.2.2).
- ``binomial`` — the nonparametric alternative: the one-sided 95 % Clopper–Pearson bound of
  P(overturn) over the independent ground motions must not exceed the limit (the category's target,
  or ``overturn_probability_limit`` when the project sets it), at the design level and at every
  intensity up to it.  A suite needs :func:`minimum_ground_motions` ground motions (29 for 10 %).

The criteria themselves are in :mod:`rockdesign.acceptance.overturning_criteria`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable

from ..errors import ProjectError
from .outcome import Outcome
from .statistics import overturning_probability

RISK_CATEGORIES = ("I", "II", "III", "IV")
METHODS = ("asce7", "binomial")
TARGET_P_COLLAPSE = {"I": 0.10, "II": 0.10, "III": 0.05, "IV": 0.025}
"""ASCE 7-22 Table 1.3-2: target probability of total or partial collapse conditioned on MCE_R shaking."""
ALLOWED_UNACCEPTABLE = {"I": 1, "II": 1, "III": 0, "IV": 0}
"""ASCE 7-22 §16.4.1.1: ground motions of a suite (of at least 11) allowed an unacceptable response."""
MIN_GROUND_MOTIONS_ASCE7 = 11
"""ASCE 7-22 §16.2.2: at least eleven ground motions (pairs for a 3D analysis)."""
ONE_SIDED_CONFIDENCE = 0.95
"""Confidence of the binomial upper bound on P(overturn) (the upper end of the two-sided 90 % interval)."""
METHOD_LABELS = {"asce7": "ASCE 7-22 §16.4 with a FEMA P695 collapse margin",
                 "binomial": "binomial bound over ground motions"}


def minimum_records(limit: float, confidence: float = ONE_SIDED_CONFIDENCE) -> int | None:
    """Smallest number n of independent trials whose one-sided bound with none failing, 1 − (1−c)^(1/n),
    is ≤ limit.

    n = ⌈ln(1 − c)/ln(1 − limit)⌉ (Clopper & Pearson 1934 with k = 0); None when no n suffices
    (limit ≤ 0).  limit = 10 %, c = 95 %: 29.
    """
    if limit <= 0.0:
        return None
    if limit >= 1.0:
        return 1
    n = math.ceil(math.log(1.0 - confidence) / math.log(1.0 - limit) - 1e-12)
    return max(1, n)


def probability_bound(k: int, n: int) -> float:
    """One-sided 95 % upper bound on P(overturn) from k of n independent trials (Clopper–Pearson)."""
    if n <= 0:
        return 1.0
    return overturning_probability(k, n, 2.0 * ONE_SIDED_CONFIDENCE - 1.0)[2]


def pct(x: float) -> str:
    """A probability as a percentage for the verdict's text (4.7 %)."""
    return f"{100 * x:.2g} %" if x < 0.1 else f"{100 * x:.3g} %"


@dataclass(frozen=True)
class AcceptanceRule:
    """The acceptance rule of a check: method, risk category, target P(collapse) and what it allows.

    ``target`` [-]: P(collapse | MCE_R) of ASCE 7-22 Table 1.3-2; ``allowed``: unacceptable ground
    motions allowed (§16.4.1.1); ``binomial_limit`` [-]: the limit of the binomial bound;
    ``collapse_margin_available``: the check has an incremental analysis (False for a kind whose check
    has none — its verdict is then the count rule alone, and says so).
    """

    method: str = "asce7"
    risk_category: str = "II"
    target: float = 0.10
    allowed: int = 1
    binomial_limit: float = 0.10
    collapse_margin_available: bool = True

    @property
    def label(self) -> str:
        """How the verdict names the method ("ASCE 7-22 §16.4, risk category II")."""
        if self.method == "binomial":
            return (f"binomial bound over ground motions, P ≤ {pct(self.binomial_limit)}, "
                    f"risk category {self.risk_category}")
        return f"ASCE 7-22 §16.4, risk category {self.risk_category}"

    @property
    def minimum_ground_motions(self) -> int | None:
        """Ground motions a suite needs for this rule to be decidable (None: no suite suffices)."""
        if self.method == "binomial":
            return minimum_records(self.binomial_limit)
        return MIN_GROUND_MOTIONS_ASCE7

    def with_collapse_margin(self, available: bool) -> "AcceptanceRule":
        """The same rule for a check with (or without) an incremental analysis."""
        return AcceptanceRule(self.method, self.risk_category, self.target, self.allowed, self.binomial_limit,
                              available)

    def as_json(self) -> dict:
        label = METHOD_LABELS[self.method]
        if self.method == "asce7" and not self.collapse_margin_available:
            label = "ASCE 7-22 §16.4 count of unacceptable ground motions (the check has no incremental analysis)"
        return {"method": self.method, "method_label": label, "risk_category": self.risk_category,
                "target_p_collapse": self.target, "allowed_unacceptable": self.allowed,
                "binomial_limit": self.binomial_limit, "min_ground_motions": self.minimum_ground_motions}


def acceptance_rule(analysis) -> AcceptanceRule:
    """The rule of a project's ``[analysis]`` (``risk_category``, ``acceptance``, ``overturn_probability_limit``)."""
    cat = getattr(analysis, "risk_category", "II")
    method = getattr(analysis, "acceptance", "asce7")
    target = TARGET_P_COLLAPSE[cat]
    limit = analysis.overturn_probability_limit if getattr(analysis, "overturn_probability_limit_set", False) \
        else target
    return AcceptanceRule(method, cat, target, ALLOWED_UNACCEPTABLE[cat], limit)


def require_suite_size(rule: AcceptanceRule, n_ground_motions: int, n_records: int, suites, *, file=None,
                       key: str = "excitation", missing=()) -> None:
    """Refuse, before any analysis, a suite with fewer ground motions than the rule needs.

    ``missing``: ids of the suite's records that were not found (named in the message).

    Raises:
        ProjectError: naming the suite(s), the ground motions and records it has and the number needed.
    """
    need = rule.minimum_ground_motions
    if need is not None and n_ground_motions >= need:
        return
    names = ", ".join(suites) if suites else "the records of [excitation]"
    why = ("ASCE 7-22 §16.2.2 asks for at least 11 ground motions" if rule.method == "asce7" else
           f"with none overturning, the one-sided 95 % bound of P(overturn) over n ground motions is "
           f"1 − 0.05^(1/n) and reaches {pct(rule.binomial_limit)} only from n = {need}" if need else
           "no suite can show a probability limit of 0")
    raise ProjectError(
        f"the suite is too small for the acceptance rule ({rule.label}): {why}", file=file, key=key,
        expected=(f"at least {need} independent ground motions" if need else "a positive probability limit"),
        found=f"{names}: {n_ground_motions} ground motion(s) from {n_records} record(s)"
        + (f"; {len(missing)} record(s) not found: {', '.join(missing[:5])}{' …' if len(missing) > 5 else ''}"
           if missing else ""),
        hint="add suites (e.g. suites = [\"p695-farfield\", \"p695-nearfield-pulse\"]), group your own records "
             "with the suite file's ground_motion key, or choose [analysis] acceptance"
             if rule.method == "binomial" else "add records from further stations (each station's pair is one "
             "ground motion), e.g. suites = [\"p695-farfield\"] (22 ground motions)")


def ground_motion_of(outcome) -> str:
    """The ground-motion id of an analysed record (its own id when the outcome has none)."""
    return getattr(outcome, "ground_motion", None) or outcome.id


def ground_motions_in_order(outcomes) -> list[str]:
    """The distinct ground motions of a list of outcomes, in suite order."""
    seen: dict[str, None] = {}
    for o in outcomes:
        seen.setdefault(ground_motion_of(o), None)
    return list(seen)


def unacceptable_ground_motions(outcomes, overturned_ids) -> list[str]:
    """Ground motions (suite order) with at least one component among ``overturned_ids``."""
    bad = {ground_motion_of(o) for o in outcomes if o.id in overturned_ids}
    return [g for g in ground_motions_in_order(outcomes) if g in bad]


def count_rule(rule: AcceptanceRule, outcomes, overturned_ids) -> tuple[bool, int, int, float]:
    """(holds, unacceptable ground motions k, ground motions n, utilisation) of the design-level rule
    for one draw of the suite: the §16.4.1.1 count (asce7) or the binomial bound (binomial)."""
    k = len(unacceptable_ground_motions(outcomes, overturned_ids))
    n = len(ground_motions_in_order(outcomes))
    if rule.method == "binomial":
        upper = probability_bound(k, n)
        limit = rule.binomial_limit
        return upper <= limit, k, n, upper / limit if limit > 0 else math.inf
    allowed = rule.allowed
    util = k / allowed if allowed else (0.0 if k == 0 else 1.0 + k)
    return k <= allowed, k, n, util


def ground_motion_table(outcomes: Iterable[Outcome]) -> list[dict]:
    """Per ground motion: its records, earthquake, station, whether it is unacceptable at the design
    level, the lowest first-overturning factor of its components and the largest response ratio
    (:attr:`~rockdesign.acceptance.outcome.Run.response_ratio`: θ_max/θc of a planar column, Eq 3.56; results.json
    keeps its key ``theta_max_over_theta_c``)."""
    rows: dict[str, dict] = {}
    for o in outcomes:
        g = ground_motion_of(o)
        meta = getattr(o, "meta", {}) or {}
        row = rows.setdefault(g, {"id": g, "records": [], "event": meta.get("event"), "year": meta.get("year"),
                                  "station": meta.get("station"), "unacceptable": False, "first_overturn_scale": None,
                                  "theta_max_over_theta_c": 0.0})
        row["records"].append(o.id)
        row["unacceptable"] = row["unacceptable"] or bool(o.run.overturned)
        row["theta_max_over_theta_c"] = max(row["theta_max_over_theta_c"], float(o.run.response_ratio))
        m = getattr(o, "margin", None)
        s = 1.0 if o.run.overturned and (m is None or m.overturn_scale is None or m.overturn_scale > 1.0) else \
            (None if m is None else m.overturn_scale)
        if s is not None:
            cur = row["first_overturn_scale"]
            row["first_overturn_scale"] = s if cur is None else min(cur, s)
    return list(rows.values())


def first_overturn_scale(outcome) -> float | None:
    """The first overturning factor of a record on its design-level scaling: the incremental analysis's
    lowest overturning factor, or 1 when the design-level analysis itself overturned below that (a
    chaotic response: the nominal analysis is one more observation); None when neither overturned."""
    m = getattr(outcome, "margin", None)
    s = None if m is None else m.overturn_scale
    run = getattr(outcome, "run", None)
    if run is not None and run.overturned and (s is None or s > 1.0):
        return 1.0
    return s
