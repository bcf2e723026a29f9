"""One front door per kind of structure (docs/architecture.md): the registry is the only place that
branches on the kind of a structure, no module outside a kind's package names the kind's words (as a value or an
identifier), the command line imports only the public library, no module is over 500 lines, and no two packages
import each other.  The kinds and their packages come from the registry: adding a kind edits no table here."""
from __future__ import annotations

import ast
import re
from pathlib import Path

from layers import graph, kind_packages

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


def built_in_kinds():
    """The built-in kinds of structure (``rockdesign.kinds.BUILT_IN``), instantiated: the words and packages below
    are theirs, whatever kinds a test has registered besides."""
    from rockdesign.kinds import BUILT_IN, _instance
    return tuple(_instance(spec) for spec in BUILT_IN)


def _kind_words() -> set[str]:
    """The words that belong to a kind: the names the registry gives its kinds of structure and their systems'
    kinds ("planar", "cylinder", "column", "podium")."""
    words = set()
    for k in built_in_kinds():
        words |= {k.name, *k.systems}
    return words


NOT_A_KIND = ("rockdesign", "rockdesign.bench")
"""Modules outside the kinds' packages that name the kinds by design: the package's table of public names
(``rockdesign/__init__.py``: each kind's functions kept for earlier versions) and the tool ``bench/``, which
measures the kinds' engines (it imports them: :data:`SHARED_EXCEPTIONS`)."""


def _own_modules(module: str) -> bool:
    """A kind's own modules (its package), the registry (``rockdesign.kinds``) and :data:`NOT_A_KIND`."""
    return (any(module == p or module.startswith(p + ".") for p in (*kind_packages(), REGISTRY))
            or module in NOT_A_KIND or module.startswith("rockdesign.bench."))


def kind_branches(package_dir: Path = PACKAGE) -> list[str]:
    """``file:line`` of every comparison with a kind's name (``x.system.kind == "cylinder"``,
    ``"cylinder" in raw``) and every ``isinstance(x, Cylinder…)`` outside the registry and the kind's own modules."""
    words = _kind_words()
    known, _ = graph(package_dir)
    found = []
    for module, path in known.items():
        if _own_modules(module):
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


SHARED_WORDS = frozenset({"column"})
"""Words of a kind that are also words of the shared code's own: a table's column (``Table.add_column``,
``np.column_stack``, a CSV column).  Identifiers may hold them; string constants may not be them."""

STILL_TO_MOVE: dict[str, str] = {}
"""Shared modules that still name a kind's word, each with what it names: the integrator removes each entry as its
module is made neutral (like TO_BE_SPLIT)."""

_TOKEN = re.compile(r"[A-Za-z0-9]+(?:[-_][A-Za-z0-9]+)*")


def _parts(text: str) -> set[str]:
    return {p.lower() for p in re.split(r"[-_]", text) if p}


def _docstrings(tree: ast.AST) -> set[int]:
    """ids of the docstrings of a module, class or function and of the strings that document an attribute."""
    return {id(node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str)}


def _identifiers(node: ast.AST):
    if isinstance(node, ast.Name):
        yield node.id
    elif isinstance(node, ast.Attribute):
        yield node.attr
    elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        yield node.name
    elif isinstance(node, ast.arg):
        yield node.arg
    elif isinstance(node, ast.keyword) and node.arg:
        yield node.arg
    elif isinstance(node, ast.alias):
        yield from (node.asname or node.name).split(".")


def kind_names(package_dir: Path = PACKAGE) -> list[str]:
    """``file:line: what`` for every name or string constant of a kind outside the kinds' packages (the rule of
    docs/architecture.md "One front door per kind of structure"): a string constant that is a single token (letters
    and digits joined by ``-`` or ``_``: a value, a key, a column) and has a kind's word as a part ("podium",
    "podium-2dof", "planar_theta_max_over_alpha"); an identifier (a variable, function, class, parameter, attribute,
    keyword or imported name) with a kind's word, other than :data:`SHARED_WORDS`, as a ``_``-part
    (``CYLINDER_UNITS``, ``planar_ratio``, ``system.podium``).  Prose (a string with a space), docstrings and
    comments are words to a reader and are not read."""
    words = _kind_words()
    name_words = words - SHARED_WORDS
    known, _ = graph(package_dir)
    found = []
    for module, path in known.items():
        if _own_modules(module):
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        skip = _docstrings(tree)
        where = path.relative_to(package_dir.parent)
        for node in ast.walk(tree):
            if (isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in skip
                    and _TOKEN.fullmatch(node.value) and _parts(node.value) & words):
                found.append(f"{where}:{node.lineno}: {node.value!r}")
            for name in _identifiers(node):
                if _parts(name) & name_words:
                    found.append(f"{where}:{getattr(node, 'lineno', '?')}: {name}")
    return sorted(set(found))


def test_no_kind_name_outside_the_kinds():
    found = [f for f in kind_names() if f.split(":")[0] not in STILL_TO_MOVE]
    assert not found, ("a kind's word outside its package (move the line into the kind, or give StructureKind an "
                       "attribute the shared module asks):\n" + "\n".join(found))
    stale = sorted(set(STILL_TO_MOVE) - {f.split(":")[0] for f in kind_names()})
    assert not stale, f"neutral already (remove from STILL_TO_MOVE): {', '.join(stale)}"


def test_the_checker_sees_a_kind_name(tmp_path):
    pkg = tmp_path / "rockdesign"
    (pkg / "report").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "report" / "__init__.py").write_text("")
    (pkg / "report" / "table.py").write_text(
        '"""The podium\'s columns (prose in a docstring is read by no one)."""\n'
        'MODELS = ("auto", "podium-2dof")\n'
        'UNITS = {"planar_theta_max_over_alpha": "-"}\n'
        'def label(system, table):\n'
        '    table.add_column("a column of a podium")\n'
        '    return system.cylinder\n'
        'def figure(planar_response): ...\n')
    assert kind_names(pkg) == ["rockdesign/report/table.py:2: 'podium-2dof'",
                               "rockdesign/report/table.py:3: 'planar_theta_max_over_alpha'",
                               "rockdesign/report/table.py:6: cylinder",
                               "rockdesign/report/table.py:7: planar_response"]


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


KIND_PACKAGES = kind_packages()
"""The packages of the built-in kinds of structure, from the registry: each spans the layers (its system, project
parser, engine, check, report and entry), so its own parts are the nodes of the package graph."""


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


def kind_uses() -> dict[str, tuple[str, ...]]:
    """What a kind's package may import from another kind's: what the kind declares
    (:attr:`~rockdesign.kinds.base.StructureKind.uses`; the cylinder's check compares with the planar rocking body
    of the same p and α along each component, thesis Ch. 5, through the planar engine's public simulate)."""
    return {pkg: tuple(kind.uses) for pkg, kind in zip(KIND_PACKAGES, built_in_kinds()) if kind.uses}


def kind_imports(package_dir: Path = PACKAGE) -> list[str]:
    """``file:line: a imports b`` for every import of a kind's package from outside it that the tables above
    do not allow."""
    known, edges = graph(package_dir)
    uses = kind_uses()
    bad = []
    for module, targets in edges.items():
        own = next((k for k in KIND_PACKAGES if module == k or module.startswith(k + ".")), None)
        for target, line in targets:
            kind = next((k for k in KIND_PACKAGES if target == k or target.startswith(k + ".")), None)
            if kind is None or kind == own:
                continue
            table = uses if own else SHARED_EXCEPTIONS
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
