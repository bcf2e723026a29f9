"""The cylinder's first-run warm-ups: its kernels called once on a short record pair, with the argument types of
the real calls (:mod:`rockdesign.execution.compilation`)."""
from __future__ import annotations

from ..execution.compilation import Kernels


def _cylinder_and_pair():
    import numpy as np

    from ..motions.motion import record_motion
    from .pairs import pair_of_records
    from .system import cylinder

    record = record_motion("warm-up", np.array([0.0, 0.3, -0.3, 0.0]) * 9.81, 0.01)
    return cylinder(1.5, 0.3), pair_of_records("warm-up", record, record)


def integrator() -> None:
    """The cylinder's integrator (Eqs 5.22–5.31) on a 0.05-s record pair."""
    from .engine import simulate_cylinder
    cyl, pair = _cylinder_and_pair()
    simulate_cylinder(cyl, pair, t_end=0.05)


def spectrum_grid() -> None:
    """The cylinder's parallel spectrum grid on one point."""
    from .spectrum import cylinder_spectrum
    cyl, pair = _cylinder_and_pair()
    cylinder_spectrum(cyl, pair, [cyl.R], [1.0], free_vibration=0.05)


INTEGRATOR = Kernels("cylinder-integrator", integrator, 28.0)
SPECTRUM = Kernels("cylinder-spectrum", spectrum_grid, 35.0)
