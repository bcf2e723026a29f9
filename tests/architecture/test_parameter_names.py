"""The library names the parameter an error is about; only the command line speaks of flags
(docs/architecture.md, "Rules that follow from the layers").

Below ``rockdesign/cli/`` an error is keyed by a parameter of the function called (``key="motion"``,
``key="t_end"``); ``cli/app.py`` shows the command's option instead (``--motion``).  These tests read every
module with :mod:`ast` and fail on a flag-shaped key there, and check that the command line imports only the
public names of ``rockdesign`` (not the names kept for compatibility).
"""
from __future__ import annotations

import ast
import re
from pathlib import Path

from layers import LAYERS, graph, layer_of

PACKAGE = Path(__file__).resolve().parents[2] / "rockdesign"
FLAG = re.compile(r"^-{1,2}[A-Za-z]")
"""A command-line flag: ``--motion``, ``-o/--out``, ``--table d``."""
KEY_POSITIONAL = {"created_folder": 1, "refuse_wrong_type": 1, "output_file": 1, "output_folder": 1}
"""Functions taking the key of their errors as a positional argument (index)."""
CLI_LAYER = [name for name, _ in LAYERS].index("cli")


def _flags(node: ast.AST) -> list[str]:
    """Flag-shaped string constants in an expression (f-strings by their first literal part)."""
    found = []
    parts = {id(part) for sub in ast.walk(node) if isinstance(sub, ast.JoinedStr) for part in sub.values}
    for sub in ast.walk(node):
        if id(sub) in parts:
            continue
        if isinstance(sub, ast.Constant) and isinstance(sub.value, str) and FLAG.match(sub.value):
            found.append(sub.value)
        elif isinstance(sub, ast.JoinedStr) and sub.values and isinstance(sub.values[0], ast.Constant) \
                and re.match(r"^-{1,2}([A-Za-z]|$)", str(sub.values[0].value)):      # f"--{which}" too
            found.append(ast.unparse(sub))
    return found


def flag_keys(package_dir: Path = PACKAGE) -> list[str]:
    """``file:line: value`` of every key that is a flag in a module below the command line: ``key=`` arguments,
    defaults of parameters named ``key``, assignments to ``key`` and the key argument of the output-path
    helpers."""
    known, _ = graph(package_dir)
    found = []
    for module, path in known.items():
        layer = layer_of(module)
        if layer is not None and layer >= CLI_LAYER:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            values: list[ast.AST] = []
            if isinstance(node, ast.Call):
                values += [kw.value for kw in node.keywords if kw.arg == "key"]
                name = node.func.attr if isinstance(node.func, ast.Attribute) else getattr(node.func, "id", None)
                index = KEY_POSITIONAL.get(name)
                if index is not None and len(node.args) > index:
                    values.append(node.args[index])
            elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                args = node.args
                positional = args.posonlyargs + args.args
                for arg, default in zip(positional[len(positional) - len(args.defaults):], args.defaults):
                    if arg.arg == "key":
                        values.append(default)
                values += [d for a, d in zip(args.kwonlyargs, args.kw_defaults) if a.arg == "key" and d is not None]
            elif isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "key" for t in node.targets):
                values.append(node.value)
            for value in values:
                found += [f"{path.relative_to(package_dir.parent)}:{node.lineno}: {flag}" for flag in _flags(value)]
    return sorted(found)


def test_no_error_below_the_command_line_is_keyed_by_a_flag():
    found = flag_keys()
    assert not found, ("errors keyed by a command-line flag below rockdesign/cli (name the library parameter; "
                       "cli/app.py shows the option):\n" + "\n".join(found))


def test_the_checker_sees_flag_keys(tmp_path):
    pkg = tmp_path / "rockdesign"
    (pkg / "motions").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "motions" / "__init__.py").write_text("")
    (pkg / "motions" / "parse.py").write_text(
        "def f(text, which, key='--suite'):\n"
        "    raise MotionError('bad', key='--motion')\n"
        "def g(which, name):\n"
        "    key = '--x' if which == 'x' else '--y'\n"
        "    created_folder(name, '-o/--out')\n"
        "    raise MotionError('bad', key=f'--table {name}', found='--not-a-key')\n"
        "    raise MotionError('bad', key=f'--{which}')\n"
        "def h(name):\n"
        "    raise MotionError('fine', key='motion', expected='--motion in the message is text')\n")
    found = flag_keys(pkg)
    assert found == ["rockdesign/motions/parse.py:1: --suite", "rockdesign/motions/parse.py:2: --motion",
                     "rockdesign/motions/parse.py:4: --x", "rockdesign/motions/parse.py:4: --y",
                     "rockdesign/motions/parse.py:5: -o/--out",
                     "rockdesign/motions/parse.py:6: f'--table {name}'", "rockdesign/motions/parse.py:7: f'--{which}'",
                     ], found


FLAG_IN_TEXT = re.compile(r"(?:^|[\s(\[\"'`])(--[a-z][a-z0-9-]*)")
"""A command-line flag inside a text: "(--prefer material)", "or --records-dir to a folder"."""
PENDING_FLAG_TEXTS: dict[str, set[str]] = {}
"""Library texts still naming a flag, each owned by another item of issue 48 ("no library message names a CLI
flag"): remove an entry when its module is fixed (the test fails on an entry that no longer applies)."""


def flag_texts(package_dir: Path = PACKAGE) -> dict[str, set[str]]:
    """module file → the flags named in its string constants (messages, reasons, notes; docstrings excepted),
    for every module below the command line."""
    known, _ = graph(package_dir)
    found: dict[str, set[str]] = {}
    for module, path in known.items():
        layer = layer_of(module)
        if layer is not None and layer >= CLI_LAYER:
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                      if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                      and node.body and isinstance(node.body[0], ast.Expr)
                      and isinstance(node.body[0].value, ast.Constant)}
        docstrings |= {id(node.value) for node in ast.walk(tree)     # attribute docstrings ("""…""" after a name)
                       if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)}
        for node in ast.walk(tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings:
                flags = set(FLAG_IN_TEXT.findall(node.value))
                if flags:
                    found.setdefault(str(path.relative_to(package_dir.parent)), set()).update(flags)
    return found


def test_no_library_text_names_a_flag():
    """A library message speaks of the parameter (``prefer="material"``, ``records_dir``); only the command line
    speaks of ``--prefer`` (issue 50, "library wording")."""
    found = flag_texts()
    new = {f: flags - PENDING_FLAG_TEXTS.get(f, set()) for f, flags in found.items()}
    new = {f: flags for f, flags in new.items() if flags}
    assert not new, f"library texts naming command-line flags: {new}"
    stale = {f: flags - found.get(f, set()) for f, flags in PENDING_FLAG_TEXTS.items()}
    assert not any(stale.values()), f"fixed: remove from PENDING_FLAG_TEXTS {stale}"


def test_the_text_checker_sees_flags(tmp_path):
    pkg = tmp_path / "rockdesign"
    (pkg / "design_space").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "design_space" / "__init__.py").write_text("")
    (pkg / "design_space" / "grid.py").write_text(
        '"""A docstring may say ``design --prefer material``."""\n'
        "NOTE = 'x'\n"
        '"""An attribute docstring: --json."""\n'
        "def f(prefer):\n"
        '    """--every-cell in a docstring."""\n'
        "    return 'least material' + (' (--prefer material)' if prefer else '') + f'{prefer} or --records-dir x'\n"
        "def g():\n"
        "    return 'a - b, x--y, -1, ---'\n")
    assert flag_texts(pkg) == {"rockdesign/design_space/grid.py": {"--prefer", "--records-dir"}}


def _names_from_rockdesign(tree: ast.AST) -> list[tuple[str, int]]:
    """(name, line) of every name a command-line module takes from the package ``rockdesign`` itself:
    ``from .. import X``, ``from rockdesign import X`` and ``rd.X`` after ``import rockdesign as rd``."""
    aliases, found = set(), []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and ((node.level == 2 and not node.module)
                                                 or (node.level == 0 and node.module == "rockdesign")):
            found += [(alias.name, node.lineno) for alias in node.names]
        elif isinstance(node, ast.Import):
            aliases |= {alias.asname or alias.name for alias in node.names if alias.name == "rockdesign"}
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases:
            found.append((node.attr, node.lineno))
    return found


def test_the_command_line_uses_only_the_public_names():
    """``rockdesign/__init__.py`` keeps older names importable (``_COMPATIBLE``); the command line calls the
    public functions (``_EXPORTS``) — or a module it may import (tests/architecture/test_front_door.py)."""
    import rockdesign
    modules = {"library", "errors", "console", "display", "templates", "cli", "__version__"}
    bad = []
    for path in sorted((PACKAGE / "cli").rglob("*.py")):
        for name, line in _names_from_rockdesign(ast.parse(path.read_text(encoding="utf-8"))):
            if name not in rockdesign._EXPORTS and name not in modules:
                bad.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {name}")
    assert not bad, "the command line uses names that are not public (rockdesign._EXPORTS):\n" + "\n".join(bad)


def test_every_name_stays_importable():
    """The public names and the names kept for compatibility all resolve (CONTRACT: extend, never break)."""
    import rockdesign
    assert not set(rockdesign._EXPORTS) & set(rockdesign._COMPATIBLE)
    for name in [*rockdesign._EXPORTS, *rockdesign._COMPATIBLE]:
        assert getattr(rockdesign, name) is not None, name
    assert set(rockdesign.__all__) == set(rockdesign._EXPORTS)


def test_no_public_name_is_a_module_of_the_package():
    """``rd.bench`` would turn into the package ``rockdesign.bench`` once that is imported (Python sets the
    attribute of a parent package): a public name may not be a module's name."""
    import rockdesign
    modules = {p.stem for p in PACKAGE.glob("*.py")} | {p.name for p in PACKAGE.iterdir() if p.is_dir()}
    assert not modules & (set(rockdesign._EXPORTS) | set(rockdesign._COMPATIBLE))
