"""Defaults of Polyakov's SD_max (SPEC §5): damping ratio, period band and period grid.

A module of its own, free of numba and numpy, so that the CLI can show them in ``--help`` without
loading the spectra kernels (:mod:`rockdesign.motions.spectra` re-exports them).
"""
from __future__ import annotations

DEFAULT_DAMPING = 0.02
"""Damping ratio of Polyakov's SD_max (SPEC §5)."""

DEFAULT_BAND = (0.05, 10.0)
"""Period band [s] of SD_max (SPEC §5)."""

DEFAULT_N_PERIODS = 400
"""Points of the logarithmic period grid before refinement."""
