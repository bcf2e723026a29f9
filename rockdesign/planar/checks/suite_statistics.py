"""The suite statistics of a planar check (results.json ``summary``): overturning counts and probability with its
90 % interval, the Fig 4.9 classes, the ECDF of θ_max/α and, with the incremental analysis, the margins."""
from __future__ import annotations

import math
import statistics as pystats

import numpy as np

from ...acceptance.statistics import empirical_cdf, overturning_probability
from .polyakov import CLASS_MEANING, CLASSES


def suite_statistics(outcomes: list, a, with_margins: bool) -> dict:
    """The ``summary`` of the valid record outcomes (:class:`~.check.RecordOutcome`) under the settings ``a``."""
    n = len(outcomes)
    k = sum(o.run.overturned for o in outcomes)
    k_dyn = sum(o.run.overturn_mode == "dynamic" for o in outcomes)
    p, lo, hi = overturning_probability(k, n, 0.90)
    classes = {c: sum(o.klass == c for o in outcomes) for c in CLASSES}
    x, f = empirical_cdf([o.run.theta_max_over_alpha for o in outcomes])
    out = {
        "n_records": n,
        "n_overturned": k,
        "n_overturned_dynamic": k_dyn,
        "n_exceeded_capacity": sum(o.run.overturn_mode != "none" for o in outcomes),
        "overturn_criterion": a.overturn,
        "n_false_negative": classes["b"],
        "classes": classes,
        "class_meaning": CLASS_MEANING,
        "p_overturn": p,
        "p_overturn_ci90": [lo, hi],
        "theta_max_over_alpha_ecdf": {"x": [float(v) for v in x], "F": [float(v) for v in f]},
        "median_theta_max_over_alpha": float(np.median(x)) if n else None,
        "max_polyakov_ratio": max((o.polyakov_ratio for o in outcomes), default=None),
        "max_theta_max_over_theta_c": max((o.run.theta_max_over_theta_c for o in outcomes), default=None),
    }
    if with_margins and outcomes:
        vals = [o.margin.overturn_scale if o.margin.overturn_scale is not None else math.inf for o in outcomes]
        finite = [v for v in vals if math.isfinite(v)]
        censored = len(vals) - len(finite)
        med = pystats.median(vals)
        out.update({
            "median_margin": None if math.isinf(med) else med,
            "median_margin_censored": bool(math.isinf(med)),
            "min_margin": min(finite) if finite else None,
            "n_margin_above_scan": censored,
            "n_margin_below_design": sum(1 for v in finite if v < 1.0),
            "margin_scan_max": a.margin_max_scale,
            "median_polyakov_scale": pystats.median([o.polyakov_scale for o in outcomes]),
            "n_polyakov_unconservative_margin": sum(
                1 for o in outcomes if o.margin.overturn_scale is not None and o.margin.overturn_scale < o.polyakov_scale),
            "n_nonmonotonic": sum(1 for o in outcomes if len(o.margin.intervals) > 1 or (
                o.margin.intervals and o.margin.intervals[0][1] is not None)),
        })
    else:
        out["median_margin"] = None
    return out
