"""Validation of command-line options before any work is done (the project file is validated in
:mod:`rockdesign.planar.project`).

Every check raises a :class:`~rockdesign.errors.RockdesignError` naming the option, what was expected
and what was found, so the CLI prints one line and exits with code 2 — never a traceback after
minutes of analysis.  Output files are checked before the analysis runs: a bad suffix, a missing
folder or a path that is a directory fails at once.
"""
from __future__ import annotations

import contextlib
import errno
import math
from pathlib import Path

from typer.core import TyperGroup

from ..console import make_console
from ..errors import RockdesignError
from .. import refuse_wrong_type

FIGURE_SUFFIXES = (".png", ".svg", ".pdf")
RTOL_RANGE = (0.0, 1e-3)
"""rtol must be in (0, 1e-3]: the engine's events and margins need at least 1e-3 (as ``[analysis] rtol``)."""


def positive_time(value: float | None, key: str) -> float | None:
    """A finite time > 0 [s] (or None)."""
    if value is None:
        return None
    if not (math.isfinite(value) and value > 0.0):
        raise RockdesignError("out of range", key=key, expected="a finite time > 0 in seconds", found=repr(value))
    return value


def rtol(value: float | None, key: str = "--rtol") -> float | None:
    """Relative tolerance in (0, 1e-3] (or None for the project's)."""
    if value is None:
        return None
    lo, hi = RTOL_RANGE
    if not (math.isfinite(value) and lo < value <= hi):
        raise RockdesignError("out of range", key=key, expected=f"a relative tolerance > {lo:g} and ≤ {hi:g} "
                              "(e.g. 1e-10)", found=repr(value))
    return value


def _expanded(path, key: str) -> Path:
    """``~`` expanded, or an input error naming ``key`` when ``~user`` names no user of this machine."""
    try:
        return Path(path).expanduser()
    except RuntimeError:            # "Could not determine home directory"
        raise RockdesignError(f"'{str(path).split('/', 1)[0]}' names no home folder on this machine", key=key,
                              expected="a path whose ~user is a user of this machine (or a path without ~)",
                              found=repr(str(path))) from None


@contextlib.contextmanager
def _path_errors(key: str, path: Path):
    """A name too long (Errno 36) or a folder that cannot be read (Errno 13) is an input error naming ``key``."""
    try:
        yield
    except OSError as exc:
        if exc.errno not in (errno.ENAMETOOLONG, errno.EACCES, errno.EPERM, errno.ELOOP):
            raise
        text = str(path) if len(str(path)) <= 120 else f"{str(path)[:60]}…{str(path)[-40:]} ({len(str(path))} characters)"
        raise RockdesignError("cannot use the path", key=key, expected="a path the file system accepts (names up "
                              "to 255 bytes), through folders you may read", found=f"'{text}': {_PATH_PROBLEMS.get(exc.errno, exc.strerror)}") from None


_PATH_PROBLEMS = {errno.ENAMETOOLONG: "a file name too long for the file system (Errno 36)",
                  errno.EACCES: "no permission to read a folder on the way (Errno 13)",
                  errno.EPERM: "no permission to read a folder on the way (Errno 13)",
                  errno.ELOOP: "a loop of symbolic links (Errno 40)"}
"""The words of rockdesign.paths.path_problem (the command line imports only the public library)."""


def output_file(path: Path | None, key: str, suffixes: tuple[str, ...] | None = None) -> Path | None:
    """A file we can create: known suffix, not a directory, in an existing folder."""
    if path is None:
        return None
    path = _expanded(path, key)
    with _path_errors(key, path):
        return _output_file(path, key, suffixes)


def _output_file(path: Path, key: str, suffixes: tuple[str, ...] | None) -> Path:
    if suffixes is not None and path.suffix.lower() not in suffixes:
        raise RockdesignError("unknown file type", key=key, expected="a file ending in " + ", ".join(suffixes),
                              found=f"'{path}'")
    if path.is_dir():
        raise RockdesignError("is a directory", key=key, expected="a file name", found=f"'{path}' (a directory)")
    refuse_wrong_type(path, key, folder=False)
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise RockdesignError("folder not found", key=key, expected="a file in an existing folder",
                              found=f"'{path}' ('{parent}' does not exist)")
    return path


def output_folder(path: Path, key: str) -> Path:
    """A folder we can write into (created if missing): not an existing file, parent not a file."""
    path = _expanded(path, key)
    with _path_errors(key, path):
        return _output_folder(path, key)


def _output_folder(path: Path, key: str) -> Path:
    if path.is_symlink():
        refuse_wrong_type(path, key, folder=True)
    if path.exists() and not path.is_dir():
        raise RockdesignError("is a file, not a folder", key=key, expected="a folder (new or existing)",
                              found=f"'{path}' (an existing file)")
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise RockdesignError("cannot create folder", key=key, expected="a path below an existing folder",
                                      found=f"'{parent}' is a file")
            break
    return path


def repeated_option(command, args: list[str]) -> None:
    """Refuse an option given twice (``--table a=1 --table a=2``: click would keep the last silently);
    options declared repeatable (``--equivalent-at``) may repeat."""
    spelled: dict[str, object] = {}
    takes_value: dict[str, bool] = {}
    for param in getattr(command, "params", []):
        if getattr(param, "param_type_name", "") != "option" or getattr(param, "multiple", False) \
                or getattr(param, "count", False):
            continue
        for flag in [*param.opts, *param.secondary_opts]:
            spelled[flag] = param
            takes_value[flag] = not param.is_flag
    seen: dict[object, str] = {}
    k = 0
    while k < len(args) and args[k] != "--":
        token = args[k]
        flag = token.split("=", 1)[0] if token.startswith("--") else token
        param = spelled.get(flag)
        width = 2 if param is not None and takes_value[flag] and "=" not in token else 1
        if param is not None:
            shown = " ".join(args[k:k + width])
            if param in seen:
                raise RockdesignError("option given twice (only one value would be used)", key=flag,
                                      expected="/".join([*param.opts, *param.secondary_opts]) + " once",
                                      found=f"'{seen[param]}' and '{shown}'")
            seen[param] = shown
        k += width


class OptionsOnce(TyperGroup):
    """The command groups of the CLI: an option of a command given twice is an input error (exit 2)."""

    def resolve_command(self, ctx, args):
        name, command, rest = super().resolve_command(ctx, args)
        if command is not None and not isinstance(command, TyperGroup):
            try:
                repeated_option(command, rest)
            except RockdesignError as exc:
                from rich.markup import escape
                make_console(stderr=True).print(f"[bold red]error:[/] {escape(str(exc))}", highlight=False,
                                           soft_wrap=True)
                ctx.exit(2)
        return name, command, rest
