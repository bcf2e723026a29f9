"""First-run compilation: detection of numba's cache index, the announcement, per-command kernels."""
from __future__ import annotations

from rockdesign.execution import compilation
from rockdesign.planar.dynamics.engine import integrate


def test_kernels_of_each_command_exist_and_are_cacheable():
    for command, kernels in compilation.KERNELS.items():
        for module, name in kernels:
            d = compilation._dispatcher(module, name)
            assert d._cache is not None, f"{module}.{name} is not cache=True"
    # simulate never needs the closed-form linear integrator, records never the rocking engine
    assert ("rockdesign.planar.dynamics.linear_exact", "integrate_linear_exact") not in compilation.KERNELS["simulate"]
    assert all(module != "rockdesign.planar.dynamics.batch" for module, _ in compilation.KERNELS["records"])


def test_compiled_kernel_is_detected_as_cached():
    from rockdesign.planar.dynamics.simulate import simulate
    from support import block_from_p
    simulate(block_from_p(2.0, 0.15), None, theta0=0.01, t_end=0.2)   # compiled or loaded from the cache
    assert compilation.is_cached(integrate)
    assert "rockdesign.planar.dynamics.engine.integrate" not in compilation.missing_kernels("simulate")
    assert compilation.prepare("simulate", say=lambda s: (_ for _ in ()).throw(AssertionError(s))) == 0.0
    for command in compilation.KERNELS:      # the warm-up problems run (kernels loaded from the cache)
        compilation._warm(command)
        assert compilation.missing_kernels(command) == [], command   # and they cover the command's table


def _signatures(command):
    return {f"{m}.{f}": len(compilation._dispatcher(m, f).signatures) for m, f in compilation.KERNELS[command]}


def test_the_real_calls_use_the_warm_up_machine_code():
    """A warm-up of other argument types would compile again on the real call, after the announcement
    said it was over: each command's real work adds no signature to its kernels."""
    from rockdesign.library import simulate
    from rockdesign.cylinder.spectrum import cylinder_spectrum
    from rockdesign.planar.experiments.ensemble import run_ensemble
    from rockdesign.motions.pairs import load_pair
    from rockdesign.paths import REPO_ROOT
    from rockdesign.library import load_project
    from rockdesign.planar.spectra.spectrum import compute_spectrum, request_from_project
    from rockdesign.planar.spectra.axes import parse_axis
    pier = load_project(REPO_ROOT / "examples" / "bridge_pier.toml")
    cyl = load_project(REPO_ROOT / "examples" / "cylinder.toml")
    cases = {
        "ensemble": lambda: run_ensemble(pier, "p695-farfield", scale=0.5),   # built-in: a suite with missing records is refused
        "spectrum": lambda: compute_spectrum(pier.system, request_from_project(
            pier, "ricker-anti", x=parse_axis("omega_p/p:1:4:3", "x"), y=parse_axis("ap/up:0:4:3", "y"))),
        "cylinder": lambda: simulate(cyl, "record:p695-ff/11", t_end=2.0),
        "cylinder-spectrum": lambda: cylinder_spectrum(cyl.system, load_pair("p695-ff/11"), [0.8], [1.5],
                                                       free_vibration=0.5),
    }
    for command, real_call in cases.items():
        compilation._warm(command)
        before = _signatures(command)
        real_call()
        assert _signatures(command) == before, command


def test_announcement_when_the_cache_is_empty(monkeypatch, tmp_path):
    said, warmed = [], []
    monkeypatch.setattr(compilation, "MEASURED", tmp_path / "compile-seconds.json")
    monkeypatch.setattr(compilation, "_load_factor", lambda: 1.0)
    monkeypatch.delenv("ROCKDESIGN_NO_WARMUP", raising=False)
    monkeypatch.setattr(compilation, "is_cached", lambda d: False)
    monkeypatch.setattr(compilation, "_start_helper", lambda command: None)    # one core
    monkeypatch.setattr(compilation, "_warm", lambda command, parts=compilation.PARTS: warmed.append(command))
    low, high = compilation.estimate("check")
    compilation.prepare("check", say=said.append)
    assert warmed == ["check"]
    assert said[0] == compilation.MESSAGE.format(command="check", low=low, high=high)
    assert "first use after installing or upgrading" in said[0] and "once per installation" not in said[0]
    assert said[1].startswith("compiled 6 kernels in")
    # unknown commands and the opt-out compile nothing
    assert compilation.prepare("init", say=said.append) == 0.0
    monkeypatch.setenv("ROCKDESIGN_NO_WARMUP", "1")
    assert compilation.prepare("check", say=said.append) == 0.0
    assert warmed == ["check"]


class _Helper:
    """Stands in for the helper process (compilation._Helper): exits with ``code``."""

    def __init__(self, code, log):
        self.code, self.log = code, log

    def go(self):
        self.log.append("go")

    def wait(self):
        self.log.append("wait")
        return self.code

    def kill(self):
        self.log.append("kill")


def test_two_processes_share_the_work_and_a_failed_helper_costs_only_time(monkeypatch):
    """This process compiles its half of the callees, lets the helper go on to the integrator and compiles
    the side kernels meanwhile; a failed helper's engine is compiled here."""
    from rockdesign.execution import compile_plan
    monkeypatch.delenv("ROCKDESIGN_NO_WARMUP", raising=False)
    monkeypatch.setattr(compilation, "is_cached", lambda d: False)
    for code, expected in ((0, [("side",)]), (1, [("side",), ("engine",)])):
        log = []
        monkeypatch.setattr(compilation, "_start_helper", lambda command: _Helper(code, log))
        monkeypatch.setattr(compilation, "_warm", lambda command, parts=compilation.PARTS: log.append(parts))
        monkeypatch.setattr(compile_plan, "compile_entries", lambda entries: log.append(list(entries)))
        compilation.prepare("check")
        assert log == [compilation._shares("check")[0], "go", ("side",), "wait"] + expected[1:]
        assert not compilation.compilation_pending()


def test_background_compilation_is_waited_for_before_the_engine_runs(monkeypatch):
    from rockdesign.execution import compile_plan
    monkeypatch.delenv("ROCKDESIGN_NO_WARMUP", raising=False)
    monkeypatch.setattr(compilation, "is_cached", lambda d: False)
    log, said = [], []
    monkeypatch.setattr(compilation, "_start_helper", lambda command: _Helper(0, log))
    monkeypatch.setattr(compilation, "_warm", lambda command, parts=compilation.PARTS: log.append(parts))
    monkeypatch.setattr(compile_plan, "compile_entries", lambda entries: log.append("half"))
    compilation.prepare("check", say=said.append, background=True)
    assert log == ["half", "go", ("side",)] and compilation.compilation_pending()
    assert len(said) == 1                   # the announcement; "compiled ..." comes when the helper is done
    assert compilation.finish_compilation() >= 0.0
    assert log[-1] == "wait" and said[-1].startswith("compiled 6 kernels in")
    assert not compilation.compilation_pending() and compilation.finish_compilation() == 0.0
    # a helper nobody waited for (the command failed before its analyses) is stopped at exit
    compilation.prepare("check", background=True)
    compilation._abandon()
    assert log[-1] == "kill" and not compilation.compilation_pending()


def test_split_keeps_every_callee_and_balances_the_two_processes():
    from rockdesign.execution.compile_plan import callee_table, split
    entries = callee_table()
    assert len(entries) >= 20
    for head_start in (0.0, 5.0, 12.0):
        mine, theirs = split(entries, head_start)
        assert sorted(mine + theirs) == sorted(entries)
        gap = sum(e[3] for e in mine) - (sum(e[3] for e in theirs) + head_start)
        assert abs(gap) <= max(e[3] for e in entries) + 1e-9, (head_start, gap)


def test_compile_plan_names_the_signatures_the_integrator_calls():
    """After the real warm-up every entry of the plan loads from numba's cache or memory: none compiles.

    A stale entry (a kernel whose argument types changed) would make the helper compile a specialisation
    that the integrator never calls; rewrite the table with ``python -m rockdesign.execution.compile_plan_writer``.
    """
    from numba.core import event
    from rockdesign.execution.compile_plan import callee_table, compile_entries
    compilation._warm("check")
    compiled = []

    class Listener(event.Listener):
        def on_start(self, ev):
            compiled.append(ev.data["dispatcher"].py_func.__qualname__)

        def on_end(self, ev):
            pass

    listener = Listener()
    event.register("numba:compile", listener)
    try:
        compile_entries(callee_table())
    finally:
        event.unregister("numba:compile", listener)
    assert compiled == []


def test_a_stale_plan_entry_costs_time_not_the_command():
    from rockdesign.execution.compile_plan import compile_entries
    compile_entries([("rockdesign.planar.dynamics.engine", "_step_to", "(float64,)", 0.1),      # other arguments
                     ("rockdesign.planar.dynamics.no_such_module", "kernel", "()", 0.1)])       # renamed


def test_estimate_scales_with_the_load_and_with_measurements(monkeypatch, tmp_path):
    """The announced range is the idle-machine time (a measurement on this machine when there is one)
    times load/cores: at load 7 on 2 cores a 30-s compilation is announced as 105–178 s, not ~30 s."""
    monkeypatch.setattr(compilation, "MEASURED", tmp_path / "compile-seconds.json")
    monkeypatch.setattr(compilation, "_load_factor", lambda: 1.0)
    assert compilation.estimate("check") == (30, 51)
    monkeypatch.setattr(compilation, "_load_factor", lambda: 3.5)
    assert compilation.estimate("check") == (105, 178)
    # a compilation measured here (124 s at load factor 2) sets the idle time of that command (62 s) …
    compilation._remember("check", 124.0, 2.0)
    assert compilation.estimate("check") == (217, 369)
    # … and scales the other commands' estimates by the same machine ratio (62/30)
    monkeypatch.setattr(compilation, "_load_factor", lambda: 1.0)
    low, high = compilation.estimate("cylinder")
    assert low == round(30 * 62 / 30) and high == round(1.7 * 62)
