"""Where numba keeps rockdesign's compiled kernels: a folder of the user's cache named by the kernels' digest.

numba (``cache=True``) keys a cached kernel on its own source file only: a kernel that inlines or calls
code of another file, or reads a constant imported from one, would keep the old machine code after that
file changes.  So rockdesign gives numba a cache folder of its own per version of the kernel sources::

    ~/.cache/rockdesign/kernels-<digest>/

where ``<digest>`` begins the SHA-256 of the sources that define kernels and of every rockdesign module
they import (:func:`sources_digest`).  An edit of any of them names another folder, so a stale kernel
cannot be loaded, and nothing is ever written into the installed package (a wheel's folder may be
read-only).  The folder's parent is, in this order: ``ROCKDESIGN_CACHE_DIR``; ``<NUMBA_CACHE_DIR>/rockdesign``
when the user set ``NUMBA_CACHE_DIR``; ``$XDG_CACHE_HOME/rockdesign``; ``~/.cache/rockdesign``
(``%LOCALAPPDATA%\\rockdesign\\Cache`` on Windows); a folder of the temporary directory when none of these
can be written.

:func:`use_kernel_cache` gives the folder to numba for rockdesign's kernels only, changing nothing for other
code: numba picks a kernel's cache folder when ``@njit(cache=True)`` decorates it, from its public
configuration ``numba.config.CACHE_DIR``, so each rockdesign module that defines kernels is executed with that
setting pointed at the folder and restored after (:func:`kernel_cache_in_use`, through an import finder for
``rockdesign.*`` modules).  ``os.environ`` is never changed: a notebook's own ``@njit(cache=True)`` functions
cache where its ``NUMBA_CACHE_DIR`` (or numba's default) says.  Processes started from this one (a process
pool, the local dask workers) import rockdesign and find the same folder.  A folder that cannot be used
(``~nosuchuser``, a name too long, another user's private folder) gives way to a temporary one, said once in a
:class:`KernelCacheWarning`, never an error at import.  The same digest stamps results.json
(``project.kernels_sha256``) and the report's Software table.
"""
from __future__ import annotations

import contextlib
import errno
import functools
import hashlib
import importlib.abc
import importlib.machinery
import os
import re
import sys
import tempfile
import threading
import warnings
from pathlib import Path

PACKAGE = Path(os.path.abspath(__file__)).parent
_KERNEL = re.compile(r"^[ \t]*@(?:numba\.)?njit\b", re.MULTILINE)
_RELATIVE_IMPORT = re.compile(r"^from[ \t]+(\.+)([\w.]*)[ \t]+import[ \t]+(\([^)]*\)|[^\n]*)", re.MULTILINE)
DIGEST_CHARS = 16
"""Hex characters of the digest in the folder's name (64 bits)."""


@functools.lru_cache(maxsize=1)
def kernel_sources() -> tuple[Path, ...]:
    """rockdesign's source files that define numba kernels (an ``@njit`` decorator), in a stable order."""
    return tuple(sorted(p for p in PACKAGE.rglob("*.py")
                        if _KERNEL.search(p.read_text(encoding="utf-8", errors="ignore"))))


def _imported_modules(path: Path) -> set[Path]:
    """The rockdesign modules a source imports at module level (``from .x import y`` at the start of a
    line, as rockdesign writes its imports; ``from . import eom`` too)."""
    found = set()
    for dots, module, names in _RELATIVE_IMPORT.findall(path.read_text(encoding="utf-8")):
        folder = path.parent
        for _ in range(len(dots) - 1):
            folder = folder.parent
        base = folder.joinpath(*module.split(".")) if module else folder
        names = re.sub(r"#[^\n]*", "", names).strip().strip("()")
        aliases = [n.split(" as ")[0].strip() for n in names.split(",")]
        for target in [base] + [base / name for name in aliases if name.isidentifier()]:
            for candidate in (target.with_suffix(".py"), target / "__init__.py"):
                if candidate.is_file():
                    found.add(candidate)
    return found


def digested_sources() -> list[Path]:
    """The kernel sources and every rockdesign module they import, transitively (numba freezes imported
    globals into the machine code: a constant of ``planar/dynamics/layout.py`` is part of the engine)."""
    seen = set(kernel_sources())
    todo = list(seen)
    while todo:
        for module in _imported_modules(todo.pop()):
            if module not in seen:
                seen.add(module)
                todo.append(module)
    return sorted(seen)


@functools.lru_cache(maxsize=1)
def sources_digest() -> str:
    """SHA-256 over the digested sources (paths relative to the package, and contents); read once per process."""
    h = hashlib.sha256()
    for p in digested_sources():
        h.update(str(p.relative_to(PACKAGE)).encode())
        h.update(p.read_bytes())
    return h.hexdigest()


def folder_name() -> str:
    """The kernel cache folder's name: ``kernels-`` and the first :data:`DIGEST_CHARS` of :func:`sources_digest`."""
    return f"kernels-{sources_digest()[:DIGEST_CHARS]}"


CACHE_VARIABLES = ("ROCKDESIGN_CACHE_DIR", "NUMBA_CACHE_DIR", "XDG_CACHE_HOME")
"""The environment variables that choose the kernel cache's parent folder (module docstring)."""


class KernelCacheWarning(RuntimeWarning):
    """The kernel cache folder asked for cannot be used; a temporary folder is used instead (said once)."""


_WARNED: set[str] = set()


def _user_cache_root() -> tuple[Path, str]:
    """The parent of the kernel cache folder and what chose it (a variable, or "your home folder").  Raises
    RuntimeError when ``~`` names no home folder (``~nosuchuser/…``)."""
    if os.environ.get("ROCKDESIGN_CACHE_DIR"):
        return Path(os.environ["ROCKDESIGN_CACHE_DIR"]).expanduser(), "ROCKDESIGN_CACHE_DIR"
    if os.environ.get("NUMBA_CACHE_DIR"):
        return Path(os.environ["NUMBA_CACHE_DIR"]).expanduser() / "rockdesign", "NUMBA_CACHE_DIR"
    if sys.platform == "win32" and os.environ.get("LOCALAPPDATA"):
        return Path(os.environ["LOCALAPPDATA"]) / "rockdesign" / "Cache", "LOCALAPPDATA"
    xdg = os.environ.get("XDG_CACHE_HOME")
    if xdg and os.path.isabs(xdg):
        return Path(xdg) / "rockdesign", "XDG_CACHE_HOME"
    return Path.home() / ".cache" / "rockdesign", "the home folder"


def _writable(folder: Path) -> bool:
    """Whether ``folder`` can be created or written (its nearest existing ancestor is writable); nothing is
    written.  Raises OSError when the path cannot even be looked at (a name too long, a folder that cannot be
    read on the way)."""
    for candidate in (folder, *folder.parents):
        if candidate.exists():
            return candidate.is_dir() and os.access(candidate, os.W_OK | os.X_OK)
    return False


def _problem(exc: BaseException) -> str:
    if isinstance(exc, RuntimeError):           # Path.expanduser: "Could not determine home directory"
        return "its ~ names no home folder on this machine"
    number = getattr(exc, "errno", None)
    if number == errno.ENAMETOOLONG:
        return "a name too long for the file system (Errno 36)"
    if number in (errno.EACCES, errno.EPERM):
        return "a folder on the way cannot be read (Errno 13)"
    return str(exc)


def kernel_cache_dir() -> Path:
    """The folder numba caches rockdesign's kernels in (see the module's docstring for the search order).  A
    folder that cannot be used — ``~nosuchuser/…``, a name too long, inside another user's private folder,
    read-only — gives way to a folder of the temporary directory, with one :class:`KernelCacheWarning` per
    process saying why; never an exception."""
    numba_dir = os.environ.get("NUMBA_CACHE_DIR")
    try:
        if numba_dir and Path(numba_dir).name == folder_name():   # set by a process that started this one
            return Path(numba_dir)
        root, chosen_by = _user_cache_root()
        folder = root / folder_name()
        if _writable(folder):
            return folder
        problem = "it cannot be written"
    except (RuntimeError, OSError) as exc:
        root, chosen_by = None, next((v for v in CACHE_VARIABLES if os.environ.get(v)), "the home folder")
        problem = _problem(exc)
    fallback = Path(tempfile.gettempdir()) / f"rockdesign-{_user_id()}" / folder_name()
    given = os.environ.get(chosen_by)
    what = f"{chosen_by}={given!r}" if given else f"the kernel cache under {chosen_by} ({root})"
    message = (f"rockdesign cannot keep its compiled kernels where {what} says: {problem}; they are kept in "
               f"{fallback} instead (set ROCKDESIGN_CACHE_DIR to a folder you can write)")
    if message not in _WARNED:
        _WARNED.add(message)
        warnings.warn(message, KernelCacheWarning, stacklevel=2)
    return fallback


def _user_id() -> str:
    try:
        return str(os.getuid())
    except AttributeError:                # Windows
        return os.environ.get("USERNAME", "user")


# --- numba's configuration for rockdesign's kernels only ---------------------------------------------------
_LOCK = threading.RLock()
_DEPTH = [0, None]            # nesting depth of kernel_cache_in_use(), the configuration it replaced


@contextlib.contextmanager
def kernel_cache_in_use():
    """numba's cache folder (``numba.config.CACHE_DIR``) set to :func:`kernel_cache_dir` inside, the user's
    setting restored after.  numba picks a kernel's cache folder when ``@njit(cache=True)`` decorates it, so
    rockdesign's kernel modules are executed inside (:class:`KernelModuleFinder`): a notebook's own kernels,
    decorated outside, cache where the user's configuration says, and ``os.environ`` is never changed."""
    import numba
    config = numba.config
    with _LOCK:
        if _DEPTH[0] == 0:
            _DEPTH[1] = config.CACHE_DIR
            config.CACHE_DIR = str(kernel_cache_dir())
        _DEPTH[0] += 1
    try:
        yield
    finally:
        with _LOCK:
            _DEPTH[0] -= 1
            if _DEPTH[0] == 0:
                config.CACHE_DIR = _DEPTH[1]


def launch_numba_threads() -> None:
    """Start numba's threads with GNU OpenMP waiting passively (sleeping, not spinning: on a shared machine a
    spinning thread burns the CPU time the analyses need; docs/engine.md, "Threads"), leaving ``os.environ`` as
    it was.  OpenMP reads ``OMP_WAIT_POLICY`` once, when numba loads it; a value the user set is kept, and
    threads the user's code started before are used as they are."""
    import numba
    with _LOCK:
        added = "OMP_WAIT_POLICY" not in os.environ
        if added:
            os.environ["OMP_WAIT_POLICY"] = "passive"
        try:
            numba.get_num_threads()         # launches numba's thread pool (the OpenMP library loads here)
        finally:
            if added:
                os.environ.pop("OMP_WAIT_POLICY", None)


class _KernelModuleLoader(importlib.machinery.SourceFileLoader):
    """Executes a rockdesign module that defines kernels inside :func:`kernel_cache_in_use`."""

    def exec_module(self, module) -> None:
        launch_numba_threads()
        with kernel_cache_in_use():
            super().exec_module(module)


class KernelModuleFinder(importlib.abc.MetaPathFinder):
    """Finds rockdesign's modules as Python does and hands those that define kernels (an ``@njit`` decorator)
    to :class:`_KernelModuleLoader`; every other module, of rockdesign or not, is left to Python."""

    def find_spec(self, fullname, path, target=None):
        if not fullname.startswith("rockdesign."):
            return None
        spec = importlib.machinery.PathFinder.find_spec(fullname, path, target)
        if spec is None or not isinstance(spec.loader, importlib.machinery.SourceFileLoader) or not spec.origin:
            return spec
        try:
            source = Path(spec.origin).read_text(encoding="utf-8", errors="ignore")
        except OSError:
            return spec
        if _KERNEL.search(source):
            spec.loader = _KernelModuleLoader(fullname, spec.origin)
        return spec


def use_kernel_cache() -> None:
    """Let rockdesign's kernels reach their cache folder (:func:`kernel_cache_dir`) through numba's public
    configuration, for rockdesign's kernels only: a finder for rockdesign's modules (first in ``sys.meta_path``,
    answering for ``rockdesign.*`` alone) executes each module that defines kernels inside
    :func:`kernel_cache_in_use`.  Nothing is imported (numba neither), written or set in ``os.environ``; called
    by ``import rockdesign`` before any module with a kernel is imported."""
    if not any(isinstance(f, KernelModuleFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, KernelModuleFinder())
