"""The planar engine's first-run warm-up: its kernels called once on a tiny problem (numba then keeps the
machine code in its cache; :mod:`rockdesign.execution.compilation`)."""
from __future__ import annotations


def warm_up(command: str, parts, engine_commands, warm_ups, cylinder_warm_up) -> None:
    """Call the kernels of ``command`` once on a tiny problem, with the argument types of the real calls
    (:func:`rockdesign.execution.compilation.prepare`); ``parts``: "engine" and/or "side"."""
    import importlib
    import numpy as np

    from ...motions.motion import record_motion
    from ..system import block
    from .batch import batch_options, run_batch
    from .model import ModelChoice, system_parameters
    from .simulate import simulate

    def _dispatcher(module, name):
        return getattr(importlib.import_module(module), name)
    g = 9.81
    system = block(1.5, 0.15)
    record = record_motion("warm-up", np.array([0.0, 0.3, -0.3, 0.0]) * g, 0.01)
    if "engine" in parts and command in warm_ups:            # e.g. the integrator inside the pulse-spectrum kernel
        _dispatcher(*warm_ups[command])()
    elif "engine" in parts and command in engine_commands:   # the batch drivers and the integrator they run
        simulate(system, record, t_end=0.05)                 # the serial driver (the job and the integrator)
        sp = system_parameters(system, ModelChoice("block", "exact"))
        run_batch(sp, [record, record], [1.0, 0.5], [0.05, 0.05], batch_options(), threads=True)
    if "side" in parts and command in ("check", "bench"):
        from .accuracy import accuracy_problem
        system_b1, pulse = accuracy_problem()
        simulate(system_b1, pulse, model="linear-exact", t_end=0.05)
    if "side" in parts and command in ("check", "records", "cylinder-check"):
        from ...motions.spectra import sd_max
        sd_max(record)
    if "side" in parts and command.startswith("cylinder"):
        _dispatcher(*cylinder_warm_up)(command, record)
