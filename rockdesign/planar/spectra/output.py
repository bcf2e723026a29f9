"""Post-processing and the files of ``rockdesign spectrum -o DIR`` (CONTRACT §4).

:func:`analyse` derives everything an engineer reads from a spectrum (overturning map by impacts,
limit-state lines and contours, minimum overturning line, Polyakov's line, relative spectrum and
equivalent size); :func:`write_outputs` writes

* ``spectrum.npz`` — ``x``, ``y`` (axis values), ``theta_max_over_alpha`` (len(y) × len(x)),
  ``overturned`` (bool), ``impacts_before_overturn`` (int, −1 if none) as CONTRACT §4, plus
  ``Tp`` [s], ``ap`` [m/s²], ``exceeded``, ``dynamic``, ``overturn_class``, ``status``, ``steps``,
  ``t_stop``, the lines ``limit_state_I`` … ``limit_state_IV``, ``min_overturn_y``,
  ``polyakov_y``, the contour polylines ``contour_I`` … (x, y rows, NaN between pieces) and, with a
  reference, ``reference_*`` and ``delta_theta_max_over_alpha``;
* ``summary.json`` — axes, system, pulse, analysis settings, results, lines, timings;
* figures ``theta_max``, ``overturning``, ``limit_states`` (and ``relative``) as PNG and SVG.
"""
from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..dynamics.layout import STATUS_NAMES
from .axes import y_unit
from .lines import (LIMIT_STATES, capped_ratio, contour_paths, default_ordinates, display_cap, equivalent_size,
                    join_paths, limit_state_lines, minimum_overturning_line, overturning_classes, relative_spectrum)
from .spectrum import RockingSpectrum
from ...jsonable import json_ready

PULSE_DEFINITIONS = {
    "ricker-anti": "antisymmetric Ricker wavelet (Eq A.2), centred at t_m",
    "ricker-sym": "symmetric Ricker wavelet (Eq A.1), centred at t_m",
    "sine": "one-cycle sine pulse −a_p sin(ω_p t), 0 ≤ t ≤ T_p (Eq 2.20)",
    "cycloidal-a": "Makris–Roussos type-A cycloidal pulse a_p sin(ω_p t) on [0, T_p]",
    "cycloidal-b": "Makris–Roussos type-B cycloidal pulse a_p cos(ω_p t) on [0, T_p]",
    "cycloidal-c": "Makris–Roussos type-C1 cycloidal pulse a_p cos(ω_p t + φ) on [0, (1.5 − φ/π) T_p]",
}


@dataclass
class SpectrumProducts:
    """A spectrum with everything read off it (arrays over x unless stated)."""

    spectrum: RockingSpectrum
    reference: RockingSpectrum | None
    cap: float
    classes: np.ndarray                       # len(y) × len(x): −1 safe, 0, 1, 2 (2+)
    limit_states: dict[str, np.ndarray]       # "I".."IV" → y per column
    contours: dict[str, list]                 # "I".."IV" → list of (k, 2) polylines
    min_overturn: np.ndarray                  # first overturning grid y per column
    polyakov_ap: np.ndarray | None = None     # a_p [m/s²] per column
    polyakov_sd_unit: np.ndarray | None = None
    polyakov_settings: dict | None = None
    reference_limit_states: dict | None = None
    delta: np.ndarray | None = None
    equivalent: dict | None = None
    seconds: float = 0.0
    extra: dict = field(default_factory=dict)

    @property
    def polyakov_y(self) -> np.ndarray | None:
        """Polyakov's line in y-axis units."""
        if self.polyakov_ap is None:
            return None
        s = self.spectrum
        return self.polyakov_ap / y_unit(s.request.y.name, s.scales)


def _lines(s: RockingSpectrum, cap: float):
    psi = s.theta_max_over_alpha
    ot = s.overturned
    ls = limit_state_lines(s.y, psi, ot, cap)
    field_ = capped_ratio(psi, ot, cap)
    contours = {}
    for name, level in LIMIT_STATES:
        if level is None:
            contours[name] = contour_paths(s.x, s.y, ot.astype(float), 0.5)
        else:
            contours[name] = contour_paths(s.x, s.y, field_, level)
    return ls, contours


def analyse(spectrum: RockingSpectrum, reference: RockingSpectrum | None = None, *, polyakov: bool = True,
            damping: float = 0.02, band: tuple[float, float] = (0.05, 10.0),
            ordinates=None) -> SpectrumProducts:
    """Read a spectrum (and optionally compare it with a reference computed on the same grid).

    Args:
        spectrum: the project's spectrum.
        reference: a spectrum of another system on the same axes values (``--relative``).
        polyakov: compute Polyakov's overturning line (SD_max of the pulse = displacement capacity).
        damping, band: of Polyakov's SD_max (SPEC §5: 2 %, 0.05–10 s).
        ordinates: y values at which Eq 3.65 is evaluated (default :func:`default_ordinates`).
    """
    t0 = time.perf_counter()
    s = spectrum
    tc = [s.scales.theta_c / s.scales.alpha]
    if reference is not None:
        if reference.x.shape != s.x.shape or reference.y.shape != s.y.shape or not (
                np.array_equal(reference.periods, s.periods) and np.array_equal(reference.amplitudes, s.amplitudes)):
            raise ValueError("a relative spectrum needs the reference computed at the same pulses (T_p, a_p)")
        tc.append(reference.scales.theta_c / reference.scales.alpha)
    cap = display_cap(*tc)
    ls, contours = _lines(s, cap)
    prod = SpectrumProducts(s, reference, cap, overturning_classes(s.overturned, s.impacts_before_overturn), ls,
                            contours, minimum_overturning_line(s.y, s.overturned))
    if polyakov:
        from .polyakov import polyakov_amplitudes
        prod.polyakov_ap, prod.polyakov_sd_unit = polyakov_amplitudes(
            s.request.pulse, s.periods, s.scales.u_capacity, tm_ratio=s.request.tm_ratio, damping=damping,
            band=band)
        prod.polyakov_settings = {"damping": damping, "band": list(band), "u_capacity": s.scales.u_capacity}
    if reference is not None:
        prod.reference_limit_states, _ = _lines(reference, cap)
        prod.delta = relative_spectrum(s.theta_max_over_alpha, s.overturned, reference.theta_max_over_alpha,
                                       reference.overturned, cap)
        if ordinates is None:
            ordinates = default_ordinates(s.request.y.name, float(s.y[0]), float(s.y[-1]))
        prod.equivalent = equivalent_size(s.x, ls["IV"], prod.reference_limit_states["IV"], ordinates,
                                          reference.scales.R)
    prod.seconds = time.perf_counter() - t0
    return prod


# ----------------------------------------------------------------------------------------- JSON
def system_json(s: RockingSpectrum) -> dict:
    """The analysed system: kind, model, normalisations and key design quantities (SI)."""
    from ..design.quantities import coefficient_of_restitution
    sys_ = s.system
    c = sys_.column
    d = {"name": sys_.name, "kind": sys_.kind, "structure": s.structure, "equations": s.request.equations,
         "model": s.model_label, "extension": c.extension, "height": 2 * c.half_height, "width": 2 * c.half_width,
         "tan_alpha": c.tan_alpha, "mass_distribution": c.mass_distribution,
         "c_r": coefficient_of_restitution(sys_)[0], "gamma": sys_.gamma, "eta": sys_.eta}
    d.update(s.scales.as_json())
    d["theta_c_over_alpha"] = s.scales.theta_c / s.scales.alpha
    return d


def _status_counts(status: np.ndarray) -> dict:
    codes, counts = np.unique(status, return_counts=True)
    return {STATUS_NAMES.get(int(k), str(int(k))): int(n) for k, n in zip(codes, counts)}


def results_json(s: RockingSpectrum, classes: np.ndarray) -> dict:
    ot = s.overturned
    psi = s.theta_max_over_alpha
    safe = ~ot
    d = {"n_analyses": s.n_analyses, "n_overturned": int(ot.sum()),
         "overturned_by_impacts": {"0": int((classes == 0).sum()), "1": int((classes == 1).sum()),
                                   "2+": int((classes == 2).sum())},
         "n_exceeded": int(s.exceeded.sum()), "n_dynamic": int(s.dynamic.sum()),
         "theta_max_over_alpha_max_safe": float(psi[safe].max()) if safe.any() else None,
         "status_counts": _status_counts(s.status), "mean_steps": float(s.steps.mean()) if s.n_analyses else 0.0}
    if ot.any():
        iy, ix = np.unravel_index(np.argmin(np.where(ot, s.y[:, None], np.inf)), ot.shape)
        d["lowest_overturning"] = {"y": float(s.y[iy]), "x": float(s.x[ix]), "Tp": float(s.periods[ix]),
                                   "ap": float(s.amplitudes[iy])}
    else:
        d["lowest_overturning"] = None
    return d


def summary_json(prod: SpectrumProducts, *, project: dict | None = None, reference_project: dict | None = None,
                 files: list[str] | None = None, timings: dict | None = None) -> dict:
    """The ``summary.json`` object (SI; NaN written as null)."""
    s = prod.spectrum
    r = s.request
    pulse = {"kind": r.pulse, "definition": PULSE_DEFINITIONS[r.pulse]}
    if r.pulse.startswith("ricker"):
        pulse["tm_over_Tp"] = r.tm_ratio
    out = {
        "project": project,
        "system": system_json(s),
        "pulse": pulse,
        "axes": {"x": dict(r.x.as_json(), values=s.x), "y": dict(r.y.as_json(), values=s.y),
                 "Tp": s.periods, "ap": s.amplitudes, "shape": list(s.shape)},
        "analysis": {"overturn": r.overturn, "rtol": r.rtol, "atol": r.atol, "t_free": r.t_free,
                     "energy_stop": r.energy_stop, "stop_at_capacity": r.stop_at_capacity,
                     "rest_velocity": r.rest_velocity,
                     "structure": s.structure, "equations": r.equations},
        "results": results_json(s, prod.classes),
        "limit_states": {name: {"theta_max_over_alpha": level, "y": prod.limit_states[name]}
                         for name, level in LIMIT_STATES},
        "minimum_overturning_acceleration": {"y": prod.min_overturn},
        "display_cap": prod.cap,
        "polyakov": None,
        "relative": None,
        "equivalent_size": None,
        "execution": s.execution,
        "timings": timings or {},
        "files": files or [],
    }
    if prod.polyakov_ap is not None:
        out["polyakov"] = dict(prod.polyakov_settings, y=prod.polyakov_y, ap=prod.polyakov_ap,
                               sd_max_unit_pulse=prod.polyakov_sd_unit,
                               rule="a_p such that SD_max(pulse) = u_capacity (Polyakov rule 2, thesis Sec 4.2.5)")
    if prod.reference is not None:
        ref = prod.reference
        ot_p, ot_r = s.overturned, ref.overturned
        out["relative"] = {
            "reference": {"project": reference_project, "system": system_json(ref),
                          "results": results_json(ref, overturning_classes(ot_r, ref.impacts_before_overturn)),
                          "execution": ref.execution},
            "definition": ("Δθ_max/α = ψ_project − ψ_reference, ψ = θ_max/α capped at display_cap, "
                           "overturned = cap (Eq 3.64)"),
            "delta_min": float(np.min(prod.delta)), "delta_max": float(np.max(prod.delta)),
            "n_project_overturns_only": int((ot_p & ~ot_r).sum()),
            "n_reference_overturns_only": int((ot_r & ~ot_p).sum()),
            "reference_limit_states": {name: prod.reference_limit_states[name] for name, _ in LIMIT_STATES},
        }
        out["equivalent_size"] = dict(prod.equivalent, equation="Eq 3.65: R̂ = (x_reference/x_project)² R_reference")
    return json_ready(out)


# ----------------------------------------------------------------------------------------- files
def _figure_context(prod: SpectrumProducts, title: str, reference_title: str | None) -> dict:
    s = prod.spectrum
    ot = s.overturned
    classes = prod.classes
    p_axis = s.scales.p if s.request.x.name == "omega_p/p" else s.scales.p_hat
    return {"x": s.x, "y": s.y, "x_name": s.request.x.name, "x_label": s.request.x.label,
            "y_label": s.request.y.label, "p_axis": p_axis, "cap": prod.cap, "psi": s.theta_max_over_alpha,
            "overturned": ot, "classes": classes, "contours": prod.contours, "limit_states": prod.limit_states,
            "min_overturn": prod.min_overturn, "polyakov": prod.polyakov_y,
            "u_capacity": (prod.polyakov_settings or {}).get("u_capacity"),
            "criterion": "θ_max ≥ θc" if s.request.overturn == "static" else "|θ| = π/2",
            "class_counts": {"safe": int((classes < 0).sum()), "0": int((classes == 0).sum()),
                             "1": int((classes == 1).sum()), "2+": int((classes == 2).sum())},
            "title": f"{title} ({s.request.pulse}, {s.model_label})",
            "reference_limit_states": prod.reference_limit_states, "reference_title": reference_title,
            "delta": prod.delta, "equivalent": prod.equivalent}


def write_outputs(prod: SpectrumProducts, out_dir, *, project: dict | None = None,
                  reference_project: dict | None = None, figures: bool = True, title: str = "",
                  reference_title: str | None = None, timings: dict | None = None) -> dict:
    """Write spectrum.npz, summary.json and the figures into ``out_dir``; returns the summary dict."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    s = prod.spectrum
    t0 = time.perf_counter()
    arrays = {
        "x": s.x, "y": s.y, "theta_max_over_alpha": s.theta_max_over_alpha, "overturned": s.overturned,
        "impacts_before_overturn": s.impacts_before_overturn, "Tp": s.periods, "ap": s.amplitudes,
        "exceeded": s.exceeded, "dynamic": s.dynamic, "overturn_class": prod.classes,
        "status": s.status.astype(np.int8), "steps": s.steps.astype(np.int32), "t_stop": s.t_stop,
        "min_overturn_y": prod.min_overturn,
    }
    for name, _ in LIMIT_STATES:
        arrays[f"limit_state_{name}"] = prod.limit_states[name]
        arrays[f"contour_{name}"] = join_paths(prod.contours[name])
    if prod.polyakov_ap is not None:
        arrays["polyakov_y"] = prod.polyakov_y
    if prod.reference is not None:
        ref = prod.reference
        arrays.update({"reference_theta_max_over_alpha": ref.theta_max_over_alpha,
                       "reference_overturned": ref.overturned,
                       "reference_impacts_before_overturn": ref.impacts_before_overturn,
                       "delta_theta_max_over_alpha": prod.delta})
        for name, _ in LIMIT_STATES:
            arrays[f"reference_limit_state_{name}"] = prod.reference_limit_states[name]
    tmp = out_dir / "spectrum.tmp.npz"
    np.savez_compressed(tmp, **arrays)
    tmp.replace(out_dir / "spectrum.npz")
    files = ["spectrum.npz", "summary.json"]
    t_fig = time.perf_counter()
    if figures:
        from . import figures as fg
        ctx = _figure_context(prod, title or s.system.name, reference_title)
        files += fg.save_both(fg.theta_max_figure(ctx), out_dir, "theta_max")
        files += fg.save_both(fg.overturning_figure(ctx), out_dir, "overturning")
        files += fg.save_both(fg.limit_states_figure(ctx), out_dir, "limit_states")
        if prod.reference is not None:
            files += fg.save_both(fg.relative_figure(ctx), out_dir, "relative")
    timings = dict(timings or {})
    timings["files_s"] = t_fig - t0
    timings["figures_s"] = time.perf_counter() - t_fig
    if timings.get("wall_s") is not None:
        timings["wall_s"] += time.perf_counter() - t0  # the caller's wall time up to the files, plus the files
    summary = summary_json(prod, project=project, reference_project=reference_project, files=files,
                           timings=timings)
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=1, ensure_ascii=False) + "\n")
    return summary
