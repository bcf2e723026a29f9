"""Rocking spectra at scale (thesis Sec 3.3.2, 4.2.4; SPEC §4; docs/spectra.md).

* :mod:`.axes` — ``AXIS:lo:hi:n`` axes and their normalisations (ω_p/p, ω_p/p̂, T_p; a_p/(g tan α), a_p/g).
* :mod:`.kernel` — the numba job kernel (one analysis per grid point, prange), importable on workers.
* :mod:`rockdesign.execution` — the chunked executor the spectra run on (shared with the checks).
* :mod:`.spectrum` — :func:`compute_spectrum` → :class:`RockingSpectrum`.
* :func:`rockdesign.planar.dynamics.parallel.run_motions` — record suites / scale factors on the same executor.
* :mod:`.lines`, :mod:`.polyakov` — overturning map by impacts, limit-state lines (Table 3.5),
  minimum overturning line, relative spectra (Eq 3.64), equivalent size (Eq 3.65), Polyakov's line.
* :mod:`.output`, :mod:`.figures` — spectrum.npz, summary.json, PNG/SVG figures (CONTRACT §4).
* :mod:`.run` — :func:`~.run.pulse_spectrum`, the whole of ``rockdesign spectrum`` for a planar project (reached
  through ``rd.spectrum`` and the planar kind).
"""
from .axes import DEFAULT_X, DEFAULT_Y, Axis, SpectrumScales, parse_axis, spectrum_scales
from ...execution.executor import ChunkRun, ChunkStore, DaskExecutor, LocalExecutor, fingerprint, make_executor, run_chunks
from .spectrum import RockingSpectrum, SpectrumRequest, compute_spectrum, request_from_project

__all__ = ["Axis", "DEFAULT_X", "DEFAULT_Y", "SpectrumScales", "parse_axis", "spectrum_scales", "ChunkRun",
           "ChunkStore", "DaskExecutor", "LocalExecutor", "fingerprint", "make_executor", "run_chunks",
           "RockingSpectrum", "SpectrumRequest", "compute_spectrum", "request_from_project"]
