"""First-run compilation of the cylinder's kernels (:mod:`rockdesign.execution.compilation` reaches it by
name, so the planar engine's package imports nothing of the cylinder's)."""
from __future__ import annotations

from ..motions.pairs import pair_of_records
from .engine import simulate_cylinder
from .spectrum import cylinder_spectrum
from .system import cylinder


def warm_up(command: str, record) -> None:
    """The cylinder's integrator (or, for ``cylinder-spectrum``, its spectrum grid) on a short record pair
    built from ``record`` (a :class:`~rockdesign.motions.motion.GroundMotion` of a few samples)."""
    cyl = cylinder(1.5, 0.3)
    pair = pair_of_records("warm-up", record, record)
    if command == "cylinder-spectrum":
        cylinder_spectrum(cyl, pair, [cyl.R], [1.0], free_vibration=0.05)
    else:
        simulate_cylinder(cyl, pair, t_end=0.05)
