"""The experiments of the planar kind (thesis Ch. 6–7): free-vibration calibration of a rocking specimen,
free-rocking histories made by the model, and the model run over a ground-motion ensemble.  The library's
``rd.calibration`` and ``rd.ensemble`` reach them through the kind (``StructureKind.experiments``)."""
from .calibrate import Calibration, calibrate, simulated_history  # noqa: F401
from .ensemble import EnsembleRun, run_ensemble  # noqa: F401
