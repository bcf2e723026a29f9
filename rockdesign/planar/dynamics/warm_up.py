"""The planar engine's first-run warm-ups: its kernels called once on a tiny problem, with the argument types
of the real calls (numba then keeps the machine code in the kernel cache; :mod:`rockdesign.execution.compilation`)."""
from __future__ import annotations

from ...execution.compilation import Kernels


def _record():
    import numpy as np

    from ...motions.motion import record_motion
    return record_motion("warm-up", np.array([0.0, 0.3, -0.3, 0.0]) * 9.81, 0.01)


def engine() -> None:
    """The rocking engine: the serial driver (``simulate``'s one analysis, the job and the integrator it runs)
    and the parallel batch kernel around the integrator."""
    from ..system import block
    from .batch import batch_options, run_batch
    from .model import ModelChoice, system_parameters
    from .simulate import simulate

    system, record = block(1.5, 0.15), _record()
    simulate(system, record, t_end=0.05)
    sp = system_parameters(system, ModelChoice("block", "exact"))
    run_batch(sp, [record, record], [1.0, 0.5], [0.05, 0.05], batch_options(), threads=True)


def linear_exact() -> None:
    """The closed-form integrator of the linearized equations (the report's accuracy statement, the benchmarks)."""
    from .accuracy import accuracy_problem
    from .simulate import simulate

    system, pulse = accuracy_problem()
    simulate(system, pulse, model="linear-exact", t_end=0.05)


ENGINE = Kernels("planar-engine", engine, 42.0)
"""The batch kernel and the integrator it runs (every planar analysis)."""
LINEAR_EXACT = Kernels("planar-linear-exact", linear_exact, 5.0)
"""The closed-form linear integrator."""
