"""The design criteria of ``rockdesign check`` and the one verdict that combines them.

Pattern of concreteproperties' ``DesignCode``: one class per criterion, each citing its source and
returning a typed :class:`CheckItem`; :func:`evaluate_criteria` runs a list of them and
:func:`decide` turns the items into the :class:`Verdict`.  Adding a criterion is one class: subclass
:class:`Criterion`, set ``key``, ``role`` and ``source``, implement :meth:`Criterion.evaluate`, and
append the class to :data:`CRITERIA` (or pass your own list).  Data a criterion needs beyond the
suite run (e.g. perturbation ensembles) travels in :attr:`CheckContext.extra`.

Roles (documented for users in ``docs/model.md``, "Verdict"):

- ``governs``: decides PASS/FAIL.  Every governing item must pass.
- ``robustness``: does not change the word PASS/FAIL but says whether it survives a perturbation of
  an uncertain input (``verdict_robust``; "PASS, not robust: fails with c_r − 2 %").
- ``informative``: reported for comparison (Polyakov's rules of thumb, largest rotation).

Statistics: single rocking histories are not predictable (thesis Ch. 6–7), so the overturning
criteria bound the probability of overturning over the suite with the exact (Clopper–Pearson)
binomial interval: the one-sided 95 % upper bound must not exceed the limit.  With k = 0 that bound
is 1 − 0.05^(1/n), so a suite of fewer than :func:`minimum_records` records can never pass.
"""
from __future__ import annotations

import abc
import math
import statistics
from dataclasses import dataclass, field

from .statistics import overturning_probability
from ..dynamics.layout import COMPLETED_STATUSES, STATUS_NAMES

GOVERNS = "governs"
ROBUSTNESS = "robustness"
INFORMATIVE = "informative"

ONE_SIDED_CONFIDENCE = 0.95
"""Confidence of the upper bound on P(overturn) (the upper end of the two-sided 90 % interval)."""

VALID_STATUSES = tuple(STATUS_NAMES[code] for code in COMPLETED_STATUSES)
"""Engine statuses of an analysis that ran to a conclusion (see docs/engine.md).  Any other status
(step size collapsed, step or event limit reached) means the analysis failed: the record is
listed as failed and never counted as safe."""


UTILISATION_CAP = 1e9
"""Utilisations are capped here (a criterion that cannot pass, e.g. a zero probability limit)."""


def analysis_failed(status: str) -> bool:
    """True when an engine status (:data:`VALID_STATUSES`) says the analysis did not finish."""
    return status not in VALID_STATUSES


def minimum_records(limit: float, confidence: float = ONE_SIDED_CONFIDENCE) -> int | None:
    """Smallest suite size n whose one-sided upper bound with no overturning, 1 − (1−c)^(1/n), is ≤ limit.

    n = ⌈ln(1 − c)/ln(1 − limit)⌉ (Clopper & Pearson 1934 with k = 0); None when no n suffices
    (limit ≤ 0).  limit = 10 %, c = 95 %: 29 records.
    """
    if limit <= 0.0:
        return None
    if limit >= 1.0:
        return 1
    n = math.ceil(math.log(1.0 - confidence) / math.log(1.0 - limit) - 1e-12)
    return max(1, n)


def probability_bound(k: int, n: int) -> float:
    """One-sided 95 % upper bound on P(overturn) from k overturning records out of n (Clopper–Pearson)."""
    if n <= 0:
        return 1.0
    return overturning_probability(k, n, 2.0 * ONE_SIDED_CONFIDENCE - 1.0)[2]


def _pct(x: float) -> str:
    return f"{100 * x:g} %"


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

    @property
    def governs_verdict(self) -> bool:
        return self.role == GOVERNS

    def as_json(self) -> dict:
        return {"name": self.name, "utilisation": self.utilisation, "passed": self.passed,
                "governs_verdict": self.governs_verdict, "detail": self.detail,
                "verdict_reason": self.verdict_reason, "criterion": self.key, "role": self.role,
                "source": self.source}


@dataclass
class CheckContext:
    """What the criteria read: the suite's record outcomes and the settings.

    Attributes:
        outcomes: :class:`~rockdesign.checks.check.RecordOutcome` of every record analysed (failed ones too).
        analysis: the project's ``[analysis]`` settings.
        quantities: design quantities (``omega_s_over_p`` for Polyakov rule 1).
        sensitivity: the c_r ± variation runs ({"variation", "runs": {label: {"restitution_factor",
            "n_overturned", "n_records", "records", ...}}}).
        margins_run: the incremental analysis was run.
        extra: data of further criteria (e.g. perturbation ensembles), keyed by their name.
    """

    outcomes: list
    analysis: object
    quantities: dict = field(default_factory=dict)
    sensitivity: dict = field(default_factory=dict)
    margins_run: bool = True
    extra: dict = field(default_factory=dict)

    @property
    def valid(self) -> list:
        """Outcomes whose analysis ran to a conclusion."""
        return [o for o in self.outcomes if not analysis_failed(o.run.status)]

    @property
    def failed(self) -> list:
        return [o for o in self.outcomes if analysis_failed(o.run.status)]


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

    @abc.abstractmethod
    def evaluate(self, ctx: CheckContext) -> CheckItem:
        """The criterion's item for this check (utilisation, passed, detail, the verdict's phrase)."""

    def item(self, utilisation: float, passed: bool, detail: str, reason: str, **kw) -> CheckItem:
        u = float(utilisation)
        u = min(u, UTILISATION_CAP) if not math.isnan(u) else UTILISATION_CAP   # JSON has no ∞
        return CheckItem(self.key, kw.pop("name", self.name), u, bool(passed), self.role, detail,
                         reason, self.source, **kw)


def _criterion_text(a) -> str:
    return "θ_max ≥ θc" if a.overturn == "static" else "|θ| = π/2"


class AnalysesCompleted(Criterion):
    """Every analysis ran to a conclusion; a failed one is never counted as safe."""

    key = "analyses_completed"
    name = "RHA: every analysis completed"
    role = GOVERNS
    source = "docs/engine.md (engine statuses); a failed analysis proves nothing about the design"

    def evaluate(self, ctx):
        failed = ctx.failed
        n = len(ctx.outcomes)
        if not failed:
            return self.item(0.0, True, f"all {n} analyses ran to a conclusion", f"all {n} analyses completed")
        listing = ", ".join(f"{o.id} ({o.run.status})" for o in failed)
        return self.item(1.0 + len(failed) / n, False, f"{len(failed)} of {n} analyses failed: {listing}",
                         f"{len(failed)} analysis(es) failed ({listing})")


class OverturningProbability(Criterion):
    """P(overturn) at the design level ≤ limit at 95 % one-sided confidence over the suite."""

    key = "overturning_probability"
    role = GOVERNS
    source = ("thesis Ch. 6–7 (single rocking histories are not predictable: suite statistics); "
              "Clopper & Pearson (1934) exact binomial bound")

    def evaluate(self, ctx):
        a = ctx.analysis
        limit = a.overturn_probability_limit
        valid = ctx.valid
        n, k = len(valid), sum(o.run.overturned for o in valid)
        upper = probability_bound(k, n)
        n_min = minimum_records(limit)
        name = (f"RHA: P(overturn) ≤ {_pct(limit)} at 95 % confidence (one-sided; {a.overturn} criterion: "
                f"{_criterion_text(a)} counts as overturning)")
        util = upper / limit if limit > 0 else math.inf
        passed = upper <= limit
        need = f"needs ≥ {n_min} records" if n_min else "no suite can show it"
        detail = (f"{k} of {n} records overturn at the design level; one-sided 95 % upper bound {upper:.3g} "
                  f"(= upper end of the two-sided 90 % interval); {need}")
        if ctx.extra.get("verdict_basis"):
            detail += "; " + ctx.extra["verdict_basis"]
        if passed:
            reason = f"{k} of {n} records overturn at the design level (P ≤ {upper:.3g} at 95 % confidence)"
        else:
            parts = []
            if k:
                ids = ", ".join(o.id for o in valid if o.run.overturned)
                parts.append(f"{k} of {n} records overturn at the design level ({ids})")
            if n_min is None or n < n_min:
                parts.append(f"{n} records cannot show P(overturn) ≤ {_pct(limit)} at 95 % confidence "
                             f"(the bound {upper:.3g}; {need})")
            elif not k:   # pragma: no cover - k = 0 and n ≥ n_min always passes
                parts.append(f"bound {upper:.3g} > {_pct(limit)}")
            reason = "; ".join(parts)
        return self.item(util, passed, detail, reason, name=name)


class IncrementalMargin(Criterion):
    """No overturning at any intensity up to the design level (responses are not monotonic)."""

    key = "incremental_margin"
    role = GOVERNS
    name = "RHA incremental: P(overturn at some intensity ≤ design) within the limit"
    source = ("thesis Sec 2.2 (Zhang & Makris 2001: safe, overturn, safe again as the amplitude grows); "
              "incremental dynamic analysis (Vamvatsikos & Cornell 2002)")

    def applies(self, ctx):
        return ctx.margins_run

    def evaluate(self, ctx):
        a = ctx.analysis
        limit = a.overturn_probability_limit
        valid = ctx.valid
        below = []      # (factor, id) of records overturning at some factor ≤ 1
        failed_scan = []
        for o in valid:
            m = o.margin
            if m is None:
                continue
            if getattr(m, "failed_scales", None) and min(m.failed_scales) <= 1.0:
                failed_scan.append((min(m.failed_scales), o.id))
            if m.overturn_scale is not None and m.overturn_scale <= 1.0:
                below.append((m.overturn_scale, o.id))
            elif o.run.overturned:
                below.append((1.0, o.id))
        below.sort()
        n, k = len(valid), len(below)
        upper = probability_bound(k, n)
        util = upper / limit if limit > 0 else math.inf
        passed = upper <= limit and not failed_scan
        listing = ", ".join(f"{i} at {f:.3g}×" for f, i in below)
        detail = (f"{k} of {n} records overturn at some intensity up to the design level"
                  + (f" ({listing})" if below else "") + f"; one-sided 95 % bound {upper:.3g}")
        if failed_scan:
            detail += "; incremental analyses failed: " + ", ".join(f"{i} at {f:.3g}×" for f, i in failed_scan)
        if passed:
            reason = f"no intensity up to the design level overturns more than the suite bound allows ({k} of {n})"
        elif below and below[0][0] < 1.0:
            f, rid = below[0]
            reason = f"overturning at {f:.2g}× design ({rid}" + (f" and {k - 1} more)" if k > 1 else ")")
        elif below:
            reason = f"{k} of {n} records overturn at or below the design level"
        else:
            reason = "incremental analyses failed below the design level (" + ", ".join(
                f"{i} at {f:.3g}×" for f, i in failed_scan) + ")"
        if failed_scan and below:
            reason += "; incremental analyses failed for " + ", ".join(i for _, i in failed_scan)
        return self.item(util, passed, detail, reason)


class RestitutionRobustness(Criterion):
    """The design-level probability criterion still holds with c_r × (1 ± variation)."""

    key = "restitution_robustness"
    role = ROBUSTNESS
    source = ("thesis Eqs 3.14, 3.39, 3.80, 4.20 (c_r from conservation of angular momentum, an idealisation; "
              "measured values scatter, Ch. 6)")

    def applies(self, ctx):
        return bool(ctx.sensitivity.get("runs"))

    def evaluate(self, ctx):
        a = ctx.analysis
        var = ctx.sensitivity.get("variation", a.restitution_variation)
        limit = a.overturn_probability_limit
        n = len(ctx.valid)
        perturbations, worst, parts = [], 0.0, []
        for run in ctx.sensitivity["runs"].values():
            f = run["restitution_factor"]
            label = f"c_r {'−' if f < 1 else '+'} {100 * abs(1 - f):g} %"
            k = run["n_overturned"]
            upper = probability_bound(k, run.get("n_records", n))
            failed = run.get("failed") or []
            holds = upper <= limit and not failed       # a failed perturbed analysis proves nothing
            worst = max(worst, upper / limit if limit > 0 else math.inf,
                        1.0 + len(failed) / max(n, 1) if failed else 0.0)
            perturbations.append((label, holds))
            changed = f" ({', '.join(run['records'])} change)" if run["records"] else ""
            parts.append(f"{label}: {k} overturn{changed}" + (f", analyses failed: {', '.join(failed)}"
                                                                 if failed else ""))
        passed = all(h for _, h in perturbations)
        fails = [lab for lab, h in perturbations if not h]
        reason = ("P(overturn) criterion holds with c_r ± " + f"{100 * var:g} %" if passed
                  else "fails with " + " and ".join(fails))
        return self.item(worst, passed, "; ".join(parts), reason,
                         name=f"Robustness: P(overturn) criterion with c_r ± {100 * var:g} %",
                         perturbations=tuple(perturbations))


class PolyakovRule2(Criterion):
    """Polyakov's rule 2: median SD_max below the displacement capacity u_B(θc)."""

    key = "polyakov_rule_2"
    role = INFORMATIVE
    name = "Polyakov rule 2: median SD_max < u_B(θc)"
    source = "thesis Sec 4.2.5 and Fig 4.9 (rule of thumb; class b records are its false negatives)"

    def evaluate(self, ctx):
        valid = ctx.valid
        ratios = sorted(o.polyakov_ratio for o in valid)
        if not ratios:
            return self.item(math.inf, False, "no completed analysis", "no completed analysis")
        median = statistics.median(ratios)
        n_b = sum(o.klass == "b" for o in valid)
        detail = (f"{sum(x >= 1 for x in ratios)} of {len(ratios)} records with SD_max ≥ capacity; "
                  f"{n_b} false negative(s) (class b)")
        return self.item(median, median < 1.0, detail, f"median SD_max/u_B(θc) = {median:.3g}")


class PolyakovRule1(Criterion):
    """Polyakov's rule 1: the superstructure may be treated as rigid (ω_s/p ≥ the ratio)."""

    key = "polyakov_rule_1"
    role = INFORMATIVE
    source = "thesis Sec 1.2.4, 4.2.1, 4.2.4 (deformability negligible for large ω_s/p)"

    def applies(self, ctx):
        return "omega_s_over_p" in ctx.quantities

    def evaluate(self, ctx):
        need = ctx.analysis.rigid_superstructure_ratio
        ratio = ctx.quantities["omega_s_over_p"].value
        passed = ratio >= need
        detail = ("the superstructure may be treated as rigid" if passed else
                  "the flexible superstructure is analysed (2DOF model) because this fails")
        return self.item(need / ratio, passed, detail, f"ω_s/p = {ratio:.3g}",
                         name=f"Polyakov rule 1: rigid superstructure (ω_s/p ≥ {need:g})")


class LargestRotation(Criterion):
    """The largest θ_max/θc of the suite at the design level (how close the worst record comes)."""

    key = "largest_rotation"
    role = INFORMATIVE
    name = "RHA: largest θ_max/θc of the suite"
    source = "thesis Eq 3.56 (rotation capacity θc)"

    def evaluate(self, ctx):
        valid = ctx.valid
        worst = max((o.run.theta_max_over_theta_c for o in valid), default=math.inf)
        n_cap = sum(o.run.theta_max_over_theta_c >= 1.0 or o.run.overturned for o in valid)
        passed = n_cap == 0 and worst < 1.0
        detail = "every record below capacity" if passed else f"{n_cap} record(s) reach the capacity θc"
        return self.item(min(worst, 1e300), passed, detail, f"largest θ_max/θc = {worst:.3g}")


class EnsembleRobustness(Criterion):
    """The design-level probability criterion still holds in every perturbation-ensemble run of the suite.

    Each ensemble member re-analyses the whole suite with the amplitude × (1 ± 0.1 %) per record, c_r ×
    (1 ± 2 %) and the tolerances one decade tighter (checks/ensemble.py): perturbations well inside the
    input's own accuracy, so a verdict that changes under them is not a prediction.
    """

    key = "ensemble_robustness"
    role = ROBUSTNESS
    optional = True     # ensemble_size = 0 is the user's explicit choice (results.json "ensemble": null)
    source = ("thesis Ch. 7 (rocking is chaotic; the statistics, not single histories, are predictable); "
              "docs/fragility.md (perturbation ensembles)")

    def applies(self, ctx):
        ens = ctx.extra.get("ensemble")
        return bool(ens) and len(ens["overturned"]) > 0

    def evaluate(self, ctx):
        ens = ctx.extra["ensemble"]
        limit = ctx.analysis.overturn_probability_limit
        ok = [not analysis_failed(o.run.status) for o in ctx.outcomes]
        n = sum(ok)
        perturbations, worst, counts = [], 0.0, []
        for m, row in enumerate(ens["overturned"]):
            k = int(sum(bool(x) for x, good in zip(row, ok) if good))
            upper = probability_bound(k, n)
            worst = max(worst, upper / limit if limit > 0 else math.inf)
            counts.append(k)
            perturbations.append((f"perturbed suite run {m + 1} (c_r × {float(ens['restitution'][m]):.4f})",
                                  upper <= limit))
        n_fail = sum(not h for _, h in perturbations)
        size = len(perturbations)
        detail = (f"{size} perturbed runs of the whole suite: overturning records per run "
                  f"{', '.join(str(k) for k in counts)} of {n}; records whose outcome flips: "
                  f"{int(sum(not r for r, good in zip(ens['robust'], ok) if good))}")
        reason = (f"P(overturn) criterion holds in all {size} perturbed suite runs" if not n_fail else
                  f"fails in {n_fail} of {size} perturbed suite runs (amplitude ± 0.1 %, c_r ± 2 %, rtol/10)")
        return self.item(worst, n_fail == 0, detail, reason,
                         name="Robustness: P(overturn) criterion in the perturbation ensembles",
                         perturbations=tuple(perturbations))


class CollapseMargin(Criterion):
    """FEMA P695-style collapse margin adapted to overturning: ACMR ≥ ACMR10% (informative).

    Informative, not governing: the verdict is the exact suite statistic at (and below) the design level;
    the margin rests on a lognormal fragility and on uncertainty values written for conventional systems.
    """

    key = "collapse_margin"
    role = INFORMATIVE
    name = "Collapse margin (FEMA P695 adaptation): ACMR ≥ ACMR10%"
    source = "FEMA P695 (2009) Ch. 7, adapted to overturning (docs/fragility.md)"

    def applies(self, ctx):
        return ctx.extra.get("collapse_margin") is not None

    def evaluate(self, ctx):
        from .collapse_margin import collapse_margin_criterion
        m = ctx.extra["collapse_margin"]
        legacy = collapse_margin_criterion(m)
        return self.item(legacy["utilisation"], legacy["passed"], legacy["detail"],
                         f"ACMR = {m['ACMR']:.3g} vs ACMR10% = {m['ACMR10']:.3g}")


CRITERIA: list[type[Criterion]] = [AnalysesCompleted, OverturningProbability, IncrementalMargin,
                                   RestitutionRobustness, EnsembleRobustness, PolyakovRule2, PolyakovRule1,
                                   LargestRotation, CollapseMargin]
"""The criteria of ``rockdesign check`` in evaluation order."""


@dataclass(frozen=True)
class Verdict:
    """PASS or FAIL, the sentence that says why, and whether it survives the perturbations."""

    verdict: str
    reason: str
    robust: bool
    not_covered: tuple[str, ...] = ()
    governing: str | None = None     # key of the governing check: the largest utilisation among those that decide

    def as_json(self) -> dict:
        return {"verdict": self.verdict, "verdict_reason": self.reason, "verdict_robust": self.robust}


def evaluate_criteria(ctx: CheckContext, criteria=None) -> tuple[list[CheckItem], list[str]]:
    """Evaluate ``criteria`` (default :data:`CRITERIA`): (items, keys of the governing and robustness
    criteria that could not be evaluated — the verdict names what it does not cover)."""
    items, skipped = [], []
    for cls in (CRITERIA if criteria is None else criteria):
        crit = cls()
        if crit.applies(ctx):
            items.append(crit.evaluate(ctx))
        elif crit.role != INFORMATIVE and not crit.optional:
            skipped.append(crit.key)
    return items, skipped


NOT_COVERED = {
    "incremental_margin": "intensities below the design level not analysed (--no-margins)",
    "restitution_robustness": "c_r sensitivity not analysed",
}


def decide(items: list[CheckItem], skipped=()) -> Verdict:
    """The one verdict of the check.

    FAIL when any governing item fails (the reason quotes each failing item); otherwise PASS.  A PASS
    whose governing criterion fails under a robustness perturbation reads "PASS, not robust: fails
    with c_r − 2 %"; a FAIL that only the design-level probability decides and that some perturbation
    would turn into a pass is flagged not robust too.  Governing criteria that could not be evaluated
    are named ("not covered: ...").
    """
    failing = [i for i in items if i.governs_verdict and not i.passed]
    robustness = [i for i in items if i.role == ROBUSTNESS]
    not_covered = tuple(NOT_COVERED.get(k, f"{k} not evaluated") for k in skipped)
    if failing:
        word = "FAIL"
        reason = "FAIL: " + "; ".join(i.verdict_reason for i in failing)
        flips = []
        if all(i.key == OverturningProbability.key for i in failing):
            flips = [lab for i in robustness for lab, holds in i.perturbations if holds]
        robust = not flips
        if flips:
            reason += "; not robust: passes with " + " and ".join(flips)
        else:
            reason += "".join(f"; also {i.verdict_reason}" for i in robustness if not i.passed)
    else:
        word = "PASS"
        fragile = [i.verdict_reason for i in robustness if not i.passed]
        robust = not fragile
        governing = [i.verdict_reason for i in items if i.governs_verdict]
        reason = ("PASS, not robust: " + "; ".join(fragile)) if fragile else "PASS: " + "; ".join(governing)
    if not_covered:
        reason += " (not covered: " + "; ".join(not_covered) + ")"
    deciding = [i for i in items if i.governs_verdict]
    governing = max(deciding, key=lambda i: i.utilisation).key if deciding else None
    return Verdict(word, reason, robust, not_covered, governing)
