"""The import graph of a package and its check against an ordered table of layers (docs/architecture.md).

Every ``import`` and ``from … import`` is read with :mod:`ast` — at module level and inside
functions, absolute and relative — so a lazy import cannot hide an upward dependency.
"""
from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "rockdesign"

SHARED_LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("base", ("rockdesign", "rockdesign.errors", "rockdesign.units", "rockdesign.paths", "rockdesign.kernel_cache",
              "rockdesign.jsonable", "rockdesign.mplfig", "rockdesign.plots", "rockdesign.progress",
              "rockdesign.console", "rockdesign.outdir", "rockdesign.display", "rockdesign.execution",
              "rockdesign.quantity", "rockdesign.project_tables", "rockdesign.dop853_tableau")),
    ("design", ()),
    ("motions", ("rockdesign.motions",)),
    ("project", ()),
    ("dynamics", ()),
    ("analyses", ("rockdesign.acceptance",)),
    ("report", ("rockdesign.report",)),
    ("experiments", ("rockdesign.experiments",)),
    ("library", ("rockdesign.library", "rockdesign.records_library", "rockdesign.kinds", "rockdesign.design_space",
                 "rockdesign.experiments.run")),
    ("bench", ("rockdesign.bench",)),
    ("cli", ("rockdesign.cli", "rockdesign.templates")),
)
"""The shared modules (prefixes) of each layer, lowest first."""

KIND_PARTS: dict[str, tuple[str, ...]] = {
    "design": ("design", "system", "validity", "quantities"),
    "motions": ("pairs",),
    "project": ("project",),
    "dynamics": ("", "dynamics", "warm_up"),
    "analyses": ("checks", "check", "criteria", "margins", "ensemble", "spectra"),
    "report": ("report", "figures", "methods"),
    "experiments": ("experiments",),
    "library": ("kind", "simulation", "grid", "grid_draws"),
}
"""Where the parts of a kind's package go, by their name in the package (a module or a subpackage): a kind's
``project.py`` is in *project*, its ``checks/`` or ``check.py`` in *analyses*, its ``kind.py`` in *library*; any
other part (``""``: the package itself — its engine, kernels, stepper) in *dynamics*."""


def kind_packages() -> tuple[str, ...]:
    """The packages of the built-in kinds of structure, from the registry (``rockdesign.kinds.BUILT_IN``:
    ``"rockdesign.cylinder.kind:Cylinder"`` → ``rockdesign.cylinder``)."""
    from rockdesign.kinds import BUILT_IN
    return tuple(spec.partition(":")[0].rpartition(".")[0] for spec in BUILT_IN)


def _kind_layers(package_dir: Path = PACKAGE) -> dict[str, tuple[str, ...]]:
    """layer → the prefixes of the built-in kinds' parts that exist (``rockdesign.planar.project``, …)."""
    out = {}
    for layer, parts in KIND_PARTS.items():
        prefixes = []
        for kind in kind_packages():
            base = package_dir.parent.joinpath(*kind.split("."))
            for part in parts:
                if not part or (base / f"{part}.py").is_file() or (base / part / "__init__.py").is_file():
                    prefixes.append(f"{kind}.{part}" if part else kind)
        out[layer] = tuple(prefixes)
    return out


def _layers() -> tuple[tuple[str, tuple[str, ...]], ...]:
    kinds = _kind_layers()
    return tuple((layer, prefixes + kinds.get(layer, ())) for layer, prefixes in SHARED_LAYERS)


LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = _layers()
"""Layers, lowest first, and the modules (prefixes) in each: a module may import only from its own
layer or a lower one.  The shared modules are listed in :data:`SHARED_LAYERS`; the kinds' modules are placed by
their package (:data:`KIND_PARTS`, for every kind of the registry), so adding a kind edits no table here.  The most
specific prefix wins (``rockdesign.cylinder.project`` is in *project* although ``rockdesign.cylinder`` is in
*dynamics*); ``rockdesign.cli`` covers every module of the command-line package.  ``rockdesign`` itself (the
package's ``__init__``) imports only ``rockdesign.kernel_cache`` at import time (numba's cache folder is set before
any kernel is defined): its lazy ``__getattr__`` names the library modules as strings, which this check does not
read."""


def module_files(package_dir: Path) -> dict[str, Path]:
    """Dotted module name → file, for every ``.py`` file below ``package_dir`` (a package folder)."""
    out = {}
    for path in sorted(package_dir.rglob("*.py")):
        parts = list(path.relative_to(package_dir.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def imports_of(module: str, path: Path, known: dict[str, Path]) -> list[tuple[str, int]]:
    """(imported module, line) for every import of ``module`` that names a module in ``known``."""
    root = module.split(".")[0]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []

    def add(name: str, line: int) -> None:
        while name and name not in known:
            name = name.rpartition(".")[0]
        if name and name != module:
            found.append((name, line))

    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == root:
                    add(alias.name, node.lineno)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != root:
                continue
            for alias in node.names:       # `from pkg import module` imports the module
                sub = f"{target}.{alias.name}"
                add(sub if sub in known else target, node.lineno)
    return found


def layer_of(module: str, layers=LAYERS) -> int | None:
    """Index of the layer of ``module`` (most specific prefix), None when the table does not place it."""
    best, best_len = None, -1
    for index, (_, prefixes) in enumerate(layers):
        for prefix in prefixes:
            matches = (module == prefix or module.startswith(prefix + ".")
                       or (prefix.endswith("_") and module.startswith(prefix)))
            if matches and len(prefix) > best_len:
                best, best_len = index, len(prefix)
    return best


def graph(package_dir: Path) -> tuple[dict[str, Path], dict[str, list[tuple[str, int]]]]:
    known = module_files(package_dir)
    return known, {m: imports_of(m, p, known) for m, p in known.items()}


def upward_imports(package_dir: Path, layers=LAYERS) -> list[str]:
    """``file:line: a (layer) imports b (higher layer)`` for every import against the layer order."""
    known, edges = graph(package_dir)
    out = []
    for module, targets in edges.items():
        lo = layer_of(module, layers)
        for target, line in targets:
            hi = layer_of(target, layers)
            if lo is not None and hi is not None and hi > lo:
                out.append(f"{known[module].name}:{line}: {module} ({layers[lo][0]}) imports {target} "
                           f"({layers[hi][0]})")
    return sorted(out)


def unplaced(package_dir: Path, layers=LAYERS) -> list[str]:
    return sorted(m for m in module_files(package_dir) if layer_of(m, layers) is None)


def cycles(package_dir: Path) -> list[list[str]]:
    """Import cycles between modules (strongly connected components of more than one module, or a
    module importing itself through a chain), each sorted."""
    _, edges = graph(package_dir)
    adj = {m: sorted({t for t, _ in ts}) for m, ts in edges.items()}
    index, low, stack, on_stack, comps, counter = {}, {}, [], set(), [], [0]

    def visit(v):                      # Tarjan, iterative over an explicit stack of iterators
        work = [(v, iter(adj.get(v, ())))]
        index[v] = low[v] = counter[0]; counter[0] += 1; stack.append(v); on_stack.add(v)
        while work:
            node, it = work[-1]
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]; counter[0] += 1; stack.append(w); on_stack.add(w)
                    work.append((w, iter(adj.get(w, ()))))
                    break
                if w in on_stack:
                    low[node] = min(low[node], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    comp = []
                    while True:
                        w = stack.pop(); on_stack.discard(w); comp.append(w)
                        if w == node:
                            break
                    if len(comp) > 1:
                        comps.append(sorted(comp))

    for v in sorted(adj):
        if v not in index:
            visit(v)
    return sorted(comps)
