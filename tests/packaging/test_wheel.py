"""rockdesign as a user installs it: ``python -m build`` makes an sdist and a wheel that both carry the
built-in records, suites and templates; the wheel, installed into a fresh virtualenv (no editable
path, no access to the checkout), runs ``init``, ``quantities``, ``simulate`` with a built-in record
and a full ``check`` to a PDF from a temporary directory.

How the clean install is made (honest and reasonably fast): ``python -m venv`` without
``--system-site-packages``; ``pip install <wheel>`` resolves every dependency itself from the package
index pip is configured with (PyPI, or a local mirror/wheel cache through pip's own configuration) —
nothing is borrowed from the development virtualenv.  The first run in the new venv compiles the
numba kernels, so the test takes a few minutes; it is marked ``slow``.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow

REPO = Path(__file__).resolve().parents[2]
SOURCE_DATA = ["ground_motions/p695_records.csv", "ground_motions/p695_farfield.npz", "ground_motions/p695-farfield.toml",
               "templates/report.html.j2", "templates/report.css", "templates/project_podium.toml"]
"""Built-in data at the top of the checkout (and of the sdist)."""
DATA = [f"rockdesign/data/{name}" for name in SOURCE_DATA]
"""The same files as package data in the wheel."""


def _run(cmd, cwd, env, timeout=900):
    out = subprocess.run([str(c) for c in cmd], cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    assert out.returncode in (0, 1), f"{cmd}\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}"
    return out


@pytest.fixture(scope="module")
def dist(tmp_path_factory):
    pytest.importorskip("build")
    out = tmp_path_factory.mktemp("dist")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    result = subprocess.run([sys.executable, "-m", "build", "--outdir", str(out), str(REPO)], env=env,
                            capture_output=True, text=True, timeout=900)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    return out


def test_sdist_and_wheel_carry_the_data(dist):
    (wheel,) = dist.glob("rockdesign-*.whl")
    (sdist,) = dist.glob("rockdesign-*.tar.gz")
    names = set(zipfile.ZipFile(wheel).namelist())
    assert set(DATA) <= names
    assert sum(n.endswith(".npz") for n in names) == 3
    with tarfile.open(sdist) as tar:
        members = {m.name.split("/", 1)[1] for m in tar.getmembers() if "/" in m.name}
    assert set(SOURCE_DATA) <= members


@pytest.fixture(scope="module")
def venv(dist, tmp_path_factory):
    """A fresh virtualenv with the wheel installed the normal way (dependencies from the index)."""
    home = tmp_path_factory.mktemp("venv")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    subprocess.run([sys.executable, "-m", "venv", str(home / "venv")], check=True, env=env, timeout=300)
    bin_dir = home / "venv" / ("Scripts" if os.name == "nt" else "bin")
    (wheel,) = dist.glob("rockdesign-*.whl")
    result = subprocess.run([bin_dir / "python", "-m", "pip", "install", "-q", str(wheel)], env=env,
                            capture_output=True, text=True, timeout=1800)
    assert result.returncode == 0, result.stderr[-3000:]
    env = {k: v for k, v in env.items() if not k.startswith("ROCKDESIGN_")}
    env["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
    return bin_dir, env


def test_installed_wheel_runs_every_command_from_a_temporary_directory(venv, tmp_path):
    bin_dir, env = venv
    work = tmp_path / "work"
    work.mkdir()
    # the imported package is the installed one; nothing of the checkout is importable
    probe = _run([bin_dir / "python", "-c", "import json, sys, rockdesign, rockdesign.paths as p; print(json.dumps("
                  "{'file': rockdesign.__file__, 'path': sys.path, 'data': str(p.ground_motions_dir()), "
                  "'meta': [type(f).__name__ for f in sys.meta_path]}))"], work, env)
    info = json.loads(probe.stdout)
    venv_root = bin_dir.parent.resolve()
    assert Path(info["file"]).resolve().is_relative_to(venv_root)
    assert Path(info["data"]).resolve().is_relative_to(venv_root)
    assert not any(p and Path(p).resolve().is_relative_to(REPO) for p in info["path"])
    assert not any("Editable" in name for name in info["meta"])

    rockdesign = bin_dir / "rockdesign"
    _run([rockdesign, "init", "podium", "podium.toml"], work, env)
    q = json.loads(_run([rockdesign, "quantities", "podium.toml", "--json"], work, env).stdout)
    assert q["quantities"]["theta_c"]["unit"] == "rad"
    s = json.loads(_run([rockdesign, "simulate", "podium.toml", "--motion", "record:p695-ff/11a,scale=0.5", "--json"],
                        work, env).stdout)
    assert s["t_end"] > 20 and s["theta_max"] >= 0   # the Landers record is read from the installed package
    # the cylinder through the same front door (the registry of kinds is in the wheel)
    _run([rockdesign, "init", "cylinder", "cyl.toml"], work, env)
    qc = json.loads(_run([rockdesign, "quantities", "cyl.toml", "--json"], work, env).stdout)
    assert qc["quantities"]["alpha"]["unit"] == "rad"
    sc = json.loads(_run([rockdesign, "simulate", "cyl.toml", "--motion", "free:theta0=0.5alpha", "--t-end", "1",
                          "--json"], work, env).stdout)
    assert sc["model"].startswith("cylinder-") and sc["theta_max_over_alpha"] > 0.49
    listing = _run([rockdesign, "records", "list", "--json"], work, env)
    assert len(json.loads(listing.stdout)) == 100
    check = _run([rockdesign, "check", "podium.toml", "-o", "out"], work, env, timeout=1800)
    assert check.returncode in (0, 1)
    assert sorted(p.name for p in (work / "out").iterdir()) == ["report.html", "report.pdf", "results.csv",
                                                               "results.json"]
    assert (work / "out" / "report.pdf").read_bytes()[:5] == b"%PDF-"
    data = json.loads((work / "out" / "results.json").read_text(encoding="utf-8"))
    assert data["summary"]["n_records"] == 44 and not data["excitation"]["missing"]


def test_installed_wheel_refuses_the_inputs_of_issue_49(venv, tmp_path):
    """From the installed wheel (no dask there: the "absent" path for real): exit 2 naming the key or option,
    and ``import rockdesign`` neither fails on a cache folder it cannot use nor changes the environment."""
    bin_dir, env = venv
    work = tmp_path / "work"
    work.mkdir()

    def refused(*args, **extra_env):
        out = subprocess.run([str(bin_dir / "rockdesign"), *map(str, args)], cwd=work, env={**env, **extra_env},
                             capture_output=True, text=True, timeout=600)
        assert out.returncode == 2 and "Traceback" not in out.stderr, (args, out.stdout[-2000:], out.stderr[-2000:])
        return " ".join(out.stderr.split())

    probe = ("import os, json; before = dict(os.environ); import rockdesign as rd; same = dict(os.environ) == before\n"
             "try:\n    rd.load_project(None)\nexcept rd.ProjectError as err:\n    key = err.key\n"
             "print(json.dumps({'same': same, 'key': key}))")
    out = subprocess.run([str(bin_dir / "python"), "-c", probe], cwd=work, capture_output=True, text=True,
                         env={**env, "ROCKDESIGN_CACHE_DIR": "~nosuchuser/cache"}, timeout=300)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout) == {"same": True, "key": "path"}

    _run([bin_dir / "rockdesign", "init", "podium", "podium.toml"], work, env)
    assert "names no home folder" in refused("check", "podium.toml", "-o", "~nosuchuser/out")
    assert "outside 1–65535" in refused("check", "podium.toml", "--dask", "tcp://127.0.0.1:70267")
    assert "invalid local cluster" in refused("check", "podium.toml", "--dask", "local:0")
    assert "dask.distributed is not installed" in refused("check", "podium.toml", "--dask", "tcp://127.0.0.1:1")
    text = (REPO / "examples" / "podium_asce7_22.toml").read_text(encoding="utf-8")
    (work / "asce.toml").write_text(text.replace('SMS = "0.30 g"', 'SMS = "1e400 g"'), encoding="utf-8")
    assert "key 'excitation.scale.SMS'" in refused("check", "asce.toml", "--no-pdf")
    assert not (work / "podium_check").exists() and not (work / "asce_check").exists()
