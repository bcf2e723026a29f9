"""numba's on-disk cache stays consistent with the kernel sources (rockdesign/kernel_cache.py).

numba keys a cached kernel on its own source file only, so a kernel that inlines a helper of another
file keeps the helper's old machine code.  The first test edits such a helper in a copy of the package
and shows, in fresh processes, that the edited code runs — with numba's cache in the package's
``__pycache__`` and under ``NUMBA_CACHE_DIR``.  The second shows that only rockdesign's cache files
are deleted.
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
import json, rockdesign
from rockdesign.planar.dynamics.eom import pack_parameters, potential_energy
sp = pack_parameters({"r": 1.0, "alpha": 0.2, "g": 9.81})
value = potential_energy(0.05, 1.0, 1, sp)
print(json.dumps({"package": rockdesign.__file__, "value": value,
                  "cache_hits": sum(potential_energy.stats.cache_hits.values())}))
"""
CLOSED_FORM = 9.81 * (math.cos(0.2 - 0.05) - math.cos(0.2))
HELPER_LINE = "    w = c_at\n"
EDITED_LINE = "    w = 2.0 * c_at\n"   # doubles W(θ), hence the potential energy


def _run(src: Path, cache_dir: Path | None) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    env["PYTHONPATH"] = str(src)
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(cache_dir)
    done = subprocess.run([sys.executable, "-c", PROBE], cwd=src, env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("user_cache", [False, True], ids=["package-pycache", "NUMBA_CACHE_DIR"])
def test_edited_inlined_helper_runs_in_a_new_process(tmp_path, user_cache):
    src = tmp_path / "src"
    package = src / "rockdesign"
    shutil.copytree(Path(rockdesign.__file__).parent, package,
                    ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    cache_dir = tmp_path / "numba-cache" if user_cache else None
    dynamics = package / "planar" / "dynamics"
    expected_cache = (cache_dir / f"dynamics_{hashlib.sha1(str(dynamics).encode()).hexdigest()}"
                      if user_cache else dynamics / "__pycache__")

    first = _run(src, cache_dir)
    assert Path(first["package"]).parent == package            # the copy runs, not the installed package
    assert first["value"] == pytest.approx(CLOSED_FORM, rel=1e-12)
    assert list(expected_cache.glob("eom.potential_energy-*.nbi"))   # compiled into the cache in use
    assert (expected_cache / kernel_cache.STAMP_NAME).is_file()      # the stamp beside that cache
    again = _run(src, cache_dir)
    assert again["cache_hits"] > 0 and again["value"] == first["value"]   # the cache is really used

    helper = package / "planar" / "design" / "kinematics.py"
    text = helper.read_text()
    assert text.count(HELPER_LINE) == 1
    helper.write_text(text.replace(HELPER_LINE, EDITED_LINE))
    edited = _run(src, cache_dir)
    assert edited["value"] == pytest.approx(2.0 * CLOSED_FORM, rel=1e-12)   # the edited helper runs
    assert edited["cache_hits"] == 0


def test_refresh_deletes_only_rockdesign_kernels(tmp_path, monkeypatch):
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path))
    folders = kernel_cache.cache_folders()
    dynamics = kernel_cache.PACKAGE / "planar" / "dynamics"
    cache = folders[dynamics]
    assert cache == tmp_path / f"dynamics_{hashlib.sha1(str(dynamics).encode()).hexdigest()}"
    ours = [cache / "engine.integrate-100.py311.nbi", cache / "engine.integrate-100.py311.0.nbc"]
    foreign_folder = tmp_path / f"dynamics_{hashlib.sha1(b'/elsewhere/dynamics').hexdigest()}"
    foreign_folder.mkdir()
    kept = [cache / "notours.f-1.py311.nbi", cache / "notes.txt",                # no rockdesign module
            foreign_folder / "engine.integrate-100.py311.nbi",                   # another package's folder
            tmp_path / "engine.integrate-100.py311.nbi"]
    for f in ours + kept:
        f.write_bytes(b"x")
    (cache / kernel_cache.STAMP_NAME).write_text("an older digest\n")

    assert kernel_cache.refresh_stale_caches()
    assert not any(f.exists() for f in ours)
    assert all(f.exists() for f in kept)
    for folder in folders.values():
        assert (folder / kernel_cache.STAMP_NAME).read_text().strip() == kernel_cache.sources_digest()

    for f in ours:   # stamps now match: nothing is deleted
        f.write_bytes(b"x")
    assert not kernel_cache.refresh_stale_caches()
    assert all(f.exists() for f in ours + kept)


def test_digest_covers_modules_whose_constants_kernels_read():
    names = {str(p.relative_to(kernel_cache.PACKAGE)) for p in kernel_cache.digested_sources()}
    assert {"planar/dynamics/engine.py", "planar/design/kinematics.py", "planar/dynamics/layout.py", "motions/defaults.py"} <= names
    assert "cli.py" not in names and "report/results.py" not in names


def test_reports_name_the_kernel_sources():
    """The report's Software table (and results.json, project.kernels_sha256) say which kernels ran."""
    digest = kernel_cache.sources_digest()
    assert len(digest) == 64
    assert ("rockdesign numerical kernels (SHA-256)", digest[:12] + "…") in software_versions()
