"""rockdesign: design checks for rocking and rolling-and-rocking structures (see README, docs/api.md).

The library API (imported on first use, so ``import rockdesign`` stays light)::

    import rockdesign as rd
    project = rd.load_project("podium.toml")       # or rd.parse_project(toml_text, name=...)
    q = rd.design_quantities(project)              # q.theta_c.value [rad], q["theta_c"].unit
    r = rd.simulate(project, "ricker-anti:ap=0.38g,Tp=0.95s")
    c = rd.check(project, progress=False)
    rd.write_report(c, "out/")
"""
import os

__version__ = "0.1.0"

# numba's OpenMP threads wait for work by sleeping, not spinning: on a shared machine a spinning thread
# burns the CPU time the analyses need (batches ran up to 2× slower; docs/engine.md, "Threads").  Read
# by GNU OpenMP when numba first starts its threads; a value the user set is kept.
os.environ.setdefault("OMP_WAIT_POLICY", "passive")

_EXPORTS = {
    "load_project": "rockdesign.library", "parse_project": "rockdesign.library",
    "design_quantities": "rockdesign.library", "simulate": "rockdesign.library", "check": "rockdesign.library",
    "write_report": "rockdesign.library", "Quantities": "rockdesign.library",
    "SimulationResponse": "rockdesign.library", "Project": "rockdesign.project",
    "CheckResult": "rockdesign.checks.check", "Quantity": "rockdesign.design.quantities",
    "RockdesignError": "rockdesign.errors", "ProjectError": "rockdesign.errors", "MotionError": "rockdesign.errors",
    "RecordError": "rockdesign.errors", "ModelError": "rockdesign.errors", "OutputError": "rockdesign.outdir",
}
__all__ = sorted(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        import importlib
        value = getattr(importlib.import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rockdesign' has no attribute '{name}'")


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))
