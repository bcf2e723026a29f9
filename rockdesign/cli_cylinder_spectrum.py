"""``rockdesign spectrum cyl.toml --record p695-ff/11 --x R:0.5:30:60 --y pga/up:1:6:51 [--relative other.toml]``."""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np


def cylinder_spectrum_command(project, project_path, record, x, y, relative, out, as_json, figures, console) -> None:
    """Compute the cylinder spectrum (and the reference's for ``--relative``), write npz/json/figures."""
    from .motions.pairs import parse_pair
    from .project import load_project
    from .plots import save
    from .cylinder.spectrum import CylinderSpectrumError, cylinder_spectrum, parse_cylinder_axis, spectrum_figure
    if not record:
        raise CylinderSpectrumError("a cylinder spectrum needs a record pair", key="--record",
                                    expected="--record p695-ff/11 (or any record/files motion string)", found="none")
    text = record if ":" in record else f"record:{record}"
    cyl = project.system
    pair = parse_pair(text, gravity=cyl.g).pair
    # the planar defaults of --x/--y become the thesis's Fig 5.16 grid for a cylinder
    _, xs = parse_cylinder_axis("R:0.5:30:60" if x.startswith("omega_p/p:0.5:12:") else x, "x")
    _, ys = parse_cylinder_axis("pga/up:1:6:51" if y.startswith("ap/up:0:12:") else y, "y")
    a = project.analysis
    console.print(f"cylinder spectrum: {ys.size} × {xs.size} analyses of {pair.name} …")
    spec = cylinder_spectrum(cyl, pair, xs, ys, rtol=a.rtol, atol=a.atol, free_vibration=a.free_vibration,
                             rest_velocity=a.rest_velocity)
    ref = None
    if relative is not None:
        other = load_project(relative)
        if other.system.kind != "cylinder":
            raise CylinderSpectrumError("a relative cylinder spectrum needs a second cylinder", key="--relative",
                                        expected="a [cylinder] project", found=f"a {other.system.kind}")
        ref = cylinder_spectrum(other.system, pair, xs, ys, rtol=other.analysis.rtol, atol=other.analysis.atol,
                                free_vibration=other.analysis.free_vibration,
                                rest_velocity=other.analysis.rest_velocity)
    out_dir = Path(out) if out is not None else Path(f"{Path(project_path).stem}-spectrum-{pair.name.replace('/', '-')}")
    out_dir.mkdir(parents=True, exist_ok=True)
    arrays = {"x": spec.x, "y": spec.y, "theta_max_over_alpha": spec.theta_max_over_alpha,
              "overturned": spec.overturned, "quasi_impacts": spec.quasi_impacts}
    if ref is not None:
        arrays.update(reference_theta_max_over_alpha=ref.theta_max_over_alpha, reference_overturned=ref.overturned,
                      relative=spec.theta_max_over_alpha - ref.theta_max_over_alpha)
    np.savez_compressed(out_dir / "spectrum.npz", **arrays)
    summary = {"system": "cylinder", "project": project.name, "record": text, "model": spec.model,
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
        save(spectrum_figure(spec, f"{project.name} — {text}", overturn_tilt=cyl.overturn_tilt),
             out_dir / "spectrum.png")
        if ref is not None:
            save(spectrum_figure(spec, f"relative: {project.name} vs {relative}", ref), out_dir / "relative.png")
    if as_json:
        sys.stdout.write(json.dumps(summary, indent=2) + "\n")
    else:
        console.print(f"{summary['n_points']} analyses in {spec.seconds:.1f} s, {summary['n_overturned']} overturned"
                      f" → {out_dir}")
