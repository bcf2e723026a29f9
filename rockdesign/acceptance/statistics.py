"""Suite statistics for a robust verdict: overturning probability with its confidence interval and
the empirical distribution of θ_max/α (thesis Ch. 6–7: single histories are not predictable)."""
from __future__ import annotations

import numpy as np
from scipy.stats import beta


def overturning_probability(n_overturned: int, n: int, confidence: float = 0.90) -> tuple[float, float, float]:
    """(k/n, lower, upper): Clopper–Pearson exact binomial interval at the given two-sided confidence."""
    if n <= 0:
        return float("nan"), float("nan"), float("nan")
    a = (1.0 - confidence) / 2.0
    k = n_overturned
    lower = 0.0 if k == 0 else float(beta.ppf(a, k, n - k + 1))
    upper = 1.0 if k == n else float(beta.ppf(1.0 - a, k + 1, n - k))
    return k / n, lower, upper


def empirical_cdf(values) -> tuple[np.ndarray, np.ndarray]:
    """(sorted values, F) with F_i = i/n (the step ECDF)."""
    v = np.sort(np.asarray(values, dtype=float))
    return v, np.arange(1, v.size + 1) / v.size if v.size else np.zeros(0)
