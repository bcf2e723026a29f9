"""One-way architecture (docs/architecture.md): imports point down the layer table, no cycles, every
module placed, and the scipy baseline stays out of the production path."""
from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from layers import KIND_PARTS, LAYERS, cycles, graph, kind_packages, layer_of, unplaced, upward_imports

PACKAGE = Path(__file__).resolve().parents[2] / "rockdesign"


def test_every_import_points_down_the_layers():
    bad = upward_imports(PACKAGE)
    assert not bad, "imports against the layer order (docs/architecture.md):\n" + "\n".join(bad)


def test_no_import_cycles():
    found = cycles(PACKAGE)
    assert not found, "import cycles: " + "; ".join(" ↔ ".join(c) for c in found)


def test_every_module_is_placed_in_a_layer():
    assert unplaced(PACKAGE) == [], "place new modules in tests/architecture/layers.py LAYERS"


def test_the_table_has_no_dead_entries():
    modules = set(graph(PACKAGE)[0])
    for _, prefixes in LAYERS:
        for prefix in prefixes:
            assert any(m == prefix or m.startswith(prefix if prefix.endswith("_") else prefix + ".")
                       for m in modules), f"{prefix} names no module"


def test_kind_modules_are_placed_by_package_from_the_registry():
    """The kinds' modules are placed by their name in the kind's package, for every kind of the registry: a new
    kind's package needs no line in the table; every part named in KIND_PARTS is a part of some kind."""
    kinds = kind_packages()
    assert len(kinds) == len(set(kinds)) >= 2
    for kind in kinds:
        assert LAYERS[layer_of(f"{kind}.kind")][0] == "library"
        assert LAYERS[layer_of(f"{kind}.project")][0] == "project"
    modules = set(graph(PACKAGE)[0])
    for layer, parts in KIND_PARTS.items():
        for part in parts:
            assert not part or any(m == f"{k}.{part}" or m.startswith(f"{k}.{part}.") for k in kinds for m in modules), \
                f"KIND_PARTS[{layer!r}] names {part!r}, a part of no kind"


def _write(root: Path, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    return root / "pkg"


def test_the_checker_sees_lazy_relative_and_from_package_imports(tmp_path):
    pkg = _write(tmp_path, {
        "pkg/__init__.py": "",
        "pkg/low.py": """
            def f():
                from .high import g          # lazy, relative, upward
                return g
            """,
        "pkg/high.py": "import pkg.low\n",
        "pkg/sub/__init__.py": "",
        "pkg/sub/a.py": "from .. import low\nfrom . import b\n",
        "pkg/sub/b.py": "from pkg.sub import a\n",
    })
    layers = (("base", ("pkg", "pkg.low", "pkg.sub")), ("top", ("pkg.high",)))
    bad = upward_imports(pkg, layers)
    assert bad == ["low.py:3: pkg.low (base) imports pkg.high (top)"]
    assert cycles(pkg) == [["pkg.high", "pkg.low"], ["pkg.sub.a", "pkg.sub.b"]]
    assert unplaced(pkg, (("base", ("pkg.low",)),)) == ["pkg", "pkg.high", "pkg.sub", "pkg.sub.a", "pkg.sub.b"]
    assert layer_of("pkg.sub.a", layers) == 0 and layer_of("pkg.high", layers) == 1


def test_most_specific_prefix_wins():
    assert LAYERS[layer_of("rockdesign.cylinder.project")][0] == "project"
    assert LAYERS[layer_of("rockdesign.cylinder.kernel")][0] == "dynamics"
    assert LAYERS[layer_of("rockdesign.cli.records")][0] == "cli"
    assert LAYERS[layer_of("rockdesign.bench.baseline.scipy_engine")][0] == "bench"


@pytest.mark.slow
def test_a_check_never_imports_the_benchmarks_or_the_scipy_baseline(tmp_path):
    """`rockdesign check` (the CLI, in a fresh interpreter) leaves no rockdesign.bench module loaded."""
    script = textwrap.dedent(f"""
        import sys
        from rockdesign.cli import main
        sys.argv = ["rockdesign", "check", "examples/bridge_pier.toml", "--no-pdf", "-o", {str(tmp_path / 'out')!r}]
        try:
            main()
        except SystemExit as exc:
            code = exc.code
        print("EXIT", code)
        print("LOADED", sorted(m for m in sys.modules if m.startswith("rockdesign.bench")))
        """)
    proc = subprocess.run([sys.executable, "-c", script], cwd=PACKAGE.parent, capture_output=True, text=True,
                          timeout=900)
    lines = proc.stdout.splitlines()
    assert any(line.startswith("EXIT 1") or line.startswith("EXIT 0") for line in lines), proc.stderr[-2000:]
    assert "LOADED []" in lines, [line for line in lines if line.startswith("LOADED")]
    assert (tmp_path / "out" / "results.json").is_file()


@pytest.mark.slow
def test_a_library_check_never_imports_the_benchmarks_or_the_scipy_baseline(tmp_path):
    """``rd.check`` + ``rd.write_report`` (docs/api.md), in a fresh interpreter so that no other test's
    imports count, leave no rockdesign.bench module loaded; nor does importing the cylinder check path."""
    script = textwrap.dedent(f"""
        import sys
        import rockdesign as rd
        result = rd.check(rd.load_project("examples/bridge_pier.toml"), margins=False)
        rd.write_report(result, {str(tmp_path / 'out')!r}, pdf=False)
        import rockdesign.cylinder.check, rockdesign.cylinder.report  # noqa: E401
        print("VERDICT", result.verdict)
        print("LOADED", sorted(m for m in sys.modules if m.startswith("rockdesign.bench")))
        """)
    proc = subprocess.run([sys.executable, "-c", script], cwd=PACKAGE.parent, capture_output=True, text=True,
                          timeout=900)
    lines = proc.stdout.splitlines()
    assert any(line in ("VERDICT PASS", "VERDICT FAIL") for line in lines), proc.stderr[-2000:]
    assert "LOADED []" in lines, [line for line in lines if line.startswith("LOADED")]
    assert (tmp_path / "out" / "results.json").is_file()


def test_the_runtime_check_would_see_a_benchmark_import(tmp_path):
    """The sys.modules probe used above is not vacuous: importing the scipy baseline shows up in it."""
    script = ("import sys, rockdesign.bench.baseline.scipy_engine\n"
              "print(sorted(m for m in sys.modules if m.startswith('rockdesign.bench')))\n")
    proc = subprocess.run([sys.executable, "-c", script], cwd=PACKAGE.parent, capture_output=True, text=True,
                          timeout=300)
    assert "rockdesign.bench.baseline.scipy_engine" in proc.stdout, proc.stderr[-2000:]
