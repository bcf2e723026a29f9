"""The planar kind's criteria: Polyakov's rules of thumb and the largest rotation (informative), and the lists
of criteria of each acceptance rule for columns, frames and podiums (the shared criteria and the verdict:
:mod:`rockdesign.acceptance.criteria`)."""
from __future__ import annotations

import math
import statistics

from ...acceptance.criteria import AnalysesCompleted
from ...acceptance.criterion_base import INFORMATIVE, Criterion
from ...acceptance.overturning_criteria import (BinomialBound, CollapseMarginAtTarget, CollapseMarginInformative,
                                                EnsembleRobustness, GoverningBinomialBound,
                                                GoverningIncrementalMargin, IncrementalMargin,
                                                RestitutionRobustness, UnacceptableResponses,
                                                UnacceptableResponsesInformative)
from ...acceptance.rule import AcceptanceRule


class PolyakovRule2(Criterion):
    """Polyakov's rule 2: median SD_max below the displacement capacity u_B(θc)."""

    key = "polyakov_rule_2"
    role = INFORMATIVE
    name = "Polyakov rule 2: median SD_max < u_B(θc)"
    source = "thesis Sec 4.2.5 and Fig 4.9 (rule of thumb; class b records are its false negatives)"

    def applies(self, ctx):
        return all(getattr(o, "polyakov_ratio", None) is not None for o in ctx.valid)

    def evaluate(self, ctx):
        valid = ctx.valid
        ratios = sorted(o.polyakov_ratio for o in valid)
        if not ratios:
            return self.item(math.inf, False, "no completed analysis", "no completed analysis")
        median = statistics.median(ratios)
        n_b = sum(o.klass == "b" for o in valid)
        detail = (f"{sum(x >= 1 for x in ratios)} of {len(ratios)} records with SD_max ≥ capacity; "
                  f"{n_b} false negative{'' if n_b == 1 else 's'} (class b)")
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
        detail = "every record below capacity" if passed else (f"{n_cap} record{' reaches' if n_cap == 1 else 's reach'} the capacity θc")
        return self.item(min(worst, 1e300), passed, detail, f"largest θ_max/θc = {worst:.3g}")


CRITERIA: list[type[Criterion]] = [AnalysesCompleted, UnacceptableResponses, CollapseMarginAtTarget,
                                   RestitutionRobustness, EnsembleRobustness, BinomialBound, IncrementalMargin,
                                   PolyakovRule2, PolyakovRule1, LargestRotation]
"""The criteria of ``acceptance = "asce7"`` (the default) in evaluation order."""


BINOMIAL_CRITERIA: list[type[Criterion]] = [AnalysesCompleted, GoverningBinomialBound, GoverningIncrementalMargin,
                                            RestitutionRobustness, EnsembleRobustness,
                                            UnacceptableResponsesInformative, CollapseMarginInformative,
                                            PolyakovRule2, PolyakovRule1, LargestRotation]
"""The criteria of ``acceptance = "binomial"``."""


def criteria_for(rule: AcceptanceRule | None = None) -> list:
    """The criteria of a check under an acceptance rule (default: asce7): :data:`CRITERIA` or
    :data:`BINOMIAL_CRITERIA`."""
    return BINOMIAL_CRITERIA if rule is not None and rule.method == "binomial" else CRITERIA
