"""``rockdesign spectrum cyl.toml --record p695-ff/11 --x R:0.5:30:60 --y pga/up:1:6:51 [--relative other.toml]``."""
from __future__ import annotations

import json
import sys
from pathlib import Path

PLANAR_ONLY = {"pulse": "--pulse", "dask": "--dask", "model": "--model", "structure": "--structure",
               "overturn": "--overturn", "t_free": "--t-free", "rtol": "--rtol", "tm_ratio": "--tm-ratio",
               "chunk_rows": "--chunk-rows", "resume": "--resume/--no-resume", "keep_chunks": "--keep-chunks",
               "energy_stop": "--energy-stop/--no-energy-stop", "stop_at_capacity": "--stop-at-capacity",
               "polyakov": "--polyakov/--no-polyakov", "equivalent_at": "--equivalent-at", "quiet": "--quiet"}
"""Options of ``spectrum`` that a cylinder's spectrum does not use (refused when given)."""


def cylinder_spectrum_command(project, project_path, record, x, y, relative, out, as_json, figures, console) -> None:
    """Compute the cylinder spectrum (and the reference's for ``--relative``), write npz/json/figures."""
    from .. import parse_pair
    from ..library import load_project, spectrum_excitation
    from .. import write_cylinder_spectrum
    from .. import CylinderSpectrumError, cylinder_spectrum, parse_cylinder_axis
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
    other = load_project(relative) if relative is not None else None
    if other is not None and spectrum_excitation(other) != "record pair":
        raise CylinderSpectrumError("a relative cylinder spectrum needs a second cylinder", key="--relative",
                                    expected="a [cylinder] project", found=f"a {other.system.kind}")
    out_dir = Path(out) if out is not None else Path(f"{Path(project_path).stem}-spectrum-{pair.name.replace('/', '-')}")
    from .. import created_folder
    created_folder(out_dir, "-o/--out")         # before any work (removed again if the run fails)
    from .inputs import compile_kernels
    compile_kernels("cylinder-spectrum")
    from .. import progress_bars
    with progress_bars(console, disable=as_json and not console.is_terminal) as bars:
        stage = f"cylinder spectrum of {pair.name}"
        spec = cylinder_spectrum(cyl, pair, xs, ys, rtol=a.rtol, atol=a.atol, free_vibration=a.free_vibration,
                                 rest_velocity=a.rest_velocity, progress=lambda done, n: bars(stage, done, n))
        ref = None
        if other is not None:
            ref = cylinder_spectrum(other.system, pair, xs, ys, rtol=other.analysis.rtol, atol=other.analysis.atol,
                                    free_vibration=other.analysis.free_vibration,
                                    rest_velocity=other.analysis.rest_velocity,
                                    progress=lambda done, n: bars(f"reference ({other.name})", done, n))
    summary = write_cylinder_spectrum(out_dir, spec, ref, project_name=project.name, record_text=text,
                                      relative=relative, overturn_tilt=cyl.overturn_tilt, figures=figures)
    if as_json:
        sys.stdout.write(json.dumps(summary, indent=2) + "\n")
    else:
        console.print(f"{summary['n_points']} analyses in {spec.seconds:.1f} s, {summary['n_overturned']} overturned"
                      f" → {out_dir}")
