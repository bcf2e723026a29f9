"""Keep numba's on-disk cache consistent with the kernel sources.

numba (``cache=True``) keys a cached function on its own source file only: a kernel that inlines or
calls code from another file keeps the old machine code after that file changes.  On import of the
numerical packages, :func:`refresh_stale_caches` hashes every rockdesign source that defines a
kernel and, when the digest differs from the one stored beside the cache, deletes rockdesign's
cached kernels so that they are compiled afresh from the current sources.
"""
from __future__ import annotations

import functools
import hashlib
import os
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
STAMP = PACKAGE / "__pycache__" / "numba-kernels.sha256"


def kernel_sources() -> list[Path]:
    """rockdesign's source files that define numba kernels, in a stable order."""
    return sorted(p for p in PACKAGE.rglob("*.py") if "@njit" in p.read_text(encoding="utf-8", errors="ignore"))


@functools.lru_cache(maxsize=1)
def sources_digest() -> str:
    """SHA-256 over the kernel sources (paths and contents); read once per process."""
    h = hashlib.sha256()
    for p in kernel_sources():
        h.update(str(p.relative_to(PACKAGE)).encode())
        h.update(p.read_bytes())
    return h.hexdigest()


def _cache_files() -> list[Path]:
    files = [f for pattern in ("*.nbi", "*.nbc") for f in PACKAGE.rglob(pattern)]
    user_dir = os.environ.get("NUMBA_CACHE_DIR")
    if user_dir and Path(user_dir).is_dir():
        files += [f for pattern in ("*.nbi", "*.nbc") for f in Path(user_dir).rglob(pattern)
                  if "rockdesign" in str(f)]
    return files


def refresh_stale_caches() -> bool:
    """Delete rockdesign's numba cache files if the kernel sources changed; True if it did."""
    try:
        digest = sources_digest()
        if STAMP.exists() and STAMP.read_text().strip() == digest:
            return False
        for f in _cache_files():
            f.unlink(missing_ok=True)
        STAMP.parent.mkdir(parents=True, exist_ok=True)
        STAMP.write_text(digest + "\n")
        return True
    except OSError:   # read-only installation: numba then compiles in memory
        return False
