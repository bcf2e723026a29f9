"""Keep numba's on-disk cache consistent with the kernel sources.

numba (``cache=True``) keys a cached function on its own source file only: a kernel that inlines or
calls code of another file, or reads a constant imported from one, keeps the old machine code after
that file changes.  On import of the numerical packages (in any process: the CLI, a process pool, a
dask worker), :func:`refresh_stale_caches` digests the kernel sources and the rockdesign modules
they import, and compares the digest with the stamp kept inside each cache folder numba uses for
rockdesign's kernels in this process: a source folder's ``__pycache__``, or, with
``NUMBA_CACHE_DIR`` set (or a read-only installation), the folder numba names
``<folder name>_<sha1 of the folder's absolute path>`` under that directory (or the user-wide
cache).  Where the stamp differs, it deletes the cached kernels of rockdesign's modules in that
folder (``*.nbi``, ``*.nbc``), so that they are compiled afresh from the current sources, and
writes the new stamp there.  Nothing else is deleted.
"""
from __future__ import annotations

import ast
import functools
import hashlib
import os
import re
import types
import warnings
from pathlib import Path

PACKAGE = Path(os.path.abspath(__file__)).parent   # as numba spells it (abspath, symlinks kept)
STAMP_NAME = "rockdesign-kernels.sha256"
"""The stamp's file name, inside each cache folder it describes."""
_KERNEL = re.compile(r"^[ \t]*@(?:numba\.)?njit\b", re.MULTILINE)


@functools.lru_cache(maxsize=1)
def kernel_sources() -> tuple[Path, ...]:
    """rockdesign's source files that define numba kernels (an ``@njit`` decorator), in a stable order."""
    return tuple(sorted(p for p in PACKAGE.rglob("*.py")
                        if _KERNEL.search(p.read_text(encoding="utf-8", errors="ignore"))))


def _imported_modules(path: Path) -> set[Path]:
    """The rockdesign modules a source imports at module level (relative imports, as rockdesign writes them)."""
    found = set()
    for node in ast.parse(path.read_bytes()).body:
        if not (isinstance(node, ast.ImportFrom) and node.level):
            continue
        folder = path.parent
        for _ in range(node.level - 1):
            folder = folder.parent
        base = folder.joinpath(*node.module.split(".")) if node.module else folder
        for target in [base] + [base / alias.name for alias in node.names]:   # ``from . import eom`` too
            for candidate in (target.with_suffix(".py"), target / "__init__.py"):
                if candidate.is_file():
                    found.add(candidate)
    return found


def digested_sources() -> list[Path]:
    """The kernel sources and every rockdesign module they import, transitively (numba freezes imported
    globals into the machine code: a constant of ``dynamics/layout.py`` is part of the engine)."""
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


def _probe():
    """Stands in for a kernel of a given source file when asking numba where it caches that file."""


def cache_folders() -> dict[Path, Path]:
    """Source folder holding kernels → the folder numba caches its kernels in, in this process.

    numba's own cache locators answer (``NUMBA_CACHE_DIR``, the in-tree ``__pycache__``, the user-wide
    cache, in numba's order).  A folder is listed only if it holds that source folder's kernels alone
    (``__pycache__`` beside the sources, or numba's ``<name>_<sha1 of the path>`` subfolder)."""
    # numba is imported here, not at module top: sources_digest() serves reports and results.json in
    # processes that need no kernel (the PDF worker), and importing numba costs 0.3-1.0 s (-X importtime)
    from numba.core.caching import CompileResultCacheImpl
    out = {}
    for source in kernel_sources():
        folder = source.parent
        if folder in out:
            continue
        probe = types.FunctionType(_probe.__code__.replace(co_filename=str(source)), {})
        try:
            cache = Path(CompileResultCacheImpl(probe).locator.get_cache_path())
        except (RuntimeError, OSError):   # no writable cache location: numba compiles in memory
            continue
        own_name = f"{folder.name}_{hashlib.sha1(str(folder).encode()).hexdigest()}"
        if cache == folder / "__pycache__" or cache.name == own_name:
            out[folder] = cache
    return out


def kernel_cache_files(folder: Path, cache: Path) -> list[Path]:
    """numba's cache files (``<module>.<function>-<line>.pyXY.nbi`` and ``….nbc``) of the modules of
    ``folder`` found in ``cache``."""
    modules = {p.stem for p in folder.glob("*.py")}
    return sorted(f for pattern in ("*.nbi", "*.nbc") for f in cache.glob(pattern)
                  if f.name.split(".", 1)[0] in modules)


def _write_stamp(cache: Path, digest: str) -> None:
    """Write the stamp atomically (several processes may refresh at once)."""
    temporary = cache / f".{STAMP_NAME}.{os.getpid()}.tmp"
    temporary.write_text(digest + "\n")
    os.replace(temporary, cache / STAMP_NAME)


def refresh_stale_caches() -> bool:
    """Delete rockdesign's cached kernels in every cache folder whose stamp differs from the sources' digest.

    Returns True if any folder was refreshed.  A folder that cannot be written is left alone (numba
    does not cache there); a stale kernel that cannot be deleted keeps its folder's old stamp and
    raises a warning naming the folder."""
    digest = sources_digest()
    refreshed = False
    for folder, cache in cache_folders().items():
        stamp = cache / STAMP_NAME
        try:
            if stamp.is_file() and stamp.read_text().strip() == digest:
                continue
            for f in kernel_cache_files(folder, cache):
                f.unlink(missing_ok=True)
        except PermissionError:
            warnings.warn(f"rockdesign: cannot delete the stale numba kernels in {cache}; they may run "
                          "the previous sources' code. Set NUMBA_CACHE_DIR to a folder of your own.",
                          RuntimeWarning, stacklevel=2)
            continue
        except OSError:
            continue
        try:
            _write_stamp(cache, digest)
        except OSError:
            continue
        refreshed = True
    return refreshed
