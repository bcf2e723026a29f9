"""The design criteria every kind shares, and the one verdict that combines a kind's criteria.

Pattern of concreteproperties' ``DesignCode``: one class per criterion, each citing its source and
returning a typed :class:`CheckItem`; :func:`evaluate_criteria` runs a kind's list of them and
:func:`decide` turns the items into the :class:`Verdict`.  Adding a criterion is one class: subclass
:class:`Criterion`, set ``key``, ``role`` and ``source``, implement :meth:`Criterion.evaluate`, and
append the class to the kind's list (planar: :data:`rockdesign.planar.checks.criteria.CRITERIA`).  Data a criterion needs beyond the
suite run (e.g. perturbation ensembles) travels in :attr:`CheckContext.extra`.

The overturning criteria of the acceptance rule (ASCE 7-22 §16.4 count per ground motion, FEMA P695
collapse margin at the risk category's target, the binomial bound) are in
:mod:`rockdesign.acceptance.overturning_criteria`; the rule itself in :mod:`rockdesign.acceptance.rule`.

Roles (documented for users in ``docs/model.md``, "Verdict"):

- ``governs``: decides.  PASS only when every governing criterion was evaluated and passed; FAIL when
  an evaluated one fails; otherwise NOT DECIDED (a governing criterion skipped, e.g. a check without margins).
- ``robustness``: does not change the word but says whether it survives a perturbation of an uncertain
  input (``verdict_robust``; "PASS, not robust: fails with c_r − 2 %").
- ``informative``: reported for comparison (Polyakov's rules of thumb, largest rotation, the other rule).
"""
from __future__ import annotations

from dataclasses import dataclass

from .criterion_base import (FAIL, GOVERNS, NOT_DECIDED, PASS, ROBUSTNESS, UTILISATION_CAP,  # noqa: F401
                             CheckContext, CheckItem, Criterion)
from .rule import AcceptanceRule


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
        # an incremental analysis that failed at or below the design level leaves the first overturning
        # intensity (the fragility's capacity) unknown there
        scans = [(min(o.margin.failed_scales), o.id) for o in ctx.valid
                 if getattr(o, "margin", None) is not None and getattr(o.margin, "failed_scales", None)
                 and min(o.margin.failed_scales) <= 1.0]
        if not failed and not scans:
            return self.item(0.0, True, f"all {n} analyses ran to a conclusion", f"all {n} analyses completed")
        parts, reasons = [], []
        if failed:
            listing = ", ".join(f"{o.id} ({o.run.status})" for o in failed)
            parts.append(f"{len(failed)} of {n} analyses failed: {listing}")
            reasons.append(f"{len(failed)} analysis(es) failed ({listing})")
        if scans:
            listing = ", ".join(f"{i} at {f:.3g}×" for f, i in scans)
            parts.append(f"incremental analyses failed below the design level: {listing}")
            reasons.append(f"incremental analyses failed below the design level ({listing})")
        return self.item(1.0 + (len(failed) + len(scans)) / max(n, 1), False, "; ".join(parts), "; ".join(reasons))


@dataclass(frozen=True)
class Verdict:
    """PASS, FAIL or NOT DECIDED, the sentence that says why, and whether it survives the perturbations."""

    verdict: str
    reason: str
    robust: bool
    not_covered: tuple[str, ...] = ()
    governing: str | None = None     # key of the governing check: the largest utilisation among those that decide
    method: str = ""                 # the acceptance rule that decided ("ASCE 7-22 §16.4, risk category II")

    @property
    def exit_code(self) -> int:
        """0 PASS, 1 FAIL, 4 NOT DECIDED (CONTRACT §6.1)."""
        return {PASS: 0, FAIL: 1}.get(self.verdict, 4)

    def as_json(self) -> dict:
        return {"verdict": self.verdict, "verdict_reason": self.reason, "verdict_robust": self.robust}


def evaluate_criteria(ctx: CheckContext, criteria) -> tuple[list[CheckItem], list[str]]:
    """Evaluate ``criteria`` (the kind's list for the context's acceptance rule): (items, keys of the
    required criteria that could not be evaluated — the verdict says what is missing)."""
    items, skipped = [], []
    for cls in criteria:
        crit = cls()
        if crit.applies(ctx):
            items.append(crit.evaluate(ctx))
        elif crit.required(ctx):
            skipped.append(crit.key)
    return items, skipped


NOT_COVERED = {
    "collapse_margin": "collapse margin not evaluated (no incremental analysis: the check ran without margins)",
    "incremental_margin": "intensities below the design level not analysed (the check ran without margins)",
    "restitution_robustness": "c_r sensitivity not analysed",
    "ensemble_robustness": "perturbation ensembles not analysed",
}
QUALIFIERS = {"restitution_robustness", "ensemble_robustness"}
"""Skipped criteria that qualify the verdict (named as not covered) but leave it decided."""


def decide(items: list[CheckItem], skipped=(), rule: AcceptanceRule | None = None, basis: str = "") -> Verdict:
    """The one verdict of the check (SPEC §14: a criterion that was not evaluated cannot pass).

    FAIL when an evaluated governing item fails (the reason quotes each); otherwise NOT DECIDED when a
    governing criterion was skipped or could not be decided (the reason says what is missing);
    otherwise PASS.  The reason names the rule: "PASS (ASCE 7-22 §16.4, risk category II): 0 of 22
    ground motions unacceptable (1 allowed); ACMR 2.41 ≥ 1.96 (P(collapse) 4.7 % ≤ 10 %)".  A PASS
    whose design-level rule fails under a robustness perturbation adds "; not robust: fails with c_r − 2 %"; a FAIL
    that only the design-level rule decides and that some perturbation would pass is flagged too.  ``basis``:
    how the records were scaled when not per ASCE 7-22 §16.2 (:func:`rockdesign.motions.scaling_report.headline_basis`),
    named beside the rule: "PASS (ASCE 7-22 §16.4, risk category II; records scaled to PGA, not per ASCE 7-22
    §16.2): …".
    """
    governing = [i for i in items if i.governs_verdict]
    failing = [i for i in governing if i.evaluated and not i.passed]
    undecided = [i for i in governing if not i.evaluated]
    robustness = [i for i in items if i.role == ROBUSTNESS]
    not_covered = tuple(NOT_COVERED.get(k, f"{k} not evaluated") for k in skipped)
    missing = [NOT_COVERED.get(k, f"{k} not evaluated") for k in skipped if k not in QUALIFIERS] \
        + [i.verdict_reason for i in undecided]
    qualifiers = [NOT_COVERED[k] for k in skipped if k in QUALIFIERS]
    label = f" ({rule.label}{'; ' + basis if basis else ''})" if rule is not None else ""
    design_level = {"unacceptable_responses", "overturning_probability"}
    if failing:
        word = FAIL
        reason = f"FAIL{label}: " + "; ".join(i.verdict_reason for i in failing)
        flips = []
        if all(i.key in design_level for i in failing):
            flips = [lab for i in robustness for lab, holds in i.perturbations if holds]
        robust = not flips
        if flips:
            reason += "; not robust: passes with " + " and ".join(flips)
        else:
            reason += "".join(f"; also {i.verdict_reason}" for i in robustness if not i.passed)
        if missing:
            reason += " (not evaluated: " + "; ".join(missing) + ")"
    elif missing:
        word = NOT_DECIDED
        robust = all(i.passed for i in robustness)
        done = [i.verdict_reason for i in governing if i.evaluated]
        reason = (f"NOT DECIDED{label}: " + "; ".join(missing)
                  + ("; evaluated: " + "; ".join(done) if done else ""))
    else:
        word = PASS
        fragile = [i.verdict_reason for i in robustness if not i.passed]
        robust = not fragile
        quoted = [i for i in governing if i.key != AnalysesCompleted.key] or governing
        reason = f"PASS{label}: " + "; ".join(i.verdict_reason for i in quoted)
        if fragile:
            reason += "; not robust: " + "; ".join(fragile)
    if qualifiers:
        reason += " (not covered: " + "; ".join(qualifiers) + ")"
    deciding = [i for i in governing if i.evaluated]
    key = max(deciding, key=lambda i: i.utilisation).key if deciding else None
    return Verdict(word, reason, robust, not_covered, key, rule.label if rule is not None else "")

