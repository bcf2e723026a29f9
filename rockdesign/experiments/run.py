"""The library functions of ``rockdesign calibrate | validate | ensemble`` (thesis Ch. 6–7; docs/experiments.md).

    import rockdesign as rd
    specimen = rd.load_project("specimen.toml")
    cal = rd.calibration(specimen, "free_vibration.csv")     # cal.p [1/s], cal.lam, cal.c_r (Eqs 2.8, 6.19)
    cal.write_figure("calibration.png")                       # measured vs simulated θ/α (Figs 6.12, 6.24)
    run = rd.ensemble(specimen, "ensemble/ensemble.toml", restitution=cal.c_r)   # one analysis per motion
    run.write_csv("analyses.csv")
    v = rd.validation("tests.csv", "analyses.csv", seed=1, out_dir="validation/")   # Ch. 7: Eq 7.1, Tables 7.2–7.3

The experiments calibrate and run a kind's specimen through its kind (``StructureKind.experiments``; the planar
kind's: a ``[column]`` or ``[podium]`` project); the validation compares any two result files.  Errors
name the parameter (``min_amplitude``, ``scale``, ``restitution``, ``suite``, ``seed``…) or the file and its key.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import ProjectError
from ..execution import compilation
from ..kinds import kind_of
from ..kinds.base import EnsembleResult, unavailable
from ..plots import save
from .figures import calibration_figure, validation_figure
from .free_vibration import ExperimentError, TiltHistory, read_tilt_csv
from .validate import MixedSample, Validation, read_results_csv, validate
from .validate_report import write_validation

__all__ = ["calibration", "validation", "ensemble", "CalibrationRun", "ValidationRun"]


def _experiments(project, function: str):
    """The experiments of ``project``'s kind (``StructureKind.experiments``: ``calibrate``,
    ``simulated_history``, ``run_ensemble``; the planar kind's calibrate and validate rocking specimens)."""
    if not hasattr(project, "system"):
        raise ProjectError(f"{function} needs a project", key="project",
                           expected="a Project (rd.load_project)", found=type(project).__name__)
    kind = kind_of(project)
    if kind.experiments is None:
        raise unavailable(f"{function} (thesis Ch. 6–7)", kind.name, "project")
    return kind.experiments


# --- calibrate ------------------------------------------------------------------------------------------
@dataclass
class CalibrationRun:
    """A free-vibration calibration of a specimen (thesis Sec 6.3.5, 6.4.3).

    Attributes:
        project: the specimen's project.
        history: the measured tilt history (``t`` [s], ``theta`` [rad], ``dropped_rows``: rows with missing values).
        calibration: the kind's calibration (planar: :class:`~rockdesign.planar.experiments.calibrate.Calibration`): ``p`` [1/s] (Eq 2.8 inverted),
            ``lam`` λ, ``c_r`` (Eq 6.19; ``c_r_left``, ``c_r_right``), ``c_r_theory``, ``half_cycles``, ``warnings``.
    """

    project: object
    history: TiltHistory
    calibration: object

    def __getattr__(self, name):
        if name in ("project", "history", "calibration"):
            raise AttributeError(name)
        return getattr(self.calibration, name)

    def as_json(self) -> dict:
        """The ``calibrate --json`` object (SI)."""
        return self.calibration.as_json()

    def simulated(self, *, say=None):
        """(t [s], θ [rad]) of the engine with the calibrated λ and c_r, released from the first measured peak
        (compiled on a first run, announced with ``say``)."""
        compilation.prepare("calibrate", kind_of(self.project).kernels("simulate"), say)
        return _experiments(self.project, "calibration").simulated_history(self.project.system, self.calibration,
                                                                           self.history)

    def write_figure(self, path, *, say=None) -> Path:
        """Measured θ/α over the simulated history (thesis Figs 6.12, 6.24; .png, .svg or .pdf)."""
        fig = calibration_figure(self.history, self.calibration, self.simulated(say=say),
                                 f"{self.project.name}: {Path(self.history.source).name}")
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        save(fig, path)
        return Path(path)


def calibration(project, free_vibration: str | Path | TiltHistory, *, half_cycles: int = 20,
                min_amplitude: float = 0.05) -> CalibrationRun:
    """Back-calculate p, λ and c_r (left/right) of ``project``'s specimen from a free-vibration test.

    Args:
        project: the specimen (a planar :class:`~rockdesign.project_tables.Project`: geometry and g).
        free_vibration: the measured tilt history: a CSV file with columns t [s] and theta [rad] (or theta_deg), or
            a :class:`~rockdesign.experiments.free_vibration.TiltHistory`.
        half_cycles: use at most this many half-cycles from the first impact (≥ 2; thesis ~15–20).
        min_amplitude: ignore half-cycles with θ0 below this fraction of α (0 ≤ value < 1).
    """
    experiments = _experiments(project, "calibration")
    if isinstance(half_cycles, bool) or not isinstance(half_cycles, int) or half_cycles < 2:
        raise ExperimentError("out of range", key="half_cycles", expected="an integer ≥ 2", found=repr(half_cycles))
    history = free_vibration if isinstance(free_vibration, TiltHistory) else read_tilt_csv(free_vibration)
    cal = experiments.calibrate(project.system, history, max_half_cycles=half_cycles, min_amplitude=min_amplitude)
    return CalibrationRun(project, history, cal)


# --- validate -------------------------------------------------------------------------------------------
@dataclass
class ValidationRun:
    """The Ch. 7 comparison of test and model statistics of θ_max/α.

    Attributes:
        validation: the :class:`~rockdesign.experiments.validate.Validation` (``as_json()``: percentiles, the
            tests of Table 7.3, Kolmogorov distances, DKW bands).
        files: the CSV files compared (``tests``, ``analyses``, ``analyses_measured_cr``).
        title: what the figure and the report call the comparison.
        written: the files written into ``out_dir`` (``json``, ``figure``, ``html``, ``pdf``), if any.
    """

    validation: Validation
    files: dict
    title: str
    written: dict = field(default_factory=dict)

    def as_json(self) -> dict:
        """The ``validate --json`` object (validation.json)."""
        return self.validation.as_json()

    def write_figure(self, path) -> Path:
        """Mixed empirical CDFs with the tests' DKW bands (thesis Figs 7.1, 7.2; .png, .svg or .pdf)."""
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        save(validation_figure(self.validation, self.title), path)
        return Path(path)


def _sample(value, name: str) -> tuple[MixedSample, str, str]:
    """(sample, file, short name) of a results CSV path or a sample."""
    if isinstance(value, MixedSample):
        return value, value.file or None, Path(value.file).name if value.file else value.name
    return read_results_csv(value, name), str(value), Path(value).name


def validation(tests, analyses, *, measured=None, seed: int = 1, out_dir: str | Path | None = None,
               pdf: bool = True) -> ValidationRun:
    """Compare test and model statistics of θ_max/α (thesis Ch. 7: Eq 7.1, Tables 7.2, 7.3).

    Args:
        tests: the test results (a CSV with ``theta_max_over_alpha``, ``overturned``, ``id``; or a
            :class:`~rockdesign.experiments.validate.MixedSample`).
        analyses: the model results with the theoretical c_r (the CSV of :func:`ensemble`, or a check's results.csv).
        measured: the model results with the measured c_r (optional).
        seed: the seed of the random D1/D2 split of the tests (an integer ≥ 0).
        out_dir: a folder for validation.json, the figure (PNG, SVG) and report.html (and report.pdf with ``pdf``).
    """
    test_sample, test_file, test_name = _sample(tests, "tests")
    model_sample, model_file, model_name = _sample(analyses, "analyses")
    measured_sample, measured_file = (None, None) if measured is None else _sample(measured, "analyses_measured_cr")[:2]
    result = validate(test_sample, model_sample, measured_sample, seed=seed)
    run = ValidationRun(result, {"tests": test_file, "analyses": model_file, "analyses_measured_cr": measured_file},
                        f"{test_name} vs {model_name}")
    if out_dir is not None:
        run.written = write_validation(result, out_dir, run.files, title=run.title, pdf=pdf)
    return run


# --- ensemble -------------------------------------------------------------------------------------------
def ensemble(project, suite: str | Path, *, scale: float = 1.0, restitution: float | None = None, records_dir=None,
             progress: Callable[[str, int, int], None] | None = None, say=None) -> EnsembleResult:
    """Run ``project`` over a ground-motion ensemble (a suite name or manifest, e.g. the ensemble.toml of
    :func:`rockdesign.records_library.records_synth`): one analysis per motion × ``scale`` with the project's model.

    Args:
        project: a planar :class:`~rockdesign.project_tables.Project`.
        suite: the ensemble; every record must be available (``records_dir``: a folder of PEER AT2 files).
        scale: a factor on every motion (finite, > 0).
        restitution: c_r to use instead of the project's (0 < c_r ≤ 1; e.g. :func:`calibration`'s).
        progress: ``progress(stage, done, total)`` as the analyses finish.
        say: announces a first-run compilation.

    Returns:
        The kind's ensemble run (planar: :class:`~rockdesign.planar.experiments.ensemble.EnsembleRun`): ``rows()`` (θ_max/α, overturned, impacts, u_B_max
        [m] per motion), ``as_json()`` (``ensemble --json``), ``write_csv(path)`` (the analyses.csv ``validation``
        reads).
    """
    experiments = _experiments(project, "ensemble")
    stage = "ensemble analyses"
    return experiments.run_ensemble(project, str(suite), scale=scale, restitution=restitution,
                        records_dir=str(records_dir) if records_dir else None,
                        before_analyses=lambda: compilation.prepare("ensemble", kind_of(project).kernels("simulate"), say),
                        progress=(lambda done, total: progress(stage, done, total)) if progress else None)
