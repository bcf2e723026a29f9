"""How a suite was scaled, for results.json (``excitation.scaling``, CONTRACT §7.1) and page 1 of the report.

:func:`scaling_block` builds the block for every scaling method from a resolved suite
(:func:`rockdesign.motions.config.resolve_motions`):

* ``asce7-22``: ``standard`` "ASCE 7-22 §16.2.3", the §16.2.1 period range and its basis, the MCE_R target
  and the suite average of the scaled pairs' maximum-direction (RotD100) 5 % spectra on the comparison
  periods, their smallest ratio, ``conformant`` and one factor per ground motion;
* any other method: ``standard`` null; the same spectra where they can be formed; ``conformant`` false when
  a target spectrum is known (the rule's own EN 1998-1 / ASCE 7 design spectrum, or one the caller gives)
  and the suite does not meet ASCE 7-22 §16.2.3.2 against it — average below 90 % somewhere in the range,
  a ground motion with only one component, or two components of one ground motion scaled differently —
  true when it does, null when no target is known; ``note`` says plainly how the suite was scaled and that
  it is not §16.2 scaling.

:func:`scaling_sentence` states the block in one line.  Periods in s, accelerations in m/s² (SI, as all of
results.json).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from .asce7_22 import MINIMUM_RATIO, RATIO_ROUND_OFF, PeriodRange, pair_components, pair_spectra, scaling_grid
from .design_spectra import EC8Spectrum
from .grouping import ground_motion_id

STANDARD = "ASCE 7-22 §16.2.3"
NOT_16_2 = "not ASCE 7-22 §16.2 scaling"


def _method_words(rule, gravity: float) -> str:
    """How one rule scaled its records, in words."""
    if rule.method == "factor":
        return "as recorded (factor 1)" if rule.value == 1.0 else f"every record multiplied by {rule.value:g}"
    if rule.method == "pga":
        return f"scaled to PGA {rule.value / gravity:.3g} g per component (the thesis's and Polyakov's practice)"
    if rule.method == "uplift":
        return f"scaled to PGA {rule.value:g} × the uplift acceleration g tan α per component"
    if rule.method == "sdmax":
        return (f"scaled to SD_max {rule.value:.3g} m per component ({100 * rule.damping:g} % damping, "
                f"{rule.band[0]:g}–{rule.band[1]:g} s; Polyakov's rule 2)")
    if rule.method == "spectrum":
        fit = ("suite-mean single-component PSA matched to the design spectrum in the geometric least-squares "
               "sense" if rule.fit == "mean" else
               f"suite-mean single-component PSA not below {100 * rule.fraction:g} % of the design spectrum")
        return (f"scaled by one factor for all records ({fit} over {rule.band[0]:g}–{rule.band[1]:g} s, "
                f"{100 * rule.damping:g} % damping)")
    return rule.describe(gravity)


def _rule_target(rule):
    """The target spectrum a rule carries, at 5 % damping (ASCE 7-22 §16.2.3 compares 5 % spectra)."""
    if rule.method != "spectrum" or rule.spectrum is None:
        return None
    if isinstance(rule.spectrum, EC8Spectrum) and rule.spectrum.damping != 0.05:
        return replace(rule.spectrum, damping=0.05)
    return rule.spectrum


def suite_target(resolved):
    """The target spectrum (5 % damping) a resolved suite was scaled against, or None: the MCE_R target of
    ASCE 7-22 §16.2.3 scaling, else the design spectrum of a ``spectrum`` rule that scaled the whole suite.
    ``psa(periods)`` [m/s²] of periods [s]; ``describe(g)`` names it."""
    result = getattr(resolved, "asce7_22", None)
    if result is not None:
        return result.target
    rules = list(getattr(resolved, "rules", []) or [])
    return _rule_target(rules[0][1]) if len(rules) == 1 else None


def _describe_target(target, gravity: float) -> str:
    try:
        return target.describe(gravity)
    except TypeError:
        return target.describe()


def _factors(resolved) -> tuple[dict[str, float], bool]:
    """(factors, shared): one per ground motion when its components share it, else one per record."""
    by_gm: dict[str, set[float]] = {}
    for record in resolved.records:
        by_gm.setdefault(ground_motion_id(record.id, record.meta), set()).add(float(record.scale))
    if all(len(v) == 1 for v in by_gm.values()):
        return {gm: next(iter(v)) for gm, v in by_gm.items()}, True
    return {record.id: float(record.scale) for record in resolved.records}, False


def _span(values) -> str:
    lo, hi = min(values), max(values)
    return f"{lo:.3g}" if abs(hi - lo) <= 1e-12 * max(abs(hi), 1.0) else f"{lo:.3g}–{hi:.3g}"


def scaling_block(resolved, *, period_range: PeriodRange | None = None, target=None,
                  gravity: float = 9.81) -> dict:
    """The ``excitation.scaling`` block of results.json (CONTRACT §7.1) for a resolved suite, any method.

    Args:
        resolved: the suite as scaled (:class:`rockdesign.motions.config.ResolvedSuite`).
        period_range: the §16.2.1 period range for comparing a suite not scaled per §16.2 with its target
            (:func:`rockdesign.motions.asce7_22.scaling_period_range` from the structure); default: the
            rule's own band (method ``spectrum``), else none.  An asce7-22 suite carries its own.
        target: a target spectrum to judge a suite scaled by another method against (psa [m/s²] of
            periods [s]); default: the rule's design spectrum (method ``spectrum``), else none.
        gravity: g [m/s²] (for words only).

    Returns:
        {"standard", "method", "period_range", "period_range_basis", "target": {"periods", "psa"} | None,
        "suite_average_max_direction": {"periods", "psa"} | None, "min_ratio", "conformant", "factors",
        "note"} — periods in s, psa in m/s², plain JSON types.
    """
    result = getattr(resolved, "asce7_22", None)
    if result is not None:
        return _asce7_22_block(resolved, result, gravity)
    rules = list(getattr(resolved, "rules", []) or [])
    method = method_block(resolved)["method"]
    how = "; ".join(((f"of {suite or 'the extra records'} " if len(rules) > 1 else "") + _method_words(rule, gravity))
                    for suite, rule in rules) or "none"
    if target is None and len(rules) == 1:
        target = _rule_target(rules[0][1])
    if period_range is None and len(rules) == 1 and rules[0][1].method == "spectrum":
        band = rules[0][1].band
        period_range = PeriodRange(band[0], band[1], "the scale rule's band (excitation.scale.band)")
    factors, shared = _factors(resolved)
    pairs, problems = pair_components([(r.id, r.motion, r.meta) for r in resolved.records])
    block = {"standard": None, "method": method,
             "period_range": period_range.as_list() if period_range else None,
             "period_range_basis": period_range.basis if period_range else None,
             "target": None, "suite_average_max_direction": None, "min_ratio": None, "conformant": None,
             "factors": factors, "note": ""}
    notes = [f"Records {how}; {NOT_16_2}."]
    if not shared:
        notes.append("Factors are per component: the two components of a ground motion were scaled separately.")
    periods = None
    if period_range is not None:
        periods = scaling_grid(period_range, getattr(target, "corner_periods", ()))
        if target is not None and hasattr(target, "covers") and not target.covers(period_range.lo, period_range.hi):
            notes.append(f"The target does not cover {period_range.lo:.3g}–{period_range.hi:.3g} s; "
                         "conformity is not judged.")
            target = None
    average = None
    if periods is not None and pairs and not problems:
        average = np.mean(pair_spectra(pairs, periods), axis=0)
        block["suite_average_max_direction"] = {"periods": periods.tolist(), "psa": average.tolist()}
    if target is None:
        notes.append("No target spectrum is known: conformity with ASCE 7-22 §16.2.3 is not judged.")
        block["note"] = " ".join(notes)
        return block
    if periods is None:
        notes.append("No period range is known: conformity with ASCE 7-22 §16.2.3 is not judged.")
        block["conformant"] = None
        block["note"] = " ".join(notes)
        return block
    n_gm = len(pairs) + len(problems)
    if n_gm < 11:
        notes.append(f"The suite has {n_gm} ground motion{'s' if n_gm != 1 else ''}; ASCE 7-22 §16.2.2 asks for at "
                     "least 11.")
    target_psa = target.psa(periods)
    block["target"] = {"periods": periods.tolist(), "psa": np.asarray(target_psa, dtype=float).tolist()}
    what = f"against {_describe_target(target, gravity)} over {period_range.lo:.3g}–{period_range.hi:.3g} s"
    if problems:
        listed = "; ".join(f"{gm} ({', '.join(ids)}): {why}" for gm, ids, why in problems[:4])
        more = f"; and {len(problems) - 4} more" if len(problems) > 4 else ""
        notes.append(f"Not conformant {what}: ASCE 7-22 §16.2.3.2 needs both horizontal components of every "
                     f"ground motion — {listed}{more}.")
        block["conformant"] = False
        block["note"] = " ".join(notes)
        return block
    ratio = average / target_psa
    low = int(np.argmin(ratio))
    block["min_ratio"] = float(ratio[low])
    meets = bool(ratio[low] >= MINIMUM_RATIO * (1 - RATIO_ROUND_OFF))
    lowest = f"the suite average of the RotD100 5 % spectra is {ratio[low]:.3f} × the target at its lowest " \
             f"({periods[low]:.3g} s)"
    if meets and shared:
        notes.append(f"Conformant {what}: {lowest}, not below 90 %, one factor per ground motion.")
    elif meets:
        notes.append(f"Not conformant {what}: {lowest}, but the components of a ground motion have different "
                     "factors (§16.2.3.2: one factor per ground motion).")
    else:
        notes.append(f"Not conformant {what}: {lowest}, below the 90 % of §16.2.3.2.")
    block["conformant"] = bool(meets and shared)
    block["note"] = " ".join(notes)
    return block


def pair_suite_block(method: str, how: str, factors: dict[str, float]) -> dict:
    """The ``excitation.scaling`` block (CONTRACT §7.1) of a suite of record pairs scaled by another rule than
    ASCE 7-22 §16.2.3 with no target spectrum (e.g. each pair to a peak resultant ground acceleration, thesis
    Table 5.4): ``standard`` null, ``conformant`` null (nothing to judge against), ``factors`` one per pair
    (ground motion), ``note`` how the suite was scaled and that it is not §16.2 scaling.

    Args:
        method: the rule's name (``resultant_pga``, ``factor``).
        how: how the pairs were scaled, in words ("each pair scaled to …").
        factors: ground motion (pair) → its factor [-].
    """
    return {"standard": None, "method": method, "period_range": None, "period_range_basis": None, "target": None,
            "suite_average_max_direction": None, "min_ratio": None, "conformant": None,
            "factors": {str(k): float(v) for k, v in factors.items()},
            "note": (f"Records {how}; {NOT_16_2}. No target spectrum is known: conformity with ASCE 7-22 "
                     "§16.2.3 is not judged.")}


def _asce7_22_block(resolved, result, gravity: float) -> dict:
    n = len(result.factors)
    factors = list(result.factors.values())
    notes = [f"One factor per ground motion ({n}), applied to both of its components: each pair fitted to the "
             f"target alone (geometric least squares over the range, factors {_span(result.fit_factors.values())}),"
             f" then all × {result.multiplier:.4g} so that the suite average of the RotD100 5 % spectra is "
             f"{100 * result.min_ratio:.1f} % of the target at its lowest ({result.min_ratio_period:.3g} s); "
             f"geometric-mean ratio over the range {result.mean_ratio:.3f}; factors {_span(factors)}.",
             f"Target: {_describe_target(result.target, gravity)}."]
    if n < 11:
        notes.append(f"The suite has {n} ground motions; ASCE 7-22 §16.2.2 asks for at least 11.")
    if "time scaled" in getattr(resolved, "scale_description", ""):
        notes.append("Records time-scaled before amplitude scaling (Eq 6.5).")
    return {"standard": STANDARD, "method": "asce7-22",
            "period_range": result.period_range.as_list(), "period_range_basis": result.period_range.basis,
            "target": {"periods": result.periods.tolist(), "psa": result.target_psa.tolist()},
            "suite_average_max_direction": {"periods": result.periods.tolist(), "psa": result.average_psa.tolist()},
            "min_ratio": float(result.min_ratio), "conformant": bool(result.conformant),
            "factors": {gm: float(f) for gm, f in result.factors.items()}, "note": " ".join(notes)}


RECORDS_SCALED = {"factor": "records multiplied by a factor", "pga": "records scaled to PGA",
                  "uplift": "records scaled to the uplift acceleration", "sdmax": "records scaled to SD_max",
                  "spectrum": "records scaled to a design spectrum",
                  "resultant_pga": "record pairs scaled to a resultant PGA", "none": "records as recorded"}
"""How a verdict's headline names a scaling method that is not ASCE 7-22 §16.2's (:func:`headline_basis`)."""


def method_block(resolved) -> dict:
    """The keys of :func:`scaling_block` a verdict's headline reads (``standard``, ``method``, ``conformant``), without
    the spectra it compares: what a design grid's cell needs (:func:`headline_basis`)."""
    result = getattr(resolved, "asce7_22", None)
    if result is not None:
        return {"standard": STANDARD, "method": "asce7-22", "conformant": bool(result.conformant)}
    methods = sorted({rule.method for _, rule in (getattr(resolved, "rules", []) or [])})
    method = methods[0] if len(methods) == 1 else ("none" if not methods else "per suite: " + ", ".join(methods))
    return {"standard": None, "method": method}


def headline_basis(block: dict | None) -> str:
    """What a verdict's headline says about the records when they do not follow ASCE 7-22 §16.2 — "records scaled
    to PGA, not per ASCE 7-22 §16.2" — or "" when they were scaled per §16.2.3 and conform: an acceptance rule of
    ASCE 7-22 §16.4 applied to other records must say so where the verdict is read."""
    if not block:
        return ""
    if block.get("standard"):
        return "" if block.get("conformant") else f"records scaled per {block['standard']}, not conformant"
    method = block.get("method") or "none"
    if method in RECORDS_SCALED:
        words = RECORDS_SCALED[method]
    elif method.startswith("per suite: "):
        words = f"records scaled per suite ({method.removeprefix('per suite: ')})"
    else:
        words = f"records scaled by {method}"
    return f"{words}, not per ASCE 7-22 §16.2"


def scaling_sentence(block: dict, gravity: float = 9.81) -> str:
    """One line for page 1 of the report: how the suite was scaled and whether it conforms (ASCE 7-22 §16.2.3)."""
    lo_hi = block.get("period_range")
    span = f" over {lo_hi[0]:.3g}–{lo_hi[1]:.3g} s" if lo_hi else ""
    if block.get("standard"):
        verdict = "conformant" if block.get("conformant") else "not conformant"
        factors = list(block["factors"].values())
        return (f"Records scaled per {block['standard']}: one factor per ground motion ({len(factors)}; "
                f"{_span(factors)}), suite-average RotD100 spectrum ≥ 90 % of the MCE_R target{span} "
                f"(lowest {block['min_ratio']:.3f}): {verdict}.")
    first = block["note"].split("; " + NOT_16_2, 1)[0].removeprefix("Records ")
    head = f"Records {first} — {NOT_16_2}"
    if block.get("conformant") is None:
        missing = "target spectrum" if "No target spectrum" in block["note"] else "period range"
        return f"{head}; no {missing} to judge it against."
    if block.get("min_ratio") is None:
        return head + "; cannot conform: single components (§16.2.3.2 needs both of every ground motion)."
    verdict = "conformant" if block["conformant"] else "not conformant"
    return (f"{head}; suite-average RotD100 spectrum {block['min_ratio']:.3f} × the target at its lowest{span}: "
            f"{verdict}.")
