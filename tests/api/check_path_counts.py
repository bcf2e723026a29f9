"""Counting the work of ``rockdesign check`` from ``cli/`` to the written report (issue 48): every function below
is wrapped wherever a module of rockdesign holds it (imported by name or called through its module), so a call
from any layer is counted."""
from __future__ import annotations

import importlib
import sys
from collections import Counter

MODULES = ("rockdesign.library", "rockdesign.kinds", "rockdesign.cli.check", "rockdesign.design_space.hint",
           "rockdesign.planar.kind", "rockdesign.planar.checks.check", "rockdesign.planar.report.report",
           "rockdesign.planar.report.figures", "rockdesign.planar.report.context", "rockdesign.planar.report.drawing",
           "rockdesign.cylinder.kind", "rockdesign.cylinder.check", "rockdesign.cylinder.report",
           "rockdesign.cylinder.figures", "rockdesign.report.document", "rockdesign.report.results",
           "rockdesign.motions.config")
"""Imported before the wrapping, so that a name a module imports at its top is wrapped there too."""


def _functions():
    """name → the function counted (the original, as its module defines it)."""
    from rockdesign import kinds
    from rockdesign.cylinder import check as cylinder_check
    from rockdesign.cylinder import quantities as cylinder_quantities
    from rockdesign.motions import config
    from rockdesign.planar.design import quantities as planar_quantities
    return {
        "registry": kinds.registered,                       # the registry consulted (kind_of, kind_of_document)
        "kind_of": kinds.kind_of,
        "kind_of_document": kinds.kind_of_document,
        "records": config.resolve_motions,                  # a planar excitation's records read and scaled
        "record_pairs": cylinder_check.suite_pairs,         # a cylinder suite's pairs read
        "quantities": planar_quantities.design_quantities,
        "cylinder_quantities": cylinder_quantities.cylinder_quantities,
    }


def _result_classes():
    from rockdesign.cylinder.check import CylinderCheckResult
    from rockdesign.planar.checks.check import CheckResult
    return (CheckResult, CylinderCheckResult)


def count_check_path(monkeypatch) -> Counter:
    """Wrap the counted functions (and each kind's ``as_json``) for the rest of the test; returns the counts."""
    for name in MODULES:
        importlib.import_module(name)
    counts: Counter = Counter()

    def wrap(name, original):
        def counted(*args, **kwargs):
            counts[name] += 1
            return original(*args, **kwargs)
        return counted

    for name, original in _functions().items():
        wrapper = wrap(name, original)
        for module in [m for n, m in list(sys.modules.items()) if n.startswith("rockdesign") and m is not None]:
            for attr, value in list(vars(module).items()):
                if value is original:
                    monkeypatch.setattr(module, attr, wrapper)
    for cls in _result_classes():
        original = cls.__dict__.get("as_json") or cls.as_json
        monkeypatch.setattr(cls, "as_json", wrap("as_json", original))
        serialise = cls.__dict__.get("serialise")
        if serialise is not None:            # results.json built (as_json may return the dict built before)
            monkeypatch.setattr(cls, "serialise", wrap("serialise", serialise))
    return counts


def first_run(monkeypatch) -> None:
    """As on a first run: every group of kernels missing (prepare_check reads what it reads before compiling),
    the compilation itself skipped (the kernels are compiled in the test session anyway)."""
    from rockdesign.execution import compilation
    monkeypatch.setattr(compilation, "missing", lambda kernels: list(kernels))
    monkeypatch.setattr(compilation, "prepare", lambda command, kernels, say=None: 0.0)
