"""rockdesign's kernel cache (rockdesign/kernel_cache.py): a folder of the user's cache named by the digest of
the kernel sources, so that an edited source never runs stale machine code, and nothing written into the package.

numba keys a cached kernel on its own source file only, so a kernel that inlines a helper of another file
would keep the helper's old machine code.  The first test edits such a helper in a copy of the package and
shows, in fresh processes, that the edited code runs, that the kernels and the first-run marker land in the
digest's folder, and that nothing is written under the package.
"""
from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numba
import pytest

import rockdesign
from rockdesign import kernel_cache
from rockdesign.report.context import software_versions

# potential_energy (dynamics/eom.py) inlines unit_centre_kinematics (design/kinematics.py, inline="always").
# Block (r = 0, γ = 0): W(θ) = cos(α − θ), so the energy is g/R · (cos(α − θ) − cos α) (Eq 3.2).
PROBE = """
import json, os, rockdesign
from rockdesign import kernel_cache
from rockdesign.execution.compilation import Kernels, marker, prepare
from rockdesign.planar.dynamics.eom import pack_parameters, potential_energy
sp = pack_parameters({"r": 1.0, "alpha": 0.2, "g": 9.81})
probe = Kernels("probe", lambda: potential_energy(0.05, 1.0, 1, sp), 1.0)
prepare("probe", [probe])
value = potential_energy(0.05, 1.0, 1, sp)
print(json.dumps({"package": rockdesign.__file__, "value": value, "folder": str(kernel_cache.kernel_cache_dir()),
                  "numba_cache_dir": os.environ.get("NUMBA_CACHE_DIR"), "marker": str(marker(probe)),
                  "cache_hits": sum(potential_energy.stats.cache_hits.values())}))
"""
CLOSED_FORM = 9.81 * (math.cos(0.2 - 0.05) - math.cos(0.2))
HELPER_LINE = "    w = c_at\n"
EDITED_LINE = "    w = 2.0 * c_at\n"   # doubles W(θ), hence the potential energy


def _run(src: Path, cache_root: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    env.update(PYTHONPATH=str(src), ROCKDESIGN_CACHE_DIR=str(cache_root), PYTHONDONTWRITEBYTECODE="1")
    done = subprocess.run([sys.executable, "-c", PROBE], cwd=src, env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def _listing(folder: Path) -> dict[str, tuple[int, int]]:
    return {str(p.relative_to(folder)): (p.stat().st_size, p.stat().st_mtime_ns) for p in folder.rglob("*")}


def test_edited_inlined_helper_runs_and_nothing_is_written_into_the_package(tmp_path):
    src = tmp_path / "src"
    package = src / "rockdesign"
    shutil.copytree(Path(rockdesign.__file__).parent, package,
                    ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    cache_root = tmp_path / "cache"
    dynamics = package / "planar" / "dynamics"
    listing = _listing(package)

    first = _run(src, cache_root)
    assert Path(first["package"]).parent == package            # the copy runs, not the installed package
    assert first["value"] == pytest.approx(CLOSED_FORM, rel=1e-12)
    folder = Path(first["folder"])
    assert folder.parent == cache_root and folder.name.startswith("kernels-")   # named by the digest
    assert first["numba_cache_dir"] is None                    # the environment is left as it was
    numba_folder = folder / f"dynamics_{hashlib.sha1(str(dynamics).encode()).hexdigest()}"
    assert list(numba_folder.glob("eom.potential_energy-*.nbi"))   # compiled into the digest's folder
    assert Path(first["marker"]).parent == folder and Path(first["marker"]).is_file()
    assert Path(first["marker"]).name.startswith("compiled-probe-")
    again = _run(src, cache_root)
    assert again["cache_hits"] > 0 and again["value"] == first["value"]   # the cache is really used
    assert _listing(package) == listing                                   # nothing written under the package

    helper = package / "planar" / "design" / "kinematics.py"
    text = helper.read_text()
    assert text.count(HELPER_LINE) == 1
    helper.write_text(text.replace(HELPER_LINE, EDITED_LINE))
    edited = _run(src, cache_root)
    assert edited["value"] == pytest.approx(2.0 * CLOSED_FORM, rel=1e-12)   # the edited helper runs
    assert edited["cache_hits"] == 0
    assert Path(edited["folder"]) != folder and Path(edited["folder"]).parent == cache_root   # another digest
    assert Path(edited["marker"]).is_file()                   # its own first run, marked in its own folder


@pytest.fixture
def clean_environment(monkeypatch):
    """No cache variable set; numba's configuration restored afterwards."""
    for name in ("NUMBA_CACHE_DIR", "ROCKDESIGN_CACHE_DIR", "XDG_CACHE_HOME"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setattr(numba.config, "CACHE_DIR", numba.config.CACHE_DIR)
    return monkeypatch


def test_the_folder_is_in_the_user_cache_and_named_by_the_digest(clean_environment, tmp_path):
    name = f"kernels-{kernel_cache.sources_digest()[:16]}"
    assert kernel_cache.folder_name() == name
    clean_environment.setenv("HOME", str(tmp_path / "home"))
    if sys.platform != "win32":
        assert kernel_cache.kernel_cache_dir() == tmp_path / "home" / ".cache" / "rockdesign" / name
    clean_environment.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert kernel_cache.kernel_cache_dir() == tmp_path / "xdg" / "rockdesign" / name
    clean_environment.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))     # a numba cache the user chose
    assert kernel_cache.kernel_cache_dir() == tmp_path / "numba" / "rockdesign" / name
    clean_environment.setenv("ROCKDESIGN_CACHE_DIR", str(tmp_path / "mine"))
    assert kernel_cache.kernel_cache_dir() == tmp_path / "mine" / name
    assert not (tmp_path / "mine").exists()                                  # nothing is written to find it


def test_the_kernel_cache_is_numbas_configuration_only_while_rockdesign_defines_kernels(clean_environment, tmp_path):
    clean_environment.setenv("ROCKDESIGN_CACHE_DIR", str(tmp_path / "mine"))
    folder = tmp_path / "mine" / kernel_cache.folder_name()
    before, environ = numba.config.CACHE_DIR, dict(os.environ)
    with kernel_cache.kernel_cache_in_use():
        with kernel_cache.kernel_cache_in_use():              # nested kernel modules
            assert numba.config.CACHE_DIR == str(folder)
        assert numba.config.CACHE_DIR == str(folder)
    assert numba.config.CACHE_DIR == before and dict(os.environ) == environ
    # a process started with NUMBA_CACHE_DIR at the folder itself uses it, not one nested in it
    clean_environment.delenv("ROCKDESIGN_CACHE_DIR")
    clean_environment.setenv("NUMBA_CACHE_DIR", str(folder))
    assert kernel_cache.kernel_cache_dir() == folder


def test_a_cache_root_that_cannot_be_written_falls_back_to_the_temporary_directory(clean_environment, tmp_path):
    blocked = tmp_path / "a file"
    blocked.write_text("")
    clean_environment.setenv("ROCKDESIGN_CACHE_DIR", str(blocked / "cache"))
    with pytest.warns(kernel_cache.KernelCacheWarning, match="cannot be written"):
        folder = kernel_cache.kernel_cache_dir()
    assert folder.name == kernel_cache.folder_name() and folder.parent.parent == Path(kernel_cache.tempfile.gettempdir())


def test_the_package_imports_no_kernel_and_sets_no_variable():
    """numba picks a kernel's cache folder when the kernel is defined: ``import rockdesign`` installs the finder
    that executes kernel modules with the folder set, imports no kernel (nor numba) and changes no variable."""
    code = ("import os, sys; before = dict(os.environ); import rockdesign; from rockdesign import kernel_cache; "
            "print(dict(os.environ) == before, 'numba' in sys.modules, "
            "isinstance(sys.meta_path[0], kernel_cache.KernelModuleFinder))")
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "OMP_WAIT_POLICY")}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    assert out.stdout.split() == ["True", "False", "True"], out


def test_digest_covers_modules_whose_constants_kernels_read():
    names = {str(p.relative_to(kernel_cache.PACKAGE)) for p in kernel_cache.digested_sources()}
    assert {"planar/dynamics/engine.py", "planar/design/kinematics.py", "planar/dynamics/layout.py", "motions/defaults.py"} <= names
    assert "cli.py" not in names and "report/results.py" not in names


def test_reports_name_the_kernel_sources():
    """The report's Software table (and results.json, project.kernels_sha256) say which kernels ran."""
    digest = kernel_cache.sources_digest()
    assert len(digest) == 64
    assert ("rockdesign numerical kernels (SHA-256)", digest[:12] + "…") in software_versions()
