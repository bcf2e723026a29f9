"""One front door per kind of structure (docs/architecture.md): the registry is the only place that
branches on the kind of a structure, the command line imports only the public library, no module is
over 500 lines, and no two packages import each other."""
from __future__ import annotations

import ast
from pathlib import Path

from layers import graph

PACKAGE = Path(__file__).resolve().parents[2] / "rockdesign"

REGISTRY = "rockdesign.kinds"
"""The registry of kinds of structure (and the kinds' entries): the one package allowed to branch on a kind."""

MAX_LINES = 500

TO_BE_SPLIT: set[str] = set()
"""Modules over 500 lines that are to be split: the integrator removes each entry as it is split."""

CLI_MAY_IMPORT = ("rockdesign", "rockdesign.library", "rockdesign.errors", "rockdesign.console", "rockdesign.display",
                  "rockdesign.cli", "rockdesign.templates")
"""What a command-line module may import from rockdesign: the package (its version), the public library,
the errors, the console factory and formatting, its siblings and the project templates."""


def _kind_words() -> set[str]:
    """The names the registry gives its kinds of structure, and the system kinds of every kind but the
    default one (planar, which claims any document): comparing with these outside the registry is a side door."""
    from rockdesign.kinds import registered
    kinds = registered()
    words = {k.name for k in kinds}
    for k in kinds[:-1]:
        words |= set(k.systems)
    return words


def _own_modules(module: str, words: set[str]) -> bool:
    """A kind's own modules (``rockdesign.cylinder.*``, ``checks/cylinder_check``...) read their own input."""
    return module.startswith(REGISTRY) or any(w in part for part in module.split(".")[1:] for w in words)


def kind_branches(package_dir: Path = PACKAGE) -> list[str]:
    """``file:line`` of every comparison with a kind's name (``x.system.kind == "cylinder"``,
    ``"cylinder" in raw``) and every ``isinstance(x, Cylinder…)`` outside the registry and the kind's own modules."""
    words = _kind_words()
    known, _ = graph(package_dir)
    found = []
    for module, path in known.items():
        if _own_modules(module, words):
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Compare):
                operands = [node.left, *node.comparators]
                if any(isinstance(o, ast.Constant) and o.value in words for o in operands):
                    found.append(f"{path.relative_to(package_dir.parent)}:{node.lineno}")
            elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "isinstance"
                  and len(node.args) == 2 and any(w.capitalize() in ast.unparse(node.args[1]) for w in words)):
                found.append(f"{path.relative_to(package_dir.parent)}:{node.lineno}")
    return sorted(found)


def test_no_kind_branch_outside_the_registry():
    found = kind_branches()
    assert not found, ("branches on the kind of a structure outside rockdesign/kinds (add a method to "
                       "StructureKind instead):\n" + "\n".join(found))


def test_the_checker_sees_a_side_door(tmp_path):
    pkg = tmp_path / "rockdesign"
    (pkg / "checks").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "checks" / "__init__.py").write_text("")
    (pkg / "checks" / "check.py").write_text(
        "def f(project):\n    if project.system.kind == 'cylinder':\n        return 1\n"
        "def g(result, CylinderCheckResult):\n    return isinstance(result, CylinderCheckResult)\n")
    assert kind_branches(pkg) == ["rockdesign/checks/check.py:2", "rockdesign/checks/check.py:5"]


def _cli_imports(package_dir: Path = PACKAGE) -> list[str]:
    known, edges = graph(package_dir)
    bad = []
    for module, targets in edges.items():
        if not module.startswith("rockdesign.cli"):
            continue
        for target, line in targets:
            if not any(target == ok or (ok != "rockdesign" and target.startswith(ok + ".")) for ok in CLI_MAY_IMPORT):
                bad.append(f"{known[module].relative_to(package_dir.parent)}:{line}: {target}")
    return sorted(bad)


def test_the_command_line_imports_only_the_public_library():
    bad = _cli_imports()
    assert not bad, ("a command imports below the library (move what it computes into rockdesign.library):\n"
                     + "\n".join(bad))


def test_no_module_over_500_lines():
    long = {str(p.relative_to(PACKAGE.parent)): n for p in PACKAGE.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_LINES}
    assert set(long) <= TO_BE_SPLIT, f"modules over {MAX_LINES} lines: " + ", ".join(
        f"{p} ({n})" for p, n in sorted(long.items()) if p not in TO_BE_SPLIT)
    split = sorted(TO_BE_SPLIT - set(long))
    assert not split, f"split already (remove from TO_BE_SPLIT): {', '.join(split)}"


KIND_PACKAGES = ("rockdesign.planar", "rockdesign.cylinder")
"""The packages of the built-in kinds of structure: each spans the layers (its system, project parser, engine,
check, report and entry), so its own parts are the nodes of the package graph."""


def package_of(module: str, package_dir: Path = PACKAGE) -> str:
    """The package a module belongs to (``rockdesign.motions.spectra`` → ``rockdesign.motions``); a top-level
    module is its own node, and so is each part of a kind's package (``rockdesign.planar.dynamics``,
    ``rockdesign.cylinder.check``)."""
    parts = module.split(".")
    depth = 3 if ".".join(parts[:2]) in KIND_PACKAGES else 2
    if len(parts) >= depth and (package_dir.joinpath(*parts[1:depth])).is_dir():
        return ".".join(parts[:depth])
    return ".".join(parts[:depth]) if len(parts) >= depth else module


def package_cycles(package_dir: Path = PACKAGE) -> list[tuple[str, str]]:
    """(a, b) for every import from package a into package b while b reaches a back."""
    _, edges = graph(package_dir)
    adj: dict[str, set[str]] = {}
    for module, targets in edges.items():
        for target, _ in targets:
            a, b = package_of(module, package_dir), package_of(target, package_dir)
            if a != b:
                adj.setdefault(a, set()).add(b)

    def reach(start):
        seen, stack = set(), [start]
        while stack:
            for nxt in adj.get(stack.pop(), ()):
                if nxt not in seen:
                    seen.add(nxt)
                    stack.append(nxt)
        return seen

    return sorted((a, b) for a in adj for b in adj[a] if a in reach(b))


def test_no_import_cycle_between_packages():
    found = package_cycles()
    assert not found, "packages importing each other: " + "; ".join(f"{a} → {b}" for a, b in found)


SHARED_EXCEPTIONS: dict[str, tuple[str, ...]] = {
    "rockdesign.kinds": KIND_PACKAGES,                       # the registry names the built-in kinds
    "rockdesign.bench": KIND_PACKAGES,                       # measures the kinds' engines
}
"""Modules outside the kinds' packages allowed to import from a kind's package, and what."""
KIND_USES: dict[str, tuple[str, ...]] = {
    "rockdesign.cylinder": ("rockdesign.planar.dynamics.simulate", "rockdesign.planar.system",
                            "rockdesign.planar.dynamics.warm_up"),
}
"""What a kind may import from another kind: the cylinder's check compares with the planar rocking body of
the same p and α along each component (thesis Ch. 5), through the planar engine's public simulate (whose
kernels its first run compiles with the planar engine's warm-up)."""


def kind_imports(package_dir: Path = PACKAGE) -> list[str]:
    """``file:line: a imports b`` for every import of a kind's package from outside it that the tables above
    do not allow."""
    known, edges = graph(package_dir)
    bad = []
    for module, targets in edges.items():
        own = next((k for k in KIND_PACKAGES if module == k or module.startswith(k + ".")), None)
        for target, line in targets:
            kind = next((k for k in KIND_PACKAGES if target == k or target.startswith(k + ".")), None)
            if kind is None or kind == own:
                continue
            table = KIND_USES if own else SHARED_EXCEPTIONS
            allowed = [a for prefix, names in table.items() if module == prefix or module.startswith(prefix + ".")
                       for a in names]
            if not any(target == a or target.startswith(a + ".") for a in allowed):
                bad.append(f"{known[module].relative_to(package_dir.parent)}:{line}: {module} imports {target}")
    return sorted(set(bad))


def test_no_shared_module_imports_a_kind():
    bad = kind_imports()
    assert not bad, ("a module outside a kind's package imports it (move the code into the kind, or give "
                     "StructureKind a hook):\n" + "\n".join(bad))


def test_the_kinds_contract_is_small_and_has_no_speed_machinery():
    """A kind writes at most 8 methods (the rest have defaults in StructureKind), and no method of the contract
    takes a PDF, worker or thread parameter: how the report becomes a PDF and how analyses are spread over
    cores are the shared layers' business (issue: speed behind one seam)."""
    import inspect

    from rockdesign.kinds.base import StructureKind
    abstract = sorted(StructureKind.__abstractmethods__)
    assert len(abstract) <= 8, abstract
    for name, member in inspect.getmembers(StructureKind, inspect.isfunction):
        params = set(inspect.signature(member).parameters)
        assert not {p for p in params if "pdf" in p or "worker" in p or "thread" in p}, (name, params)
