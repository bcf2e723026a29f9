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

:func:`use_kernel_cache` sets it through numba's public configuration (``NUMBA_CACHE_DIR`` in the
environment, and ``numba.config.CACHE_DIR`` when numba is already imported).  ``import rockdesign`` calls
it, before any module with a kernel is imported (numba picks a kernel's cache folder when the kernel is
defined); processes started from this one (a process pool, the local dask workers) inherit the folder.
The same digest stamps results.json (``project.kernels_sha256``) and the report's Software table.
"""
from __future__ import annotations

import functools
import hashlib
import os
import re
import sys
import tempfile
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


def _user_cache_root() -> Path:
    if os.environ.get("ROCKDESIGN_CACHE_DIR"):
        return Path(os.environ["ROCKDESIGN_CACHE_DIR"]).expanduser()
    if os.environ.get("NUMBA_CACHE_DIR"):
        return Path(os.environ["NUMBA_CACHE_DIR"]).expanduser() / "rockdesign"
    if sys.platform == "win32" and os.environ.get("LOCALAPPDATA"):
        return Path(os.environ["LOCALAPPDATA"]) / "rockdesign" / "Cache"
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg) if xdg and os.path.isabs(xdg) else Path.home() / ".cache"
    return base / "rockdesign"


def _writable(folder: Path) -> bool:
    """Whether ``folder`` can be created or written (its nearest existing ancestor is writable); nothing is written."""
    for candidate in (folder, *folder.parents):
        if candidate.exists():
            return candidate.is_dir() and os.access(candidate, os.W_OK | os.X_OK)
    return False


def kernel_cache_dir() -> Path:
    """The folder numba caches rockdesign's kernels in (see the module's docstring for the search order)."""
    numba_dir = os.environ.get("NUMBA_CACHE_DIR")
    if numba_dir and Path(numba_dir).name == folder_name():   # set by the process that started this one
        return Path(numba_dir)
    folder = _user_cache_root() / folder_name()
    if _writable(folder):
        return folder
    return Path(tempfile.gettempdir()) / f"rockdesign-{_user_id()}" / folder_name()


def _user_id() -> str:
    try:
        return str(os.getuid())
    except AttributeError:                # Windows
        return os.environ.get("USERNAME", "user")


def use_kernel_cache() -> Path:
    """Point numba's cache (``NUMBA_CACHE_DIR``, ``numba.config.CACHE_DIR``) at :func:`kernel_cache_dir` and
    return it.  Call before a module with a kernel is imported; nothing is written (numba creates the folder
    when it first stores a kernel), and numba is not imported."""
    folder = kernel_cache_dir()
    os.environ["NUMBA_CACHE_DIR"] = str(folder)
    numba = sys.modules.get("numba")
    if numba is not None and hasattr(numba, "config"):
        numba.config.CACHE_DIR = str(folder)
    return folder
