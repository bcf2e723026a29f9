"""First-run compilation (rockdesign/execution/compilation.py): the groups of kernels each command names, the
announcement, the markers in the kernel cache folder, and warm-ups that compile what the real calls run."""
from __future__ import annotations

import pytest

from rockdesign.execution import compilation
from rockdesign.execution.compilation import Kernels
from rockdesign.kinds import registered


def _kind(name):
    return next(k for k in registered() if k.name == name)


def test_each_kind_names_the_kernels_of_its_commands():
    planar, cylinder = _kind("planar"), _kind("cylinder")
    names = {command: [k.name for k in planar.kernels(command)] for command in ("simulate", "check")}
    assert names == {"simulate": ["planar-engine"],
                     "check": ["planar-engine", "planar-linear-exact", "elastic-spectrum"]}
    assert [k.name for k in cylinder.kernels("simulate")] == ["cylinder-integrator"]
    assert [k.name for k in cylinder.kernels("check")] == ["cylinder-integrator", "planar-engine", "elastic-spectrum"]
    assert planar.kernels("no such command") == () and cylinder.kernels("no such command") == ()
    groups = [k for kind in registered() for c in ("simulate", "check") for k in kind.kernels(c)]
    assert all(isinstance(k, Kernels) and callable(k.warm_up) and k.seconds > 0 for k in groups)
    by_name = {}
    for k in groups:                          # one name, one group (the name is its marker's)
        assert by_name.setdefault(k.name, k) is k


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty kernel cache folder (markers only: nothing is compiled by the fake warm-ups below)."""
    folder = tmp_path / "kernels-0123456789abcdef"
    monkeypatch.setattr(compilation, "kernel_cache_dir", lambda: folder)
    monkeypatch.setattr(compilation, "_load_factor", lambda: 1.0)
    monkeypatch.delenv("ROCKDESIGN_NO_WARMUP", raising=False)
    return folder


def _groups(log):
    return [Kernels("engine", lambda: log.append("engine"), 30.0), Kernels("side", lambda: log.append("side"), 4.4)]


def test_a_first_run_announces_compiles_and_marks(cache):
    log, said = [], []
    groups = _groups(log)
    assert compilation.prepare("check", groups, said.append) >= 0.0
    assert log == ["engine", "side"]
    assert said[0] == "first run: compiling the numerical kernels of `check` (about 34 s, once per version)"
    assert said[1].startswith("compiled in ") and len(said) == 2
    markers = sorted(cache.iterdir())
    assert markers == sorted(compilation.marker(g) for g in groups)                          # the markers
    assert [p.name.rsplit("-", 1)[0] for p in markers] == ["compiled-engine", "compiled-side"]
    assert float(markers[0].read_text()) >= 0.0                                               # (seconds)
    # the next run: every marker present, nothing compiled or said
    assert compilation.prepare("check", groups, lambda s: pytest.fail(s)) == 0.0 and log == ["engine", "side"]


def test_only_the_missing_groups_compile_and_count_in_the_estimate(cache):
    log, said = [], []
    engine, side = _groups(log)
    compilation.prepare("simulate", [engine], said.append)          # `simulate` compiled the engine
    said.clear()
    compilation.prepare("check", [engine, side], said.append)        # then `check` adds only its side kernels
    assert log == ["engine", "side"]
    assert said[0] == "first run: compiling the numerical kernels of `check` (about 4 s, once per version)"


def test_the_estimate_scales_with_the_machine_load(cache, monkeypatch):
    """At load 7 on 2 cores a compilation of 30 idle seconds is announced as about 105 s."""
    monkeypatch.setattr(compilation, "_load_factor", lambda: 3.5)
    assert "(about 105 s," in compilation.announcement("check", [Kernels("engine", print, 30.0)])


def test_no_warmup_and_nothing_to_compile(cache, monkeypatch):
    log = []
    assert compilation.prepare("init", (), lambda s: pytest.fail(s)) == 0.0
    monkeypatch.setenv("ROCKDESIGN_NO_WARMUP", "1")
    assert compilation.prepare("check", _groups(log), lambda s: pytest.fail(s)) == 0.0 and log == []


def test_a_cache_folder_that_cannot_be_written_costs_a_second_compilation_not_the_command(cache, monkeypatch):
    log = []
    blocked = cache.parent / "a file"
    blocked.write_text("")
    monkeypatch.setattr(compilation, "kernel_cache_dir", lambda: blocked / "kernels-0123456789abcdef")
    compilation.prepare("check", _groups(log))
    compilation.prepare("check", _groups(log))
    assert log == ["engine", "side"] * 2


def _signatures() -> dict[str, int]:
    """Compiled signatures of every numba kernel of rockdesign imported in this process."""
    import sys
    out = {}
    for name, module in list(sys.modules.items()):
        if not name.startswith("rockdesign."):
            continue
        for attr, value in vars(module).items():
            if hasattr(value, "signatures") and hasattr(value, "py_func"):
                out[f"{name}.{attr}"] = len(value.signatures)
    return out


def test_the_real_calls_use_the_warm_up_machine_code():
    """A warm-up of other argument types would compile again on the real call, after the announcement said
    it was over: each command's real work adds no signature to the kernels."""
    from rockdesign.cylinder.spectrum import cylinder_spectrum
    from rockdesign.cylinder.warm_up import SPECTRUM
    from rockdesign.library import load_project, simulate
    from rockdesign.cylinder.pairs import load_pair
    from rockdesign.paths import REPO_ROOT
    from rockdesign.planar.experiments.ensemble import run_ensemble
    from rockdesign.planar.spectra.axes import parse_axis
    from rockdesign.planar.spectra.run import PULSE_SPECTRUM
    from rockdesign.planar.spectra.spectrum import compute_spectrum, request_from_project
    pier = load_project(REPO_ROOT / "examples" / "bridge_pier.toml")
    cyl = load_project(REPO_ROOT / "examples" / "cylinder.toml")
    cases = [
        (_kind("planar").kernels("simulate"), lambda: run_ensemble(pier, "p695-farfield", scale=0.5)),
        ((PULSE_SPECTRUM,), lambda: compute_spectrum(pier.system, request_from_project(
            pier, "ricker-anti", x=parse_axis("omega_p/p:1:4:3", "x"), y=parse_axis("ap/up:0:4:3", "y")))),
        (_kind("cylinder").kernels("simulate"), lambda: simulate(cyl, "record:p695-ff/11", t_end=2.0)),
        ((SPECTRUM,), lambda: cylinder_spectrum(cyl.system, load_pair("p695-ff/11"), [0.8], [1.5],
                                                free_vibration=0.5)),
    ]
    for groups, real_call in cases:
        for group in groups:
            group.warm_up()
        before = _signatures()
        real_call()
        after = _signatures()
        assert {k: v for k, v in after.items() if before.get(k, 0) not in (0, v)} == {}, [g.name for g in groups]


def test_the_load_factor_is_the_share_of_a_core_this_process_gets():
    """The estimate's factor follows the competition for the cores, measured at once (the load average lagged it
    by a minute): with twice as many busy processes as cores beside it, this process gets at most a third of a
    core, and a compilation is announced as at least twice as long as on a quiet machine."""
    import os
    import subprocess
    import sys
    import time
    quiet = compilation._load_factor()
    assert quiet >= 1.0
    busy = [subprocess.Popen([sys.executable, "-c", "import time\nt = time.time()\nwhile time.time() - t < 8: pass"])
            for _ in range(2 * (os.cpu_count() or 1))]
    try:
        time.sleep(0.5)
        crowded = compilation._load_factor()
    finally:
        for p in busy:
            p.kill()
            p.wait()
    assert crowded >= 2.0 and crowded > quiet
