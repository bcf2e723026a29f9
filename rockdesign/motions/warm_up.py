"""The elastic response spectrum's first-run warm-up (:mod:`rockdesign.execution.compilation`), kept apart from
the kernels' module so that the compilation machinery is not among the sources digested for the kernel cache."""
from __future__ import annotations

from ..execution.compilation import Kernels


def elastic_spectrum() -> None:
    """SD_max of a four-sample record: the elastic-spectrum kernels, for the argument types of the real calls."""
    import numpy as np

    from .motion import record_motion
    from .spectra import sd_max
    sd_max(record_motion("warm-up", np.array([0.0, 0.3, -0.3, 0.0]) * 9.81, 0.01))


ELASTIC_SPECTRUM = Kernels("elastic-spectrum", elastic_spectrum, 2.0)
"""The elastic response spectrum and SD_max (``records``, Polyakov's rule in a check), compiled on a first run."""
