"""``import rockdesign`` changes nothing for the rest of the process and never fails (issues 48 and 49).

It used to set NUMBA_CACHE_DIR and OMP_WAIT_POLICY in ``os.environ``, so a notebook's own
``@njit(cache=True)`` functions cached into rockdesign's folder, and it raised at import when the cache
folder it was given could not be used (``~nosuchuser/…``: RuntimeError; a name too long: OSError 36; another
user's private folder: PermissionError).  Each case runs in a fresh interpreter, as a notebook would.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from rockdesign import kernel_cache

NOTEBOOK = textwrap.dedent('''
    import json, os, sys, warnings
    warnings.simplefilter("always")
    before = dict(os.environ)
    with warnings.catch_warnings(record=True) as caught:
        import rockdesign
        after_import = dict(os.environ) == before
        import numba
        from rockdesign import kernel_cache
        from rockdesign.planar.dynamics.eom import pack_parameters, potential_energy   # defines kernels
        from rockdesign.motions import spectra                                           # more kernel modules

        @numba.njit(cache=True)
        def notebook_kernel(x):
            return 2.0 * x

        value = notebook_kernel(1.5)
        energy = potential_energy(0.05, 1.0, 1, pack_parameters({"r": 1.0, "alpha": 0.2, "g": 9.81}))
        folder = kernel_cache.kernel_cache_dir()
        kernel_cache.kernel_cache_dir()
    print(json.dumps({"after_import": after_import, "after_kernels": dict(os.environ) == before,
                      "numba_cache_dir": numba.config.CACHE_DIR, "folder": str(folder), "value": value,
                      "energy": energy, "warnings": [str(w.message) for w in caught
                                                      if w.category is kernel_cache.KernelCacheWarning]}))
''')


def run_notebook(tmp_path: Path, **variables) -> dict:
    script = tmp_path / "notebook.py"
    script.write_text(NOTEBOOK)
    env = {k: v for k, v in os.environ.items()
           if k not in ("NUMBA_CACHE_DIR", "ROCKDESIGN_CACHE_DIR", "OMP_WAIT_POLICY", "PYTHONWARNINGS")}
    env.update({k: str(v) for k, v in variables.items()})
    env["ROCKDESIGN_NO_WARMUP"] = "1"
    done = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def cached_files(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*.nbi")) if folder.is_dir() else []


def test_import_sets_no_variable_and_other_kernels_cache_where_the_user_says(tmp_path):
    mine, theirs = tmp_path / "rockdesign-cache", tmp_path / "notebook-cache"
    out = run_notebook(tmp_path, ROCKDESIGN_CACHE_DIR=mine, NUMBA_CACHE_DIR=theirs)
    assert out["after_import"] and out["after_kernels"]              # os.environ untouched, OMP_WAIT_POLICY too
    assert out["numba_cache_dir"] == str(theirs)                     # numba's setting is the user's again
    assert Path(out["folder"]).parent == mine and not out["warnings"]
    ours = cached_files(mine)
    assert any("potential_energy" in name for name in ours), ours
    assert not any("notebook_kernel" in name for name in ours), ours  # the notebook's kernel is not in ours
    assert any("notebook_kernel" in name for name in cached_files(theirs))
    assert not any("potential_energy" in name for name in cached_files(theirs) if not name.startswith("rockdesign"))


def test_without_a_numba_setting_other_kernels_cache_beside_their_source(tmp_path):
    out = run_notebook(tmp_path, ROCKDESIGN_CACHE_DIR=tmp_path / "rd")
    assert out["after_kernels"] and out["numba_cache_dir"] == ""
    assert any("notebook_kernel" in n for n in cached_files(tmp_path / "__pycache__"))   # numba's default
    assert not any("notebook_kernel" in n for n in cached_files(tmp_path / "rd"))


LONG = "x" * 300


@pytest.mark.parametrize("variable,value,why", [
    ("ROCKDESIGN_CACHE_DIR", "~nosuchuser/cache", "its ~ names no home folder"),
    ("NUMBA_CACHE_DIR", "~nosuchuser/numba", "its ~ names no home folder"),
    ("ROCKDESIGN_CACHE_DIR", f"{{tmp}}/{LONG}/cache", "a name too long for the file system (Errno 36)"),
])
def test_a_cache_folder_that_cannot_be_used_falls_back_once(tmp_path, variable, value, why):
    value = value.format(tmp=tmp_path)
    out = run_notebook(tmp_path, **{variable: value})
    assert out["after_import"] and out["after_kernels"]
    assert len(out["warnings"]) == 1, out["warnings"]                 # said once, however often it is asked
    warning = out["warnings"][0]
    assert f"{variable}={value!r}" in warning and why in warning and "ROCKDESIGN_CACHE_DIR" in warning
    folder = Path(out["folder"])
    assert folder.parent.parent == Path(kernel_cache.tempfile.gettempdir()) and str(folder) in warning
    assert out["energy"] > 0 and any("potential_energy" in n for n in cached_files(folder))


@pytest.fixture
def another_users_private_folder(tmp_path, monkeypatch):
    """A folder of mode 700 owned by someone else: looking inside raises PermissionError (Errno 13).  As root
    (who may look anywhere) the refusal is what Python raises for any other user, made by Path.exists."""
    private = tmp_path / "other-user"
    (private / "cache").mkdir(parents=True)
    private.chmod(0o700)
    if os.geteuid() != 0:
        private.chmod(0o000)
    else:
        real = Path.exists

        def exists(path, *args, **kwargs):
            if str(path).startswith(str(private) + os.sep):
                raise PermissionError(13, "Permission denied", str(path))
            return real(path, *args, **kwargs)
        monkeypatch.setattr(Path, "exists", exists)
    yield private
    private.chmod(0o700)


def test_another_users_private_folder_falls_back(another_users_private_folder, monkeypatch):
    monkeypatch.setenv("ROCKDESIGN_CACHE_DIR", str(another_users_private_folder / "cache"))
    monkeypatch.setattr(kernel_cache, "_WARNED", set())
    with pytest.warns(kernel_cache.KernelCacheWarning, match=r"a folder on the way cannot be read \(Errno 13\)"):
        folder = kernel_cache.kernel_cache_dir()
    assert folder.parent.parent == Path(kernel_cache.tempfile.gettempdir())
