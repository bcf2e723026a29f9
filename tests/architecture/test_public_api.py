"""rockdesign uses only the public API of numba, scipy and WeasyPrint: no module of theirs whose dotted
name has a ``_``-prefixed part (``scipy.integrate._ivp``) and nothing of ``numba.core`` (numba's
internals: caching, dispatchers, events, signatures) is imported, at module level or inside a function.
A private module changes without notice between releases, and pinning a dependency for one would hold
back every user's environment."""
from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "rockdesign"
GUARDED = ("numba", "scipy", "weasyprint")


def private(module: str) -> bool:
    """True when ``module`` (dotted) is an internal module of a guarded library."""
    parts = module.split(".")
    if parts[0] not in GUARDED:
        return False
    return any(p.startswith("_") for p in parts[1:]) or module == "numba.core" or module.startswith("numba.core.")


def private_imports(package: Path) -> list[str]:
    """``file:line module`` for every import of a private module (or of a private name) below ``package``."""
    found = []
    for path in sorted(package.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            names: list[str] = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
                names = [node.module] + [f"{node.module}.{alias.name}" for alias in node.names]
            for name in names:
                if private(name):
                    found.append(f"{path.relative_to(package.parent)}:{node.lineno} {name}")
                    break
    return found


def test_no_private_module_of_numba_scipy_or_weasyprint_is_imported():
    bad = private_imports(PACKAGE)
    assert not bad, "private API imported (use the library's public API):\n" + "\n".join(bad)


def test_the_check_sees_private_imports(tmp_path):
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "a.py").write_text("from scipy.integrate._ivp import dop853_coefficients\n")
    (package / "b.py").write_text("def f():\n    from numba.core.caching import CompileResultCacheImpl\n")
    (package / "c.py").write_text("import weasyprint.layout._page\nfrom scipy import _lib\n")
    (package / "d.py").write_text("from numba import njit\nfrom scipy.integrate import DOP853\n"
                                  "from numba.extending import intrinsic\nimport weasyprint\n")
    found = private_imports(package)
    assert [f.split()[0] for f in found] == ["pkg/a.py:1", "pkg/b.py:2", "pkg/c.py:1", "pkg/c.py:2"]


def test_every_function_of_the_public_api_says_what_it_returns():
    """Every function ``rockdesign`` exports (``rockdesign.__all__``: rd.check, rd.simulate, rd.design, …) has a
    return annotation, so a notebook user and a type checker see what comes back."""
    import inspect

    import rockdesign
    missing = [name for name in rockdesign.__all__
               if inspect.isfunction(getattr(rockdesign, name))
               and inspect.signature(getattr(rockdesign, name)).return_annotation is inspect.Signature.empty]
    assert not missing, "no return type: " + ", ".join(missing)
