"""Progress when stderr is not a terminal (CI, a log file): plain lines while the work runs — a line when
a stage starts, one every PLAIN_INTERVAL seconds, one when it ends — instead of bars drawn once at the end."""
from __future__ import annotations

import io

from rich.console import Console

from rockdesign import progress as progress_module
from rockdesign.progress import progress_bars, working


def _console() -> tuple[Console, io.StringIO]:
    out = io.StringIO()
    return Console(file=out, force_terminal=False, width=200), out


def test_plain_lines_per_stage(monkeypatch):
    console, out = _console()
    clock = iter([0.0, 4.0, 12.0, 13.0, 13.0, 13.0, 20.0])   # one reading per call, one per stage end
    monkeypatch.setattr(progress_module.time, "perf_counter", lambda: next(clock))
    with progress_bars(console) as tick:
        tick("suite analysis (RHA)", 0, 44)
        assert out.getvalue() == "suite analysis (RHA): 44 to do\n"     # printed at once, not at the end
        tick("suite analysis (RHA)", 10, 44)       # 4 s: nothing new
        tick("suite analysis (RHA)", 30, 44)       # 12 s ≥ 10 s: a line
        tick("suite analysis (RHA)", 44, 44)
        tick("writing the suite", 0, 1)            # a new stage ends the last one
    lines = out.getvalue().splitlines()
    assert lines == ["suite analysis (RHA): 44 to do", "suite analysis (RHA): 30/44 (12 s)",
                     "suite analysis (RHA): 44/44 done in 13 s", "writing the suite …",
                     "writing the suite: done in 7 s"]


def test_working_prints_a_line_before_and_after():
    console, out = _console()
    with working("writing the results and calculation report (figures, PDF)", console):
        assert out.getvalue() == "writing the results and calculation report (figures, PDF) …\n"
    assert out.getvalue().splitlines()[-1].startswith("writing the results and calculation report (figures, PDF): "
                                                      "done in ")


def test_terminal_keeps_the_bars():
    out = io.StringIO()
    console = Console(file=out, force_terminal=True, width=100)
    with progress_bars(console) as tick:
        tick("suite analysis (RHA)", 44, 44)
    assert "44/44" in out.getvalue() and "to do" not in out.getvalue()
