"""First-run compilation: detection of numba's cache index, the announcement, per-command kernels."""
from __future__ import annotations

from rockdesign.dynamics import compilation
from rockdesign.dynamics.engine import integrate


def test_kernels_of_each_command_exist_and_are_cacheable():
    for command, kernels in compilation.KERNELS.items():
        for module, name in kernels:
            d = compilation._dispatcher(module, name)
            assert d._cache is not None, f"{module}.{name} is not cache=True"
    # simulate never needs the parallel batch runner
    assert ("rockdesign.dynamics.batch", "_run_batch") not in compilation.KERNELS["simulate"]


def test_compiled_kernel_is_detected_as_cached():
    from rockdesign.dynamics.simulate import simulate
    from support import block_from_p
    simulate(block_from_p(2.0, 0.15), None, theta0=0.01, t_end=0.2)   # compiled or loaded from the cache
    assert compilation.is_cached(integrate)
    assert "rockdesign.dynamics.engine.integrate" not in compilation.missing_kernels("simulate")
    assert compilation.prepare("simulate", say=lambda s: (_ for _ in ()).throw(AssertionError(s))) == 0.0
    for command in compilation.KERNELS:      # the warm-up problems run (kernels loaded from the cache)
        compilation._warm(command)


def test_announcement_when_the_cache_is_empty(monkeypatch):
    said, warmed = [], []
    monkeypatch.delenv("ROCKDESIGN_NO_WARMUP", raising=False)
    monkeypatch.setattr(compilation, "is_cached", lambda d: False)
    monkeypatch.setattr(compilation, "_warm", lambda command: warmed.append(command))
    compilation.prepare("check", say=said.append)
    assert warmed == ["check"]
    assert said[0] == compilation.MESSAGE.format(seconds=compilation.ESTIMATE_SECONDS["check"])
    assert "once per installation" in said[0]
    assert said[1].startswith("compiled 5 kernels in")
    # unknown commands and the opt-out compile nothing
    assert compilation.prepare("init", say=said.append) == 0.0
    monkeypatch.setenv("ROCKDESIGN_NO_WARMUP", "1")
    assert compilation.prepare("check", say=said.append) == 0.0
    assert warmed == ["check"]
