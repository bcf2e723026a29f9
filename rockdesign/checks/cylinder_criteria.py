"""The criteria of a cylinder's check (thesis Ch. 5), in the terms of :mod:`rockdesign.checks.criteria`.

The governing criteria are the planar check's own — every analysis completed, and the one-sided 95 %
bound of P(overturn) within the limit — read from the typed pair outcomes of
:mod:`rockdesign.checks.cylinder_check`; the cylinder adds its overturning criterion's words (θ reaching
θ_ot), its perturbation ensemble (no c_r: the 3D model has no impact law) and two informative checks
(does a planar analysis suffice; Polyakov's rule 2 per component).
"""
from __future__ import annotations

import dataclasses
import math
import statistics

from .criteria import (GOVERNS, INFORMATIVE, ROBUSTNESS, AnalysesCompleted, Criterion, IncrementalMargin,
                       OverturningProbability, probability_bound)


def _pct(x: float) -> str:
    return f"{100 * x:g} %"


class CylinderOverturning(OverturningProbability):
    """P(overturn) of the 3D cylinder at the design level ≤ limit at 95 % one-sided confidence."""

    role = GOVERNS
    source = ("thesis Sec 5.5.1 (θ reaching θ_ot = overturn_tilt·α) and Ch. 6–7 (suite statistics); "
              "Clopper & Pearson (1934) exact binomial bound")

    def evaluate(self, ctx):
        item = super().evaluate(ctx)
        tilt = ctx.extra["cylinder"].overturn_tilt
        name = (f"RHA (3D): P(overturn) ≤ {_pct(ctx.analysis.overturn_probability_limit)} at 95 % confidence "
                f"(θ reaching θ_ot = {tilt:g}α counts as overturning)")
        return dataclasses.replace(item, name=name, source=self.source,
                                   verdict_reason=item.verdict_reason.replace("records", "record pairs"),
                                   detail=item.detail.replace("records", "record pairs"))


class CylinderEnsembleRobustness(Criterion):
    """The P(overturn) criterion still holds in every perturbed run of the suite of pairs (amplitude of
    each pair × (1 ± 0.1 %), tolerances one decade tighter)."""

    key = "ensemble_robustness"
    role = ROBUSTNESS
    optional = True     # ensemble_size = 0 is the user's explicit choice (results.json "ensemble": null)
    source = ("thesis Ch. 7 (rocking is chaotic; the statistics, not single histories, are predictable); "
              "docs/fragility.md (perturbation ensembles)")
    name = "Robustness: P(overturn) criterion in the perturbation ensembles (3D)"

    def applies(self, ctx):
        ens = ctx.extra.get("ensemble")
        return bool(ens) and len(ens["overturned"]) > 0

    def evaluate(self, ctx):
        ens = ctx.extra["ensemble"]
        limit = ctx.analysis.overturn_probability_limit
        ok = [o.run.status == "completed" for o in ctx.outcomes]
        n = sum(ok)
        perturbations, worst, counts = [], 0.0, []
        for m, row in enumerate(ens["overturned"]):
            k = int(sum(bool(x) for x, good in zip(row, ok) if good))
            upper = probability_bound(k, n)
            worst = max(worst, upper / limit if limit > 0 else math.inf)
            counts.append(k)
            perturbations.append((f"perturbed suite run {m + 1}", upper <= limit))
        n_fail = sum(not h for _, h in perturbations)
        size = len(perturbations)
        flips = int(sum(not r for r, good in zip(ens["robust"], ok) if good))
        detail = (f"{size} perturbed runs of the whole suite: overturning pairs per run "
                  f"{', '.join(str(k) for k in counts)} of {n}; pairs whose outcome flips: {flips}")
        reason = (f"P(overturn) criterion holds in all {size} perturbed suite runs" if not n_fail else
                  f"fails in {n_fail} of {size} perturbed suite runs (amplitude ± 0.1 %, rtol/10)")
        return self.item(worst, n_fail == 0, detail, reason, perturbations=tuple(perturbations))


class PlanarSuffices(Criterion):
    """Would the planar Housner analysis along each component have reached the same overturning verdict?"""

    key = "planar_suffices"
    role = INFORMATIVE
    name = "Does a planar analysis suffice? (Housner along each component)"
    source = "thesis Sec 5.6 (the wobbling cylinder against the planar rocking block)"

    def evaluate(self, ctx):
        s = ctx.extra["summary"]
        n, k3, kp = s["n_records"], s["n_overturned"], s["planar"]["n_overturned"]
        unsafe = s["n_planar_unconservative"]
        passed = unsafe == 0 and kp >= k3
        util = (k3 / kp) if kp else (math.inf if k3 else 0.0)
        detail = (f"planar: {kp} of {n} overturn (P = {s['planar']['p_overturn']:.3g}); 3D − planar ΔP = "
                  f"{s['difference_p_overturn']:+.3g}; {unsafe} pair(s) overturn in 3D but not in the planar analysis")
        reason = ("the planar analysis overturns at least the pairs the 3D analysis does" if passed else
                  f"{unsafe} pair(s) overturn in 3D but not in the planar analysis")
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


CYLINDER_CRITERIA: list[type[Criterion]] = [AnalysesCompleted, CylinderOverturning, IncrementalMargin,
                                            CylinderEnsembleRobustness, PlanarSuffices, PolyakovPerComponent]
"""The criteria of a cylinder's check in evaluation order (:func:`~rockdesign.checks.criteria.evaluate_criteria`)."""
