"""The criteria of a cylinder's check (thesis Ch. 5), in the terms of :mod:`rockdesign.acceptance.criteria`.

Each record pair is one ground motion, and the cylinder is judged as every kind is.  Under the default
acceptance (``asce7``) the governing criteria are every analysis completed, the ASCE 7-22 §16.4.1.1
count of unacceptable ground motions (pairs that overturn at the design level) within the risk
category's allowance, the same count over the pairs that overturn at *some* intensity up to the design
level (their first overturning factor ≤ 1: a non-monotonic band below the design level counts), and
the FEMA P695 collapse margin at the category's target
(:class:`~rockdesign.acceptance.overturning_criteria.CollapseMarginAtTarget`, on each pair's first
overturning intensity of the resultant PGA).  Under ``acceptance = "binomial"`` the one-sided 95 %
bound of P(overturn) over the pairs governs instead (the count and the margin are then information).  All read from the typed
pair outcomes of
:mod:`rockdesign.cylinder.check`; the cylinder adds its overturning criterion's words (θ reaching
θ_ot), its perturbation ensemble (no c_r: the 3D model has no impact law) and two informative checks
(does a planar analysis suffice; Polyakov's rule 2 per component).
"""
from __future__ import annotations

import math
import statistics

from ..acceptance.perturbations import draw_words
from ..acceptance.rule import (count_rule, first_overturn_scale, minimum_records, probability_bound,
                         unacceptable_ground_motions)
from ..acceptance.criterion_base import GOVERNS, INFORMATIVE, ROBUSTNESS, Criterion
from ..acceptance.criteria import AnalysesCompleted
from ..acceptance.overturning_criteria import (CollapseMarginAtTarget, CollapseMarginInformative,
                                               GoverningIncrementalMargin)


def _pct(x: float) -> str:
    return f"{100 * x:g} %"


class CylinderOverturning(Criterion):
    """P(overturn) of the 3D cylinder at the design level ≤ limit at 95 % one-sided confidence over the
    record pairs (Clopper & Pearson 1934 exact binomial bound)."""

    key = "overturning_probability"
    role = GOVERNS
    source = ("thesis Sec 5.5.1 (θ reaching θ_ot = overturn_tilt·α) and Ch. 6–7 (suite statistics); "
              "Clopper & Pearson (1934) exact binomial bound")

    def evaluate(self, ctx):
        limit = ctx.rule.binomial_limit if ctx.rule is not None else ctx.analysis.overturn_probability_limit
        valid = ctx.valid
        n, k = len(valid), sum(o.run.overturned for o in valid)
        upper = probability_bound(k, n)
        n_min = minimum_records(limit)
        tilt = ctx.extra["cylinder"].overturn_tilt
        name = (f"RHA (3D): P(overturn) ≤ {_pct(limit)} at 95 % confidence "
                f"(θ reaching θ_ot = {tilt:g}α counts as overturning)")
        util = upper / limit if limit > 0 else math.inf
        passed = upper <= limit
        need = f"needs ≥ {n_min} record pairs" if n_min else "no suite can show it"
        detail = (f"{k} of {n} record pairs overturn at the design level; one-sided 95 % upper bound {upper:.3g} "
                  f"(= upper end of the two-sided 90 % interval); {need}")
        if passed:
            reason = f"{k} of {n} record pairs overturn at the design level (P ≤ {upper:.3g} at 95 % confidence)"
        else:
            parts = []
            if k:
                ids = ", ".join(o.id for o in valid if o.run.overturned)
                parts.append(f"{k} of {n} record pairs overturn at the design level ({ids})")
            if n_min is None or n < n_min:
                parts.append(f"{n} record pairs cannot show P(overturn) ≤ {_pct(limit)} at 95 % confidence "
                             f"(the bound {upper:.3g}; {need})")
            reason = "; ".join(parts)
        return self.item(util, passed, detail, reason, name=name)


class CylinderUnacceptable(Criterion):
    """ASCE 7-22 §16.4.1.1 for record pairs: at most the risk category's allowance of pairs (ground
    motions) overturn at the design level (one for I/II, none for III/IV)."""

    key = "unacceptable_responses"
    role = GOVERNS
    source = ("ASCE 7-22 §16.4.1.1 (unacceptable responses; overturning — θ reaching θ_ot — is the "
              "unacceptable response of a rocking cylinder) and §16.2 (a record pair is one ground motion)")

    def evaluate(self, ctx):
        rule, valid = ctx.rule, ctx.valid
        overturned = {o.id for o in valid if o.run.overturned}
        k = len(unacceptable_ground_motions(valid, overturned))
        n = len(valid)
        allowed = rule.allowed
        util = k / allowed if allowed else (0.0 if k == 0 else 1.0 + k)
        passed = k <= allowed
        tilt = ctx.extra["cylinder"].overturn_tilt
        name = (f"RHA (3D): unacceptable ground motions ≤ {allowed} (ASCE 7-22 §16.4.1.1, risk category "
                f"{rule.risk_category}; θ reaching θ_ot = {tilt:g}α counts as overturning)")
        ids = ", ".join(o.id for o in valid if o.run.overturned)
        detail = (f"{k} of {n} record pairs (ground motions) overturn at the design level"
                  + (f": {ids}" if k else "") + f"; {allowed} allowed")
        reason = f"{k} of {n} ground motions unacceptable ({allowed} allowed)" + (f": {ids}" if k and not passed else "")
        return self.item(util, passed, detail, reason, name=name)


class CylinderOverturningInformative(Criterion):
    """The one-sided 95 % binomial bound of P(overturn) over the record pairs, as information (it governs
    only under ``acceptance = "binomial"``)."""

    key = "binomial_bound"
    role = INFORMATIVE
    source = "Clopper & Pearson (1934) exact binomial bound over the record pairs (each one ground motion)"

    def evaluate(self, ctx):
        limit = ctx.rule.binomial_limit
        valid = ctx.valid
        n, k = len(valid), sum(o.run.overturned for o in valid)
        upper = probability_bound(k, n)
        n_min = minimum_records(limit)
        name = f"RHA (3D): P(overturn) ≤ {_pct(limit)} at 95 % confidence over the record pairs (information)"
        detail = (f"{k} of {n} record pairs overturn; one-sided 95 % upper bound {upper:.3g}"
                  + (f" (a bound ≤ {_pct(limit)} needs ≥ {n_min} pairs)" if n_min else ""))
        return self.item(upper / limit if limit > 0 else math.inf, upper <= limit, detail,
                         f"binomial bound {upper:.3g}", name=name)


class CylinderIncrementalCount(Criterion):
    """ASCE 7-22 §16.4.1.1 applied to the first overturning intensity: at most the allowance of pairs
    overturn at some intensity up to the design level (responses are not monotonic)."""

    key = "incremental_margin"
    role = GOVERNS
    source = ("thesis Sec 2.2 (Zhang & Makris 2001: safe, overturn, safe again as the amplitude grows); "
              "ASCE 7-22 §16.4.1.1 applied to each pair's first overturning intensity")

    def applies(self, ctx):
        return ctx.margins_run

    def evaluate(self, ctx):
        rule, valid = ctx.rule, ctx.valid
        below = sorted((f, o.id) for o in valid if (f := first_overturn_scale(o)) is not None and f <= 1.0)
        passed, k, n, util = count_rule(rule, valid, {i for _, i in below})   # failed scans: AnalysesCompleted
        name = (f"RHA incremental (3D): ground motions overturning at some intensity ≤ design ≤ {rule.allowed} "
                f"(ASCE 7-22 §16.4.1.1 on the first overturning intensity)")
        listing = ", ".join(f"{i} at {f:.3g}×" for f, i in below)
        detail = (f"{k} of {n} record pairs overturn at some intensity up to the design level"
                  + (f" ({listing})" if below else "") + f"; {rule.allowed} allowed")
        if passed:
            reason = f"{k} of {n} ground motions overturn at some intensity up to the design level ({rule.allowed} allowed)"
        else:
            f, rid = below[0]
            reason = (f"{k} of {n} ground motions overturn at some intensity up to the design level "
                      f"({rule.allowed} allowed), the first at {f:.2g}× design ({rid})")
        return self.item(util, passed, detail, reason, name=name)


class CylinderEnsembleRobustness(Criterion):
    """The P(overturn) criterion still holds in every perturbed run of the suite of pairs (amplitude of
    each pair × (1 ± 0.1 %), tolerances one decade tighter)."""

    key = "ensemble_robustness"
    role = ROBUSTNESS
    optional = True     # ensemble_size = 0 is the user's explicit choice (results.json "ensemble": null)
    source = ("thesis Ch. 7 (rocking is chaotic; the statistics, not single histories, are predictable); "
              "docs/fragility.md (perturbation ensembles)")
    name = "Robustness: design-level rule in the perturbation ensembles (3D)"

    def applies(self, ctx):
        ens = ctx.extra.get("ensemble")
        return bool(ens) and len(ens["overturned"]) > 0

    def evaluate(self, ctx):
        ens = ctx.extra["ensemble"]
        limit = ctx.rule.binomial_limit if ctx.rule is not None else ctx.analysis.overturn_probability_limit
        ok = [o.run.status == "completed" for o in ctx.outcomes]
        n = sum(ok)
        perturbations, worst, counts = [], 0.0, []
        for m, row in enumerate(ens["overturned"]):
            k = int(sum(bool(x) for x, good in zip(row, ok) if good))
            if ctx.rule is not None and ctx.rule.method == "asce7":   # the count rule of each draw
                allowed = ctx.rule.allowed
                util, holds = (k / allowed if allowed else (0.0 if k == 0 else 1.0 + k)), k <= allowed
            else:
                upper = probability_bound(k, n)
                util, holds = (upper / limit if limit > 0 else math.inf), upper <= limit
            worst = max(worst, util)
            counts.append(k)
            perturbations.append((f"perturbed suite run {m + 1}", holds))
        n_fail = sum(not h for _, h in perturbations)
        size = len(perturbations)
        flips = int(sum(not r for r, good in zip(ens["robust"], ok) if good))
        detail = (f"{size} perturbed runs of the whole suite: overturning pairs per run "
                  f"{', '.join(str(k) for k in counts)} of {n}; pairs whose outcome flips: {flips}")
        reason = (f"the design-level rule holds in all {size} perturbed suite runs" if not n_fail else
                  f"fails in {n_fail} of {size} perturbed suite runs ({draw_words(restitution=False)})")
        return self.item(worst, n_fail == 0, detail, reason, perturbations=tuple(perturbations))


class PlanarSuffices(Criterion):
    """Would the planar Housner analysis along each component have reached the same overturning verdict?"""

    key = "planar_suffices"
    role = INFORMATIVE
    name = "Does a planar analysis suffice? (Housner along each component)"
    source = "thesis Sec 5.6 (the wobbling cylinder against the planar rocking block)"

    def applies(self, ctx):
        return ctx.extra["summary"]["planar"] is not None    # (the design grid skips the planar runs)

    def evaluate(self, ctx):
        s = ctx.extra["summary"]
        n, k3, kp = s["n_records"], s["n_overturned"], s["planar"]["n_overturned"]
        unsafe = s["n_planar_unconservative"]
        passed = unsafe == 0 and kp >= k3
        util = (k3 / kp) if kp else (math.inf if k3 else 0.0)
        detail = (f"planar: {kp} of {n} overturn (P = {s['planar']['p_overturn']:.3g}); 3D − planar ΔP = "
                  f"{s['difference_p_overturn']:+.3g}; {unsafe} {'pair overturns' if unsafe == 1 else 'pairs overturn'} in 3D "
                  "but not in the planar analysis")
        reason = ("the planar analysis overturns at least the pairs the 3D analysis does" if passed else
                  f"{unsafe} {'pair overturns' if unsafe == 1 else 'pairs overturn'} in 3D but not in the planar analysis")
        return self.item(util, passed, detail, reason)


class PolyakovPerComponent(Criterion):
    """Polyakov's rule 2 along each component: median SD_max < 2B (information: the rule is planar)."""

    key = "polyakov_rule_2"
    role = INFORMATIVE
    name = "Polyakov rule 2 per component: median SD_max < 2B (information)"
    source = "thesis Sec 4.2.5 (a planar rule of thumb)"

    def evaluate(self, ctx):
        ratios = [o.polyakov_ratio for o in ctx.valid]
        median = statistics.median(ratios) if ratios else math.inf
        return self.item(median, True, "informative only: Polyakov's rule is planar",
                         f"median SD_max/2B = {median:.3g}")


CYLINDER_CRITERIA: list[type[Criterion]] = [AnalysesCompleted, CylinderOverturning, GoverningIncrementalMargin,
                                            CylinderEnsembleRobustness, CollapseMarginInformative, PlanarSuffices,
                                            PolyakovPerComponent]
"""The criteria of a cylinder's check under ``acceptance = "binomial"``, in evaluation order
(:func:`~rockdesign.acceptance.criteria.evaluate_criteria`)."""

CYLINDER_CRITERIA_ASCE7: list[type[Criterion]] = [AnalysesCompleted, CylinderUnacceptable, CylinderIncrementalCount,
                                                  CollapseMarginAtTarget, CylinderEnsembleRobustness,
                                                  CylinderOverturningInformative, PlanarSuffices,
                                                  PolyakovPerComponent]
"""The criteria of a cylinder's check under the default ``acceptance = "asce7"`` (the count rules and the
collapse margin decide)."""


def cylinder_criteria(rule) -> list[type[Criterion]]:
    """The cylinder's criteria for an acceptance rule (:func:`~rockdesign.acceptance.rule.acceptance_rule`)."""
    return CYLINDER_CRITERIA_ASCE7 if rule.method == "asce7" else CYLINDER_CRITERIA
