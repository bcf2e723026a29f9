"""The progress bars of the check's stages (rockdesign/progress.py)."""
import io
import time

from rich.console import Console
from rich.progress import Progress

from rockdesign.progress import progress_bars


def test_a_new_stage_stops_the_clock_of_the_earlier_ones(monkeypatch):
    """Stages run one after another.  A stage whose counter stops short of its total (the margin scan
    ends early for most records) must show its own time, not count on until the last stage ends."""
    captured = {}
    original = Progress.__exit__

    def keep(self, *exc):
        captured["tasks"] = list(self.tasks)
        return original(self, *exc)

    monkeypatch.setattr(Progress, "__exit__", keep)
    with progress_bars(Console(file=io.StringIO(), force_terminal=True)) as progress:    # bars: a terminal
        progress("scan", 0, 10)
        progress("scan", 4, 10)                  # the scan ended early
        progress("next stage", 0, 1)
        time.sleep(0.5)
        progress("next stage", 1, 1)
    scan, following = captured["tasks"]
    assert scan.finished and scan.completed == 10           # every bar is shown complete
    assert scan.finished_time < 0.25 and following.finished_time >= 0.5


def test_bench_shows_its_stages():
    """`bench` runs for minutes: it shows a bar per stage (problems, stability cases), not only -v lines.  The
    command's plain stage lines off a terminal are checked on its first run (tests/cli/test_first_run.py, which
    runs the same command once); here the stability study's steps."""
    from rockdesign.bench.stability import run_stability
    steps = []
    run_stability(quick=True, keys=["missed-events", "event-location-crash"],
                  step=lambda done, total: steps.append((done, total)))
    assert steps == [(0, 2), (1, 2), (2, 2)]
