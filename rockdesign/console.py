"""The one place rockdesign creates rich consoles (the CLI, progress bars, tables)."""
from __future__ import annotations

from rich.console import Console


def make_console(**options) -> Console:
    """A rich console that prints text verbatim: emoji codes are never replaced (``omega_p/p:-1:8:5`` would
    otherwise show a thumbs-down for ``:-1:``).  Markup stays on where a caller asks for it; user text
    printed with markup goes through :func:`rich.markup.escape`.  ``options`` are rich's."""
    options.setdefault("emoji", False)
    return Console(**options)
