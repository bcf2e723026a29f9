"""The rocking spectrum of a cylinder project for one record pair, written to a folder: the work of
``rockdesign spectrum cyl.toml --record p695-ff/11`` (thesis Figs 5.16–5.17; docs/cylinder.md), reached through
``rd.spectrum`` and the cylinder kind.

:func:`record_pair_spectrum` validates the record pair, the axes and the output folder before any work,
compiles the spectrum kernel on a first run, runs the grid (:func:`rockdesign.cylinder.spectrum.cylinder_spectrum`;
and the reference project's on the same grid for a relative spectrum) and writes ``spectrum.npz``,
``summary.json`` and the figures (:func:`rockdesign.cylinder.spectrum_output.write_cylinder_spectrum`).
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from ..errors import RockdesignError
from ..execution import compilation
from ..execution.executor import check_executor, running_on
from .pairs import parse_pair
from ..outdir import created_folder
from .spectrum import CylinderSpectrum, CylinderSpectrumError, cylinder_spectrum, parse_cylinder_axis
from .spectrum_output import write_cylinder_spectrum
from .warm_up import SPECTRUM

DEFAULT_X = "R:0.5:30:60"
"""Sizes R [m] of the thesis's Fig 5.16 grid."""
DEFAULT_Y = "pga/up:1:6:51"
"""Resultant PGA over g tan α (Eq 5.43) of the thesis's Fig 5.16 grid."""


@dataclass
class CylinderSpectrumRun:
    """A cylinder's rocking spectrum and the folder it was written to.

    Attributes:
        out_dir: the output folder (spectrum.npz, summary.json, figures).
        summary: the summary.json object (docs/cylinder.md).
        spectrum: θ_max/α (θ_ot/α where overturned) over R [m] × max|ü_g|/(g tan α).
        reference: the reference project's spectrum on the same grid (``relative``), or None.
    """

    out_dir: Path
    summary: dict
    spectrum: CylinderSpectrum
    reference: CylinderSpectrum | None

    def as_json(self) -> dict:
        """summary.json (the ``spectrum --json`` output)."""
        return self.summary

    @property
    def title(self) -> str:
        return f"cylinder rocking spectrum — {self.summary['project']}"

    def summary_rows(self) -> list[tuple[str, str]]:
        """(quantity, value) rows of the console summary."""
        s, spec = self.summary, self.spectrum
        x, y = spec.x, spec.y
        rows = [("record pair", s["record"]), ("model", s["model"]),
                ("grid", f"R {x[0]:g}…{x[-1]:g} m ({x.size}) × pga/up {y[0]:g}…{y[-1]:g} ({y.size})"),
                ("analyses", f"{s['n_points']:,}"), ("overturned", f"{s['n_overturned']:,}")]
        ref = s["reference"]
        if ref is not None:
            rows.append(("reference", f"{ref['project']} ({ref['model']}): {ref['n_overturned']:,} overturned, "
                                      f"{ref['n_outcome_differs']:,} outcomes differ"))
        seconds = spec.seconds + (self.reference.seconds if self.reference is not None else 0.0)
        rows += [("time", f"{seconds:.1f} s computing"), ("output", str(self.out_dir))]
        return rows


def record_pair_spectrum(project, *, record: str | None = None, x: str | None = None, y: str | None = None,
                         relative=None, out_dir: str | Path | None = None, figures: bool = True,
                         progress: Callable[[str, int, int], None] | None = None, say=None,
                         executor=None) -> CylinderSpectrumRun:
    """θ_max/α of a cylinder project's slenderness and contact over sizes R and resultant PGAs of one record pair
    (thesis Figs 5.16–5.17), written into ``out_dir``.  The parameters are those of ``rd.spectrum``.

    Args:
        project: a cylinder :class:`~rockdesign.project_tables.Project`.
        record: the record pair: ``p695-ff/11`` or any ``record:``/``files:`` motion string of a pair.
        x: ``R:lo:hi:n`` (sizes [m]; default ``R:0.5:30:60``).
        y: ``pga/up:lo:hi:n`` (max|ü_g|/(g tan α), Eq 5.43; default ``pga/up:1:6:51``).
        relative: a second cylinder project on the same grid: the relative spectrum (Fig 5.16b/5.17).
        out_dir: output folder (default: ``<project file stem>-spectrum-<pair>``).
        figures: write spectrum.png (and relative.png).
        progress: ``progress(stage, done, total)`` as blocks of grid points finish.
        say: prints the first-run compilation announcement.
        executor: None (this process, every core), a ``--dask`` value ("local:N", a scheduler address; started and
            closed here) or an executor object: the grid's blocks of amplitude rows run there.
    """
    if not record:
        raise CylinderSpectrumError("a cylinder spectrum needs a record pair", key="record",
                                    expected="a record pair such as p695-ff/11 (or any record/files motion string)",
                                    found="none")
    text = record if ":" in record else f"record:{record}"
    cyl = project.system
    try:
        pair = parse_pair(text, gravity=cyl.g).pair
    except RockdesignError as exc:       # the motion string is this function's record
        if exc.key == "motion":
            exc.key = "record"
            exc.args = (exc.format(),)
        raise
    _, xs = parse_cylinder_axis(DEFAULT_X if x is None else x, "x")
    _, ys = parse_cylinder_axis(DEFAULT_Y if y is None else y, "y")
    out_dir = Path(out_dir) if out_dir is not None else \
        Path(f"{Path(project.path).stem}-spectrum-{pair.name.replace('/', '-')}")
    check_executor(executor)                   # a dask value checked (and its scheduler reached) before any work
    created_folder(out_dir, "out_dir")         # before any work (removed again if the run fails)
    compilation.prepare("spectrum", (SPECTRUM,), say)

    def run(prj, stage: str, on) -> CylinderSpectrum:
        a = prj.analysis
        return cylinder_spectrum(prj.system, pair, xs, ys, rtol=a.rtol, atol=a.atol, free_vibration=a.free_vibration,
                                 rest_velocity=a.rest_velocity,
                                 progress=(lambda done, n: progress(stage, done, n)) if progress else None, executor=on)

    with running_on(executor) as on:
        spec = run(project, f"cylinder spectrum of {pair.name}", on)
        ref = run(relative, f"reference ({relative.name})", on) if relative is not None else None
    summary = write_cylinder_spectrum(out_dir, spec, ref, project_name=project.name, record_text=text,
                                      relative=relative.path if relative is not None else None,
                                      overturn_tilt=cyl.overturn_tilt, figures=figures)
    return CylinderSpectrumRun(out_dir, summary, spec, ref)
