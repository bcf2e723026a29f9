"""The command line (``rockdesign …``): typer commands that parse options, call the library and print.

:mod:`.app` holds the typer application, the error handling and exit codes and the project commands
(``init``, ``quantities``, ``simulate``); every other command lives in its own module
(:mod:`.check`, :mod:`.records`, :mod:`.spectrum`, :mod:`.experiments`, :mod:`.bench`) and is
mounted by :mod:`.app`.  ``rockdesign = rockdesign.cli:main`` is the console-script entry point.
"""
from .app import app, main

__all__ = ["app", "main"]
