"""Reading a rocking spectrum: overturning map by impacts, limit-state lines, minimum overturning line,
relative spectra and the equivalent size of Eq 3.65 (thesis Sec 3.3.2, Table 3.5, Eqs 3.64–3.65).

Conventions (arrays len(y) × len(x), rows = amplitudes, columns = pulse frequencies or periods):

* ψ = θ_max/α; for maps and contours ψ is *capped*: overturned points count as the cap
  (:func:`display_cap`, 1.5 as the thesis's colour scale, or θc/α if larger), so "overturned" is the
  top of the scale whatever θ_max the analysis reached.
* A limit-state line (Table 3.5: I 0.25α, II 0.50α, III 1.00α, IV overturning) is, in each column,
  the lowest amplitude at which the limit state is reached: the first upward crossing of the level by
  the capped ψ, interpolated linearly between grid rows — the lowest branch of the contour line at
  that level (as the thesis extracts them "from the contour plots, as minimum overturning lines").
  Line IV is the contour of the overturning indicator at ½: the midpoint between the last safe row
  and the first overturning row.
* The minimum overturning acceleration line is the first overturning grid row of each column (an
  upper bound on the true minimum within one row spacing).
"""
from __future__ import annotations

import math

import numpy as np

LIMIT_STATES = (("I", 0.25), ("II", 0.50), ("III", 1.00), ("IV", None))
"""Thesis Table 3.5: limit state name and θ_max/α (None: overturning)."""
DISPLAY_CAP = 1.5
"""Top of the θ_max/α colour scale of thesis Figs 3.19–3.22 (overturned points are shown there)."""


def display_cap(*theta_c_over_alpha: float) -> float:
    """The cap of ψ = θ_max/α for maps and relative spectra: max(1.5, θc/α of every system compared)."""
    return max([DISPLAY_CAP] + [float(v) for v in theta_c_over_alpha])


def capped_ratio(theta_max_over_alpha: np.ndarray, overturned: np.ndarray, cap: float) -> np.ndarray:
    """ψ capped at ``cap``, with overturned points set to the cap."""
    psi = np.minimum(np.asarray(theta_max_over_alpha, dtype=float), cap)
    return np.where(overturned, cap, psi)


def overturning_classes(overturned: np.ndarray, impacts_before_overturn: np.ndarray) -> np.ndarray:
    """Overturning map split by the impacts before overturning (thesis Figs 2.4a, 3.19b–3.20b).

    Returns:
        int8 array: −1 safe, 0 overturned without impact, 1 with one impact, 2 with two or more.
    """
    cls = np.minimum(np.asarray(impacts_before_overturn), 2).astype(np.int8)
    cls[~np.asarray(overturned, dtype=bool)] = -1
    cls[(np.asarray(overturned, dtype=bool)) & (cls < 0)] = 0
    return cls


def first_crossing_line(y: np.ndarray, field: np.ndarray, level: float) -> np.ndarray:
    """Per column, the lowest y where ``field`` (len(y) × len(x)) first reaches ``level``.

    Linear interpolation between the last row below the level and the first row at or above it;
    y[0] where the first row already reaches it; NaN where no row does.
    """
    y = np.asarray(y, dtype=float)
    f = np.asarray(field, dtype=float)
    reached = f >= level
    any_ = reached.any(axis=0)
    k = np.argmax(reached, axis=0)
    line = np.full(f.shape[1], np.nan)
    for j in np.nonzero(any_)[0]:
        i = k[j]
        if i == 0:
            line[j] = y[0]
            continue
        f0, f1 = f[i - 1, j], f[i, j]
        w = (level - f0) / (f1 - f0) if f1 != f0 else 1.0
        line[j] = y[i - 1] + min(max(w, 0.0), 1.0) * (y[i] - y[i - 1])
    return line


def overturning_line(y: np.ndarray, overturned: np.ndarray) -> np.ndarray:
    """Limit state IV: per column the midpoint between the last safe row and the first overturning
    row (the ½-contour of the overturning indicator); y[0] if the first row overturns; NaN if none."""
    return first_crossing_line(y, np.asarray(overturned, dtype=float), 0.5)


def minimum_overturning_line(y: np.ndarray, overturned: np.ndarray) -> np.ndarray:
    """Per column, the lowest grid amplitude y that overturns (NaN: no overturning in the column)."""
    ot = np.asarray(overturned, dtype=bool)
    line = np.full(ot.shape[1], np.nan)
    has = ot.any(axis=0)
    line[has] = np.asarray(y, dtype=float)[np.argmax(ot, axis=0)[has]]
    return line


def limit_state_lines(y: np.ndarray, theta_max_over_alpha: np.ndarray, overturned: np.ndarray,
                      cap: float) -> dict[str, np.ndarray]:
    """Lines I–IV of thesis Table 3.5 (see the module docstring), keyed by ``"I"`` … ``"IV"``."""
    psi = capped_ratio(theta_max_over_alpha, overturned, cap)
    out = {}
    for name, level in LIMIT_STATES:
        out[name] = overturning_line(y, overturned) if level is None else first_crossing_line(y, psi, level)
    return out


def contour_paths(x: np.ndarray, y: np.ndarray, field: np.ndarray, level: float) -> list[np.ndarray]:
    """All contour lines of ``field`` at ``level`` as (k, 2) arrays of (x, y) points (contourpy)."""
    import contourpy
    f = np.asarray(field, dtype=float)
    if f.shape[0] < 2 or f.shape[1] < 2:
        return []
    gen = contourpy.contour_generator(np.asarray(x, float), np.asarray(y, float), f,
                                      line_type=contourpy.LineType.Separate)
    return [np.asarray(p) for p in gen.lines(level)]


def join_paths(paths: list[np.ndarray]) -> np.ndarray:
    """Concatenate polylines into one (k, 2) array with NaN rows between them (for npz files)."""
    if not paths:
        return np.zeros((0, 2))
    parts = []
    for p in paths:
        parts.append(p)
        parts.append(np.full((1, 2), np.nan))
    return np.concatenate(parts[:-1], axis=0)


def relative_spectrum(psi_project: np.ndarray, overturned_project: np.ndarray, psi_reference: np.ndarray,
                      overturned_reference: np.ndarray, cap: float) -> np.ndarray:
    """Δθ_max/α = ψ_project − ψ_reference (Eq 3.64 over α), both capped (overturned = cap).

    Negative: the project responds less (better) than the reference; +(cap − 1) or more: the project
    overturns where the reference survives (thesis Fig 3.22: |Δ| ≥ 0.5 with the 1.5 cap).
    """
    return (capped_ratio(psi_project, overturned_project, cap)
            - capped_ratio(psi_reference, overturned_reference, cap))


def crossing_abscissa(x: np.ndarray, line: np.ndarray, y0: float) -> float | None:
    """The abscissa where an overturning line passes the ordinate ``y0``.

    The overturning region lies above the line; at the ordinate y0 it extends up to the largest x
    whose line value is ≤ y0.  Linear interpolation towards the next column (whose line is above
    y0, or absent: then the midpoint).  None if no column overturns at y0, or if the region reaches
    the end of the x grid (the crossing lies outside the spectrum).
    """
    x = np.asarray(x, dtype=float)
    line = np.asarray(line, dtype=float)
    below = np.nonzero(np.isfinite(line) & (line <= y0))[0]
    if below.size == 0:
        return None
    j = int(below.max())
    if j == x.size - 1:
        return None
    l0, l1 = line[j], line[j + 1]
    if not math.isfinite(l1):
        return float(0.5 * (x[j] + x[j + 1]))
    w = (y0 - l0) / (l1 - l0) if l1 != l0 else 0.0
    return float(x[j] + min(max(w, 0.0), 1.0) * (x[j + 1] - x[j]))


def equivalent_size(x: np.ndarray, line_project: np.ndarray, line_reference: np.ndarray, ordinates,
                    R_reference: float) -> dict:
    """Eq 3.65 at several ordinates: R̂ = (x_ref/x_proj)² R_ref from the two overturning lines.

    Both spectra must share their axes (the same physical pulses at each grid point, as the
    thesis's B1–B5 do).  R̂ is the size of a body of the reference's type (same α and λ) whose
    overturning line coincides with the project's at that ordinate.

    Returns:
        {"ordinates", "x_reference", "x_project", "R_hat_over_R", "R_hat", "median_R_hat_over_R",
        "median_R_hat"} (None where a line does not cross the ordinate inside the grid).
    """
    from ..design.equivalence import equivalent_size_from_spectra
    xs_ref, xs_pro, ratio = [], [], []
    for y0 in ordinates:
        a = crossing_abscissa(x, line_reference, float(y0))
        b = crossing_abscissa(x, line_project, float(y0))
        xs_ref.append(a)
        xs_pro.append(b)
        ratio.append(equivalent_size_from_spectra(a, b) if (a is not None and b is not None and b > 0) else None)
    valid = [r for r in ratio if r is not None]
    med = float(np.median(valid)) if valid else None
    return {"ordinates": [float(v) for v in ordinates], "x_reference": xs_ref, "x_project": xs_pro,
            "R_hat_over_R": ratio, "R_hat": [None if r is None else r * R_reference for r in ratio],
            "median_R_hat_over_R": med, "median_R_hat": None if med is None else med * R_reference,
            "R_reference": R_reference}


def default_ordinates(axis_name: str, lo: float, hi: float) -> list[float]:
    """Ordinates at which Eq 3.65 is evaluated by default: 3, 4, 5 (the thesis's), 6 and 8 for
    ``ap/up`` when inside the axis, else five evenly spread interior values."""
    if axis_name == "ap/up":
        vals = [v for v in (3.0, 4.0, 5.0, 6.0, 8.0) if lo < v < hi]
        if vals:
            return vals
    return [lo + (hi - lo) * k / 6.0 for k in range(1, 6)]
