"""Progress bars for long work (rich): the design check's stages, in a terminal or a notebook."""
from __future__ import annotations

import contextlib

from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from .console import make_console


@contextlib.contextmanager
def progress_bars(console: Console | None = None, *, disable: bool = False):
    """Yield ``progress(stage, done, total)``: one bar per stage; every bar shown complete at the end."""
    bar = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                   console=console or make_console(stderr=True), transient=False, disable=disable)
    tasks: dict[str, int] = {}

    def progress(stage: str, done: int, total: int) -> None:
        if stage not in tasks:
            # stages run one after another: a new stage ends the earlier ones, so their clocks stop (a scan
            # that ends early, e.g. the margins', would otherwise count on until the last stage ends)
            for t in tasks.values():
                bar.update(t, completed=bar.tasks[t].total)
            tasks[stage] = bar.add_task(escape(stage), total=total)   # user text (names, ids) verbatim
        bar.update(tasks[stage], completed=min(done, total), total=total)

    with bar:
        yield progress
        for t in tasks.values():
            bar.update(t, completed=bar.tasks[t].total)
