"""One executor protocol (docs/architecture.md): a check runs its batches through ``executor.map`` and counts
them with ``executor.count`` whatever it was given — no module asks which executor class it has, and only
``execution/`` names the design grid's pool member.  Read from the sources (every module of the package)."""
from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "rockdesign"
EXECUTOR_CLASSES = {"LocalExecutor", "DaskExecutor", "PoolMember", "BatchPool", "SharedCall"}


def _modules():
    for path in sorted(PACKAGE.rglob("*.py")):
        yield path.relative_to(PACKAGE.parent).as_posix(), ast.parse(path.read_text(encoding="utf-8"))


def _names(node) -> set[str]:
    return {n.id if isinstance(n, ast.Name) else n.attr for n in ast.walk(node) if isinstance(n, (ast.Name, ast.Attribute))}


def test_no_module_asks_which_executor_it_was_given():
    found = []
    for name, tree in _modules():
        for node in ast.walk(tree):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("isinstance", "type")
                    and len(node.args) > 1 and _names(node.args[1]) & EXECUTOR_CLASSES):
                found.append(f"{name}:{node.lineno}")
    assert not found, "a branch on the executor's class (use the protocol: map, count, slots): " + ", ".join(found)


def test_only_execution_names_the_grid_s_pool():
    found = [name for name, tree in _modules() if not name.startswith("rockdesign/execution/")
             and {"PoolMember", "AnalysisCount"} & _names(tree)]
    assert not found, "the pool member is an executor like any other; analyses are counted on the executor: " \
                      + ", ".join(found)


def test_the_test_sees_a_branch_on_the_executor_s_class():
    """The checks above fail on the code they replaced (a member recognised by type)."""
    old = ast.parse("member = executor if isinstance(executor, PoolMember) else None\n")
    node = next(n for n in ast.walk(old) if isinstance(n, ast.Call))
    assert _names(node.args[1]) & EXECUTOR_CLASSES and {"PoolMember"} & _names(old)
