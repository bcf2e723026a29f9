"""Progress of long work on stderr: rich bars in a terminal or a notebook, plain lines elsewhere.

When stderr is not a terminal (CI, a log file, a pipe) a progress bar would only be drawn once, at
the end, so the user would see nothing while the work runs.  There each stage prints plain lines
instead: when it starts, every :data:`PLAIN_INTERVAL` seconds while it runs, and when it ends.
"""
from __future__ import annotations

import contextlib
import time
from collections.abc import Callable, Iterator

from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from .console import make_console

PLAIN_INTERVAL = 10.0
"""Seconds between two plain progress lines of one stage (non-terminal stderr)."""


def _is_live(console: Console) -> bool:
    """True when the console redraws in place (a terminal or a notebook)."""
    return console.is_terminal or bool(getattr(console, "is_jupyter", False))


class _PlainStages:
    """``progress(stage, done, total)`` printing one line per stage start, one every
    :data:`PLAIN_INTERVAL` seconds and one when the stage ends (the next stage starts or all end)."""

    def __init__(self, console: Console, interval: float = PLAIN_INTERVAL):
        self.console, self.interval = console, interval
        self.stage: str | None = None
        self.done = self.total = 0
        self.t0 = self.last = 0.0

    def _say(self, text: str) -> None:
        self.console.print(text, highlight=False, soft_wrap=True)

    def _end(self) -> None:
        if self.stage is not None:
            count = f"{self.total}/{self.total} " if self.total > 1 else ""
            self._say(f"{self.stage}: {count}done in {time.perf_counter() - self.t0:.0f} s")
        self.stage = None

    def note(self, text: str) -> None:
        """A line of its own while a stage runs (e.g. why it is slow)."""
        self._say(text)

    def __call__(self, stage: str, done: int, total: int) -> None:
        now = time.perf_counter()
        if stage != self.stage:
            self._end()
            self.stage, self.t0, self.last = stage, now, now
            self._say(f"{stage}: {total} to do" if total > 1 else f"{stage} …")
        self.done, self.total = min(done, total), total
        if now - self.last >= self.interval and self.done < total:
            self.last = now
            self._say(f"{stage}: {self.done}/{total} ({now - self.t0:.0f} s)")


@contextlib.contextmanager
def progress_bars(console: Console | None = None, *, disable: bool = False) -> Iterator[Callable[[str, int, int], None]]:
    """Yield ``progress(stage, done, total)``: one bar per stage, every bar shown complete at the end; plain
    lines (see module docstring) when ``console`` (default: stderr) is not a terminal."""
    console = console or make_console(stderr=True)
    if not disable and not _is_live(console):
        plain = _PlainStages(console)
        yield plain
        plain._end()
        return
    bar = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                   console=console, transient=False, disable=disable)
    tasks: dict[str, int] = {}

    def progress(stage: str, done: int, total: int) -> None:
        if stage not in tasks:
            # stages run one after another: a new stage ends the earlier ones, so their clocks stop (a scan
            # that ends early, e.g. the margins', would otherwise count on until the last stage ends)
            for t in tasks.values():
                bar.update(t, completed=bar.tasks[t].total)
            tasks[stage] = bar.add_task(escape(stage), total=total)   # user text (names, ids) verbatim
        bar.update(tasks[stage], completed=min(done, total), total=total)

    # a line printed above the bars while a stage runs (e.g. why it is slow)
    progress.note = lambda text: bar.console.print(escape(text), highlight=False, soft_wrap=True)

    with bar:
        yield progress
        for t in tasks.values():
            bar.update(t, completed=bar.tasks[t].total)


@contextlib.contextmanager
def working(text: str, console: Console | None = None) -> Iterator[None]:
    """A spinner with ``text`` in a terminal, elsewhere a plain line ``text …``; at the end a line saying how
    long it took (work without a count, e.g. writing the report)."""
    console = console or make_console(stderr=True)
    t0 = time.perf_counter()
    if _is_live(console):
        with console.status(text):
            yield
    else:
        console.print(f"{text} …", highlight=False, soft_wrap=True)
        yield
    console.print(f"{text}: done in {time.perf_counter() - t0:.0f} s", highlight=False, soft_wrap=True)
