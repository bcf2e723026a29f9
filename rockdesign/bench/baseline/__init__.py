"""Independent scipy reference implementation of the rocking dynamics (SPEC §3).

``simulate_scipy`` integrates the generic Lagrangian equation of SPEC §3.1 (or the linearized
equations of §3.2) with ``scipy.integrate.solve_ivp``, restarted at every event.  It shares no code
with :mod:`rockdesign.planar.dynamics` on purpose: it is the accuracy cross-check of the numba engine and
the scipy baseline of the benchmarks.
"""
from .equations import accelerations_exact, accelerations_linear, cap_beam_kinematics
from .parameters import ModelParameters, model_parameters, restitution_coefficient, uplift_thresholds
from .scipy_engine import Event, ReferenceResult, simulate_scipy

__all__ = ["simulate_scipy", "ReferenceResult", "Event", "ModelParameters", "model_parameters",
           "restitution_coefficient", "uplift_thresholds", "cap_beam_kinematics",
           "accelerations_exact", "accelerations_linear"]
