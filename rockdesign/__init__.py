"""rockdesign: design checks for rocking and rolling-and-rocking structures (see README, docs/api.md).

The library API (imported on first use, so ``import rockdesign`` stays light)::

    import rockdesign as rd
    project = rd.load_project("podium.toml")       # or rd.parse_project(toml_text, name=...)
    q = rd.design_quantities(project)              # q.theta_c.value [rad], q["theta_c"].unit
    r = rd.simulate(project, "ricker-anti:ap=0.38g,Tp=0.95s")
    c = rd.check(project, progress=False)
    rd.write_report(c, "out/")
    s = rd.spectrum(project, pulse="sine", out_dir="spectrum/")
    chart = rd.design(project, ["podium.width=0.36m:0.60m:7"], out_dir="design/")
"""
__version__ = "0.1.0"

# numba caches rockdesign's kernels in a folder of the user's cache named by the digest of their sources, never
# in the package, and only rockdesign's: a finder executes each module that defines kernels with numba's cache
# folder set, restoring it after (rockdesign.kernel_cache).  os.environ is not changed; nothing is imported.
from .kernel_cache import use_kernel_cache  # noqa: E402

use_kernel_cache()

_EXPORTS = {
    # the library: every kind of structure through one front door (rockdesign.library, rockdesign.kinds)
    "load_project": "rockdesign.library", "parse_project": "rockdesign.library",
    "design_quantities": "rockdesign.library", "simulate": "rockdesign.library", "check": "rockdesign.library",
    "write_report": "rockdesign.library", "spectrum": "rockdesign.library", "Quantities": "rockdesign.library",
    "SimulationResponse": "rockdesign.planar.simulation:SimulationResult",
    "CylinderSimulation": "rockdesign.cylinder.simulation",
    "Project": "rockdesign.project_tables",
    "CheckResult": "rockdesign.planar.checks.check", "Quantity": "rockdesign.quantity",
    "RockdesignError": "rockdesign.errors", "ProjectError": "rockdesign.errors", "MotionError": "rockdesign.errors",
    "RecordError": "rockdesign.errors", "ModelError": "rockdesign.errors", "OutputError": "rockdesign.outdir",
    # ground-motion records (``rockdesign records``)
    "records_list": "rockdesign.records_library", "records_show": "rockdesign.records_library",
    "records_spectrum": "rockdesign.records_library", "records_synth": "rockdesign.records_library",
    "records_scale_model": "rockdesign.records_library", "load_record": "rockdesign.motions.library",
    "DEFAULT_BAND": "rockdesign.motions.defaults", "DEFAULT_DAMPING": "rockdesign.motions.defaults",
    "DEFAULT_N_PERIODS": "rockdesign.motions.defaults",
    # experiments (``rockdesign calibrate | validate | ensemble``)
    "calibration": "rockdesign.experiments.run", "validation": "rockdesign.experiments.run",
    "ensemble": "rockdesign.experiments.run",
    # benchmarks (``rockdesign bench``; never loaded by a check)
    "benchmark": "rockdesign.bench.run",
    # design charts (``rockdesign design``)
    "design": "rockdesign.design_space.run", "plan_design": "rockdesign.design_space.run",
    "prepare_design": "rockdesign.design_space.run",
    "run_design": "rockdesign.design_space.run", "write_design": "rockdesign.design_space.run",
    "design_folder": "rockdesign.design_space.run", "recommended_check": "rockdesign.design_space.run",
    "DesignResult": "rockdesign.design_space.run", "DesignPlan": "rockdesign.design_space.run",
    "FULL_CHECK": "rockdesign.design_space.run", "SLOW_ANALYSIS": "rockdesign.design_space.run",
    "design_hint": "rockdesign.design_space.hint", "report_citation": "rockdesign.report.methods:cite",
    # running long work: progress on stderr or in a notebook, executors (a dask cluster)
    "progress_bars": "rockdesign.progress", "working": "rockdesign.progress",
    "make_executor": "rockdesign.execution.executor",
    # the options each kind's rocking spectrum offers on the command line (``rockdesign spectrum``)
    "spectrum_cli_options": "rockdesign.kinds",
    # output folders (a folder a failed command created is removed again)
    "refuse_wrong_type": "rockdesign.outdir", "discard_unfinished": "rockdesign.outdir",
    "forget_created": "rockdesign.outdir",
}
"""The public names: ``name → "module"`` (the attribute of the same name) or ``"module:attribute"``.
Imported on first use, so ``import rockdesign`` stays light; the command line imports nothing else
from the package (tests/architecture/test_front_door.py)."""

_COMPATIBLE = {
    "list_records": "rockdesign.motions.suites", "motion_measures": "rockdesign.motions.measures",
    "plausibility_warnings": "rockdesign.motions.measures", "sd_max": "rockdesign.motions.spectra",
    "motion_spectrum": "rockdesign.motions.spectra", "period_grid": "rockdesign.motions.spectra",
    "synthesize": "rockdesign.motions.synth", "SCALE_CHOICES": "rockdesign.motions.synth",
    "record_history_figure": "rockdesign.motions.figures", "record_spectrum_figure": "rockdesign.motions.figures",
    "parse_pair": "rockdesign.cylinder.pairs", "parse_quantity": "rockdesign.units",
    "QuantityParseError": "rockdesign.units", "save_figure": "rockdesign.plots:save",
    "created_folder": "rockdesign.outdir", "json_ready": "rockdesign.jsonable",
    "check_dask_address": "rockdesign.execution.executor:check_address",
    "parse_axis": "rockdesign.planar.spectra.axes", "spectrum_scales": "rockdesign.planar.spectra.axes",
    "compute_spectrum": "rockdesign.planar.spectra.spectrum", "request_from_project": "rockdesign.planar.spectra.spectrum",
    "SpectrumError": "rockdesign.planar.spectra.spectrum", "analyse_spectrum": "rockdesign.planar.spectra.output:analyse",
    "write_spectrum_outputs": "rockdesign.planar.spectra.output:write_outputs",
    "spectrum_warm_up": "rockdesign.planar.spectra.kernel:warm_up", "resolve_structure": "rockdesign.planar.dynamics.model",
    "remove_tree": "rockdesign.execution.executor",
    "cylinder_spectrum": "rockdesign.cylinder.spectrum", "parse_cylinder_axis": "rockdesign.cylinder.spectrum",
    "CylinderSpectrumError": "rockdesign.cylinder.spectrum",
    "check_grid": "rockdesign.planar.spectra.spectrum", "check_ordinates": "rockdesign.planar.spectra.spectrum",
    "write_cylinder_spectrum": "rockdesign.cylinder.spectrum_output",
    "calibrate": "rockdesign.planar.experiments.calibrate", "simulated_history": "rockdesign.planar.experiments.calibrate",
    "read_tilt_csv": "rockdesign.experiments.free_vibration", "validate": "rockdesign.experiments.validate",
    "read_results_csv": "rockdesign.experiments.validate",
    "write_validation": "rockdesign.experiments.validate_report",
    "run_ensemble": "rockdesign.planar.experiments.ensemble", "write_analyses_csv": "rockdesign.planar.experiments.ensemble",
    "parse_limits": "rockdesign.experiments.scale_model", "scale_record": "rockdesign.experiments.scale_model",
    "write_at2": "rockdesign.experiments.scale_model",
    "scale_model_figure": "rockdesign.experiments.figures", "calibration_figure": "rockdesign.experiments.figures",
    "validation_figure": "rockdesign.experiments.figures",
    "problem_set": "rockdesign.bench.problems", "run_study": "rockdesign.bench.runner",
    "highlights": "rockdesign.bench.runner", "speed_summary": "rockdesign.bench.speed",
    "speed_format_value": "rockdesign.bench.speed:format_value",
    "write_study_figures": "rockdesign.bench.figures", "run_stability": "rockdesign.bench.stability",
    "stability_markdown": "rockdesign.bench.stability", "write_stability_figures": "rockdesign.bench.stability",
    "publish_docs": "rockdesign.bench.publish",
}
"""Names earlier versions exported: the tools below the commands' functions (``rd.compute_spectrum``,
``rd.calibrate``, ``rd.run_study``…).  They still import from ``rockdesign`` (CONTRACT: extend, never break) but
are not in ``__all__`` and the command line uses none of them (tests/architecture/test_front_door.py)."""
__all__ = sorted(_EXPORTS)


def __getattr__(name):
    where = _EXPORTS.get(name) or _COMPATIBLE.get(name)
    if where is not None:
        import importlib
        module, _, attribute = where.partition(":")
        value = getattr(importlib.import_module(module), attribute or name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rockdesign' has no attribute '{name}'")


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS) | set(_COMPATIBLE))
