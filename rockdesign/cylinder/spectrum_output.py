"""The files of a cylinder spectrum (``rockdesign spectrum cyl.toml --record …``): ``spectrum.npz``
(arrays), ``summary.json`` and the figures (thesis Figs 5.16/5.17), written by the library so a notebook
user gets the same folder as the command line."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..plots import save
from .spectrum import spectrum_figure


def write_cylinder_spectrum(out_dir, spec, ref=None, *, project_name: str, record_text: str, relative=None,
                            overturn_tilt: float, figures: bool = True) -> dict:
    """Write the spectrum (and the reference's, for a relative spectrum) into ``out_dir``; returns summary.json."""
    out_dir = Path(out_dir)
    text = record_text
    out_dir.mkdir(parents=True, exist_ok=True)
    arrays = {"x": spec.x, "y": spec.y, "theta_max_over_alpha": spec.theta_max_over_alpha,
              "overturned": spec.overturned, "quasi_impacts": spec.quasi_impacts}
    if ref is not None:
        arrays.update(reference_theta_max_over_alpha=ref.theta_max_over_alpha, reference_overturned=ref.overturned,
                      relative=spec.theta_max_over_alpha - ref.theta_max_over_alpha)
    np.savez_compressed(out_dir / "spectrum.npz", **arrays)
    summary = {"system": "cylinder", "project": project_name, "record": text, "model": spec.model,
               "axes": {"x": {"name": "R", "unit": "m", "values": [float(v) for v in spec.x]},
                        "y": {"name": "pga/up", "definition": "max √(ü_gx² + ü_gy²) / (g tan α) (Eq 5.43)",
                              "values": [float(v) for v in spec.y]}},
               "n_points": int(spec.x.size * spec.y.size), "n_overturned": int(spec.overturned.sum()),
               "seconds": spec.seconds, "reference": None if ref is None else {
               "project": str(relative), "model": ref.model, "seconds": ref.seconds,
               "n_overturned": int(ref.overturned.sum()),
               "n_outcome_differs": int((spec.overturned != ref.overturned).sum())}}
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    if figures:
        save(spectrum_figure(spec, f"{project_name} — {text}", overturn_tilt=overturn_tilt),
             out_dir / "spectrum.png")
        if ref is not None:
            save(spectrum_figure(spec, f"relative: {project_name} vs {relative}", ref), out_dir / "relative.png")
    return summary
