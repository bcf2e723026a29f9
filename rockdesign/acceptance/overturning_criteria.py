"""The overturning criteria of the acceptance rules (SPEC §14; rules in :mod:`rockdesign.acceptance.rule`).

Counted per ground motion, never per component: a ground motion (one station's recording of one
earthquake) is unacceptable when any of its analysed components overturns (``[analysis] overturn``:
θ_max ≥ θc, or |θ| = π/2).

- :class:`UnacceptableResponses` — ASCE 7-22 §16.4.1.1 at the design level (= MCE_R).
- :class:`CollapseMarginAtTarget` — FEMA P695 (2009) Ch. 7 adapted: ACMR ≥ exp(−β_TOT Φ⁻¹(x)) at the
  risk category's target x, with Ŝ_CT counted (Ch. 6, §6.4: the intensity at which half the records
  overturn) on each record's *first* overturning intensity (a non-monotonic band below the design
  level counts); the fitted lognormal median is reported beside it.
- :class:`BinomialBound`, :class:`IncrementalMargin` — one-sided 95 % Clopper–Pearson bounds over the
  independent ground motions, at the design level and at any intensity up to it.
- :class:`RestitutionRobustness`, :class:`EnsembleRobustness` — the design-level rule (count or bound)
  in every perturbed run of the suite: c_r ± 2 % and the perturbation ensembles are further draws of
  the same suite (rocking is chaotic: the nominal run is one draw).

Each rule's governing criteria are the classes with ``role = GOVERNS`` in
:data:`rockdesign.acceptance.criteria.CRITERIA` (asce7) and ``BINOMIAL_CRITERIA`` (binomial); the others
are reported beside them as information.
"""
from __future__ import annotations

import math

from .perturbations import draw_words
from .rule import (first_overturn_scale, count_rule, ground_motions_in_order, minimum_records, pct, probability_bound,
                         unacceptable_ground_motions)
from .collapse_margin import acceptable_acmr, collapse_probability
from .criterion_base import GOVERNS, INFORMATIVE, ROBUSTNESS, Criterion


REASON_LISTING = 4
"""Ground motions the verdict sentence names (the check's detail lists all of them)."""


def _criterion_text(a) -> str:
    return "θ_max ≥ θc" if a.overturn == "static" else "|θ| = π/2"


def _overturned_ids(outcomes) -> set[str]:
    return {o.id for o in outcomes if o.run.overturned}


def _listing(ctx, gms, limit: int | None = None) -> str:
    """"p695-ff/11 (p695-ff/11a), …": ground motions with their overturning components (the first
    ``limit`` of them, then "and N more")."""
    parts = []
    more = len(gms) - limit if limit is not None and len(gms) > limit else 0
    gms = gms[:limit] if more else gms
    for g in gms:
        comps = [o.id for o in ctx.valid if o.run.overturned and (getattr(o, "ground_motion", None) or o.id) == g]
        parts.append(g if comps == [g] else f"{g} ({', '.join(comps)})")
    return ", ".join(parts) + (f" and {more} more" if more else "")


class UnacceptableResponses(Criterion):
    """ASCE 7-22 §16.4.1.1: at most one (risk category I/II) or no (III/IV) unacceptable ground motion."""

    key = "unacceptable_responses"
    role = GOVERNS
    source = ("ASCE 7-22 §16.4.1.1 (unacceptable responses; overturning is the unacceptable response of a "
              "rocking structure) and §16.2 (ground motions, not components)")

    def evaluate(self, ctx):
        rule, a = ctx.rule, ctx.analysis
        valid = ctx.valid
        holds, k, n, util = _count(rule, valid, _overturned_ids(valid))
        bad = unacceptable_ground_motions(valid, _overturned_ids(valid))
        name = (f"RHA: unacceptable ground motions ≤ {rule.allowed} (ASCE 7-22 §16.4.1.1, risk category "
                f"{rule.risk_category}; overturning: {_criterion_text(a)})")
        n_rec = len(valid)
        detail = (f"{k} of {n} ground motions ({n_rec} records) overturn at the design level"
                  + (f": {_listing(ctx, bad)}" if bad else "") + f"; {rule.allowed} allowed")
        reason = f"{k} of {n} ground motions unacceptable ({rule.allowed} allowed)"
        if k and not holds:
            reason += f": {_listing(ctx, bad, REASON_LISTING)}"
        return self.item(util, holds, detail, reason, name=name)


def _count(rule, outcomes, overturned) -> tuple[bool, int, int, float]:
    """The §16.4.1.1 count whatever the rule's method (the binomial rule reports it as information)."""
    k = len(unacceptable_ground_motions(outcomes, overturned))
    n = len(ground_motions_in_order(outcomes))
    util = k / rule.allowed if rule.allowed else (0.0 if k == 0 else 1.0 + k)
    return k <= rule.allowed, k, n, util


class CollapseMarginAtTarget(Criterion):
    """FEMA P695-style collapse margin at the risk category's target: ACMR ≥ ACMR_x (P(collapse) ≤ x)."""

    key = "collapse_margin"
    role = GOVERNS
    source = ("FEMA P695 (2009) Ch. 7 adapted to overturning (SSF = 1, β_TOT from the quality ratings); Ŝ_CT "
              "counted per Ch. 6 (§6.4) on each record's first overturning intensity; target x from ASCE 7-22 "
              "Table 1.3-2")

    def applies(self, ctx):
        return ctx.margins_run and ctx.rule.collapse_margin_available

    def required(self, ctx):
        return self.role == GOVERNS and ctx.rule.collapse_margin_available

    def evaluate(self, ctx):
        rule = ctx.rule
        x = rule.target
        m = ctx.extra.get("collapse_margin")
        name = (f"Collapse margin (FEMA P695 adaptation): ACMR ≥ ACMR{100 * x:g}% "
                f"(P(collapse | design) ≤ {pct(x)}, risk category {rule.risk_category})")
        if m is None:
            return self.item(math.inf, False, "no first overturning intensities (no completed incremental "
                             "analysis)", "collapse margin: no incremental analysis completed",
                             name=name, evaluated=False)
        beta = m["beta_tot"]
        need = acceptable_acmr(beta, x)
        acmr = m["ACMR"]
        p = collapse_probability(acmr, beta)
        lower = m["CMR_is_lower_bound"]
        ge = "≥ " if lower else ""
        counted = m.get("median_counted") or {}
        im = m.get("im_label") or m["im"]
        half = (f"the {im} at which {counted['k']} of {counted['n']} records have overturned, " if counted else "")
        fitted = ("" if m.get("ACMR_fitted") is None else
                  f"; the fitted lognormal median {m['median_fitted']:.4g} {m['unit']} gives ACMR "
                  f"{m['ACMR_fitted']:.3g}, P(collapse) {pct(m['p_collapse_design_fitted'])} (information)")
        detail = (f"CMR {ge}{m['CMR']:.3g} (Ŝ_CT counted, FEMA P695 §6.4: {half}{ge}{m['median_capacity']:.4g} "
                  f"{m['unit']}, over the design {m['design_intensity']:.4g} {m['unit']}), SSF = 1, ACMR "
                  f"{ge}{acmr:.3g} vs ACMR{100 * x:g}% = exp(−β_TOT Φ⁻¹({x:g})) = {need:.3g} with β_TOT = "
                  f"{beta:.3f}; P(collapse | design) = Φ(−ln ACMR/β_TOT) {'≤ ' if lower else '= '}{pct(p)}{fitted}")
        if lower and acmr < need:
            scan = ctx.analysis.margin_max_scale
            why = counted.get("note", "more than half of the records do not overturn within the scan")
            censored = (f"{counted['n_censored']} of {counted['n']} records" if counted else "records")
            return self.item(need / acmr, False, detail + f"; {why}, so the ACMR is only a lower bound",
                             f"collapse margin not shown: ACMR ≥ {acmr:.3g} (lower bound: {censored} do not "
                             f"overturn up to {scan:g}× design) < {need:.3g}; raise [analysis] margin_max_scale",
                             name=name, evaluated=False)
        passed = acmr >= need
        rel = "≥" if passed else "<"
        reason = (f"ACMR {ge}{acmr:.3g} {rel} {need:.3g} (P(collapse) {'≤ ' if lower else ''}{pct(p)} "
                  f"{'≤' if passed else '>'} {pct(x)})")
        return self.item(need / acmr, passed, detail, reason, name=name)


class CollapseMarginInformative(CollapseMarginAtTarget):
    """The collapse margin reported beside the binomial rule."""

    role = INFORMATIVE


class BinomialBound(Criterion):
    """P(overturn) at the design level ≤ limit at 95 % one-sided confidence over the independent ground motions."""

    key = "overturning_probability"
    role = INFORMATIVE
    source = ("thesis Ch. 6–7 (suite statistics); Clopper & Pearson (1934) exact binomial bound; trials = ground "
              "motions (the components of one station are not independent)")

    def evaluate(self, ctx):
        rule, a = ctx.rule, ctx.analysis
        limit = rule.binomial_limit
        valid = ctx.valid
        bad = unacceptable_ground_motions(valid, _overturned_ids(valid))
        n, k = len(ground_motions_in_order(valid)), len(bad)
        upper = probability_bound(k, n)
        need = minimum_records(limit)
        name = (f"RHA: P(overturn) ≤ {pct(limit)} at 95 % confidence over ground motions (one-sided; "
                f"{_criterion_text(a)} counts as overturning)")
        passed = upper <= limit
        detail = (f"{k} of {n} ground motions ({len(valid)} records) overturn at the design level; one-sided 95 % "
                  f"upper bound {upper:.3g}; a suite needs ≥ {need} ground motions for this bound to reach "
                  f"{pct(limit)}" if need else f"{k} of {n} ground motions overturn; no suite can show a zero limit")
        reason = f"{k} of {n} ground motions overturn at the design level (P ≤ {upper:.3g} at 95 % confidence)"
        if not passed:
            reason += f" > {pct(limit)}" + (f": {_listing(ctx, bad, REASON_LISTING)}" if bad else "")
        return self.item(upper / limit if limit > 0 else math.inf, passed, detail, reason, name=name)


class GoverningBinomialBound(BinomialBound):
    """The binomial bound deciding the verdict (``acceptance = "binomial"``)."""

    role = GOVERNS


class IncrementalMargin(Criterion):
    """Ground motions overturning at some intensity up to the design level (responses are not monotonic)."""

    key = "incremental_margin"
    role = INFORMATIVE
    name = "RHA incremental: ground motions overturning at some intensity ≤ design"
    source = ("thesis Sec 2.2 (Zhang & Makris 2001: safe, overturn, safe again as the amplitude grows); "
              "incremental dynamic analysis (Vamvatsikos & Cornell 2002)")

    def applies(self, ctx):
        return ctx.margins_run

    def evaluate(self, ctx):
        limit = ctx.rule.binomial_limit
        valid = ctx.valid
        first = {o.id: f for o in valid if (f := first_overturn_scale(o)) is not None and f <= 1.0}
        bad = unacceptable_ground_motions(valid, set(first))
        n, k = len(ground_motions_in_order(valid)), len(bad)
        upper = probability_bound(k, n)
        passed = upper <= limit
        ordered = sorted((s, i) for i, s in first.items())
        listing = ", ".join(f"{i} at {s:.3g}×" for s, i in ordered)
        detail = (f"{k} of {n} ground motions overturn at some intensity up to the design level"
                  + (f" ({listing})" if ordered else "") + f"; one-sided 95 % bound {upper:.3g} vs {pct(limit)}"
                  + ("; the collapse margin's fragility uses these first overturning intensities"
                     if ctx.rule.collapse_margin_available else ""))
        if ordered and ordered[0][0] < 1.0:
            s, rid = ordered[0]
            reason = f"overturning at {s:.2g}× design ({rid}" + (f" and {len(ordered) - 1} more)"
                                                                  if len(ordered) > 1 else ")")
        else:
            reason = f"{k} of {n} ground motions overturn at or below the design level"
        reason += f" (P ≤ {upper:.3g} at 95 % confidence)"
        return self.item(upper / limit if limit > 0 else math.inf, passed, detail, reason)


class GoverningIncrementalMargin(IncrementalMargin):
    """The incremental bound deciding the verdict (``acceptance = "binomial"``)."""

    role = GOVERNS


def _draw(ctx, overturned: set[str], failed) -> tuple[bool, int, int, float]:
    """The design-level rule in one perturbed draw of the suite (a failed analysis proves nothing)."""
    holds, k, n, util = count_rule(ctx.rule, ctx.valid, overturned)
    if failed:
        return False, k, n, max(util, 1.0 + len(failed) / max(n, 1))
    return holds, k, n, util


def _rule_words(rule) -> str:
    return "count rule" if rule.method == "asce7" else "binomial bound"


class RestitutionRobustness(Criterion):
    """The design-level rule (count or bound) still holds with c_r × (1 ± variation)."""

    key = "restitution_robustness"
    role = ROBUSTNESS
    source = ("thesis Eqs 3.14, 3.39, 3.80, 4.20 (c_r from conservation of angular momentum, an idealisation; "
              "measured values scatter, Ch. 6)")

    def applies(self, ctx):
        return bool(ctx.sensitivity.get("runs"))

    def evaluate(self, ctx):
        var = ctx.sensitivity.get("variation", ctx.analysis.restitution_variation)
        nominal = _overturned_ids(ctx.valid)
        perturbations, worst, parts = [], 0.0, []
        for run in ctx.sensitivity["runs"].values():
            f = run["restitution_factor"]
            label = f"c_r {'−' if f < 1 else '+'} {100 * abs(1 - f):g} %"
            failed = run.get("failed") or []
            holds, k, n, util = _draw(ctx, nominal ^ set(run["records"]), failed)
            worst = max(worst, util)
            perturbations.append((label, holds))
            changed = f" ({', '.join(run['records'])} change)" if run["records"] else ""
            parts.append(f"{label}: {k} of {n} ground motions unacceptable{changed}"
                         + (f", analyses failed: {', '.join(failed)}" if failed else ""))
        passed = all(h for _, h in perturbations)
        fails = [lab for lab, h in perturbations if not h]
        reason = (f"{_rule_words(ctx.rule)} holds with c_r ± {100 * var:g} %" if passed
                  else "fails with " + " and ".join(fails))
        return self.item(worst, passed, "; ".join(parts), reason,
                         name=f"Robustness: design-level {_rule_words(ctx.rule)} with c_r ± {100 * var:g} %",
                         perturbations=tuple(perturbations))


class EnsembleRobustness(Criterion):
    """The design-level rule still holds in every perturbation-ensemble run of the suite.

    Each ensemble member re-analyses the whole suite with the amplitude × (1 ± 0.1 %) per record, c_r ×
    (1 ± 2 %) and the tolerances one decade tighter (checks/ensemble.py): perturbations well inside the
    input's own accuracy, so each member is another draw of the same suite.
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
        ok = [not o.run.failed for o in ctx.outcomes]
        perturbations, worst, counts = [], 0.0, []
        n = 0
        for m, row in enumerate(ens["overturned"]):
            ids = {o.id for o, x, good in zip(ctx.outcomes, row, ok) if good and bool(x)}
            holds, k, n, util = _draw(ctx, ids, ())
            worst = max(worst, util)
            counts.append(k)
            perturbations.append((f"perturbed suite run {m + 1} (c_r × {float(ens['restitution'][m]):.4f})", holds))
        n_fail = sum(not h for _, h in perturbations)
        size = len(perturbations)
        detail = (f"{size} perturbed runs of the whole suite: unacceptable ground motions per run "
                  f"{', '.join(str(k) for k in counts)} of {n}; records whose outcome flips: "
                  f"{int(sum(not r for r, good in zip(ens['robust'], ok) if good))}")
        reason = (f"{_rule_words(ctx.rule)} holds in all {size} perturbed suite runs" if not n_fail else
                  f"fails in {n_fail} of {size} perturbed suite runs ({draw_words()})")
        return self.item(worst, n_fail == 0, detail, reason,
                         name=f"Robustness: design-level {_rule_words(ctx.rule)} in the perturbation ensembles",
                         perturbations=tuple(perturbations))


class UnacceptableResponsesInformative(UnacceptableResponses):
    """The §16.4.1.1 count reported beside the binomial rule."""

    role = INFORMATIVE

