"""Where rockdesign finds its data: the bundled records and suites, templates, and ../shared.

The built-in record sets, suite manifests and the report/project templates live at the top of the
checkout (``ground_motions/`` and ``templates/``).  The wheel carries them as package data
(``rockdesign/data/ground_motions`` and ``rockdesign/data/templates``, mapped by the build backend),
so :func:`data_dir` looks in the installed package first and then in the checkout beside the
package: an installed wheel, an editable install and a plain checkout all go through that one lookup,
and every command works from any directory.  ``ROCKDESIGN_GROUND_MOTIONS`` /
``ROCKDESIGN_TEMPLATES`` point rockdesign at other folders.
"""
from __future__ import annotations

import errno
import os
from contextlib import contextmanager
from importlib import resources
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
REPO_ROOT = PACKAGE_DIR.parent
"""The folder above the package: the checkout's root in a source tree (site-packages when installed)."""


def data_dir(name: str) -> Path:
    """The folder of built-in data ``name`` (``ground_motions`` | ``templates``): the installed wheel's
    package data (``rockdesign/data/NAME``, found by :mod:`importlib.resources`), else the checkout's
    top-level folder ``NAME`` beside the package (editable install or plain checkout)."""
    folder = resources.files("rockdesign") / "data" / name
    if isinstance(folder, Path) and folder.is_dir():
        return folder
    checkout = REPO_ROOT / name
    if checkout.is_dir() and (PACKAGE_DIR / "__init__.py").is_file():
        return checkout
    raise RuntimeError(f"rockdesign's built-in data '{name}' was found neither in the package ({folder}) "
                       f"nor in the checkout ({checkout})")


def ground_motions_dir() -> Path:
    """Folder of the built-in record sets and suite manifests (``ground_motions/`` of the checkout, package data in the wheel)."""
    env = os.environ.get("ROCKDESIGN_GROUND_MOTIONS")
    return Path(env) if env else data_dir("ground_motions")


def templates_dir() -> Path:
    """Folder of the report and project templates (``templates/`` of the checkout, package data in the wheel)."""
    env = os.environ.get("ROCKDESIGN_TEMPLATES")
    return Path(env) if env else data_dir("templates")


def shared_dir() -> Path | None:
    """``../shared`` beside the checkout (staged accelerograms for tests and benchmarks), if present.

    ``ROCKDESIGN_SHARED`` overrides the search; set it to a folder without ``SPEC.md`` (e.g.
    ``/nonexistent``) to run the tests as in a clean clone.
    """
    env = os.environ.get("ROCKDESIGN_SHARED")
    if env:
        return Path(env) if (Path(env) / "SPEC.md").exists() else None
    for c in (REPO_ROOT.parent / "shared", REPO_ROOT.parent.parent / "shared"):
        if (c / "SPEC.md").exists():
            return c
    return None


# --- paths the user gives -------------------------------------------------------------------------------
def require_path(value, key: str, what: str = "a file name") -> None:
    """Refuse a path argument that is not text or a path (``rd.load_project(None)``, ``out_dir=123``) or is
    blank, naming the parameter ``key``."""
    from .errors import ProjectError
    if isinstance(value, bool) or not isinstance(value, (str, os.PathLike)) or \
            (isinstance(value, str) and not value.strip()):
        raise ProjectError("not a path", key=key, expected=f"{what} (a string or a pathlib.Path)",
                           found=f"{value!r} ({type(value).__name__})")


def expand_user(path, key: str | None, *, file: str | None = None, error=None) -> Path:
    """``Path(path).expanduser()``, or an input error naming ``key`` (and ``file``) when ``~user`` names no
    user of this machine or there is no home folder (Python raises RuntimeError "Could not determine home
    directory").  ``error``: the error class (default :class:`~rockdesign.errors.ProjectError`)."""
    from .errors import ProjectError
    try:
        return Path(path).expanduser()
    except RuntimeError:
        text = str(path)
        user = text.split("/", 1)[0].split(os.sep, 1)[0]
        raise (error or ProjectError)(
            f"'{user}' names no home folder on this machine", file=file, key=key,
            expected="a path whose ~user is a user of this machine (or a path without ~)",
            found=repr(text)) from None


def path_problem(exc: OSError) -> str:
    """A path's OS error in words (a name too long, no permission, …), for messages."""
    if exc.errno == errno.ENAMETOOLONG:
        return "a file name too long for the file system (Errno 36)"
    if exc.errno in (errno.EACCES, errno.EPERM):
        return "no permission to read a folder on the way (Errno 13)"
    if exc.errno == errno.ELOOP:
        return "a loop of symbolic links (Errno 40)"
    return exc.strerror or str(exc)


PATH_ERRNOS = frozenset({errno.ENAMETOOLONG, errno.EACCES, errno.EPERM, errno.ELOOP})
"""OS errors of a path the user gave, not of rockdesign: ENAMETOOLONG, EACCES, EPERM, ELOOP."""


@contextmanager
def user_path_errors(key: str | None, path, *, file: str | None = None, error=None):
    """Inside, an OS error that a user's path causes (a name too long, a folder that cannot be read, a loop of
    symbolic links) becomes an input error naming ``key`` (and ``file``) and the path."""
    from .errors import ProjectError
    try:
        yield
    except OSError as exc:
        if exc.errno not in PATH_ERRNOS:
            raise
        raise (error or ProjectError)(
            "cannot use the path", file=file, key=key,
            expected="a path the file system accepts (names up to 255 bytes), through folders you may read",
            found=f"{_shown(path)}: {path_problem(exc)}") from None


def _shown(path) -> str:
    text = str(path)
    return repr(text if len(text) <= 120 else text[:60] + "…" + text[-40:] + f" ({len(text)} characters)")


def user_path(text, key: str | None, *, file: str | None = None, base: Path | None = None, error=None) -> Path:
    """A path the user gave (a project key, an option): ``~`` expanded (:func:`expand_user`), joined to ``base``
    when relative, and probed, so that a name too long or an unreadable folder is an input error naming ``key``
    (:func:`user_path_errors`) rather than an OSError later."""
    path = expand_user(text, key, file=file, error=error)
    if base is not None and not path.is_absolute():
        path = base / path
    with user_path_errors(key, path, file=file, error=error):
        path.exists()
    return path
