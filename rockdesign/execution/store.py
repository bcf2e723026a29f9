"""Chunk files of resumable runs: exact input fingerprints and an atomic, resumable chunk store.

A run that maps a batch function over chunks saves every completed chunk as ``chunk-NNNNN.npz``
beside a ``manifest.json`` holding the fingerprint of all inputs. A rerun with the same fingerprint
loads the completed chunks and computes only the missing ones; another fingerprint discards them.
"""
from __future__ import annotations

import hashlib
import json
import os
import tempfile
from pathlib import Path

import numpy as np

ChunkResult = dict
"""A chunk's result: ``dict[str, numpy.ndarray]`` (what :class:`ChunkStore` can save)."""


def fingerprint(*parts) -> str:
    """A SHA-256 hex digest of arrays, numbers, strings, tuples/lists and dicts (canonical, exact).

    Arrays enter with dtype, shape and raw bytes, floats with their exact repr, so two inputs share
    a fingerprint only if they are identical.
    """
    h = hashlib.sha256()

    def feed(x):
        if isinstance(x, np.ndarray):
            a = np.ascontiguousarray(x)
            h.update(f"nd:{a.dtype.str}:{a.shape}:".encode())
            h.update(a.tobytes())
        elif isinstance(x, dict):
            h.update(b"dict:")
            for k in sorted(x):
                feed(str(k))
                feed(x[k])
        elif isinstance(x, (list, tuple)):
            h.update(f"seq:{len(x)}:".encode())
            for v in x:
                feed(v)
        elif isinstance(x, float):
            h.update(f"f:{x!r};".encode())
        elif isinstance(x, (bool, int, np.integer)):
            h.update(f"i:{int(x)};".encode())
        elif x is None:
            h.update(b"none;")
        else:
            h.update(f"s:{x};".encode())

    for p in parts:
        feed(p)
    return h.hexdigest()


class ChunkStore:
    """Completed chunk results in ``directory`` (one ``chunk-NNNNN.npz`` per chunk, plus ``manifest.json``).

    Args:
        directory: folder for the chunk files (created on demand).
        fingerprint: identifies the inputs; chunks of another fingerprint are never reused.
        meta: extra JSON-serialisable information written into the manifest.
    """

    MANIFEST = "manifest.json"

    def __init__(self, directory, fingerprint: str, meta: dict | None = None):
        self.directory = Path(directory)
        self.fingerprint = fingerprint
        self.meta = dict(meta or {})
        self.discarded = 0

    def manifest(self) -> dict | None:
        """The manifest found in the folder, or None."""
        try:
            return json.loads((self.directory / self.MANIFEST).read_text())
        except (OSError, ValueError):
            return None

    def open(self, resume: bool = True) -> None:
        """Prepare the folder: keep matching chunks if ``resume``, otherwise (or on mismatch) delete them."""
        found = self.manifest()
        if not resume or found is None or found.get("fingerprint") != self.fingerprint:
            self.discarded = len(self._chunk_files())
            self.clear()
        self.directory.mkdir(parents=True, exist_ok=True)
        self._write_json(self.directory / self.MANIFEST, {"fingerprint": self.fingerprint, **self.meta})

    def path(self, index: int) -> Path:
        return self.directory / f"chunk-{index:05d}.npz"

    def load(self, index: int) -> ChunkResult | None:
        """The saved result of chunk ``index``, or None (missing or unreadable files are ignored)."""
        path = self.path(index)
        if not path.exists():
            return None
        try:
            with np.load(path, allow_pickle=False) as data:
                return {k: data[k] for k in data.files}
        except Exception:  # a torn or foreign file: recompute the chunk
            path.unlink(missing_ok=True)
            return None

    def save(self, index: int, result: ChunkResult) -> None:
        """Write chunk ``index`` atomically (temporary file + rename): an interruption never leaves
        a half-written chunk behind."""
        self.directory.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".chunk-{index:05d}-", suffix=".npz", dir=self.directory)
        try:
            with os.fdopen(fd, "wb") as fh:
                np.savez(fh, **{k: np.asarray(v) for k, v in result.items()})
            os.replace(tmp, self.path(index))
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise

    def completed(self) -> list[int]:
        """Indices of the chunks saved so far."""
        out = []
        for p in self._chunk_files():
            try:
                out.append(int(p.stem.split("-")[1]))
            except (IndexError, ValueError):
                continue
        return sorted(out)

    def clear(self) -> None:
        """Delete every chunk file and the manifest (the folder itself if it ends up empty)."""
        if not self.directory.exists():
            return
        for p in list(self._chunk_files()) + list(self.directory.glob(".chunk-*")):
            p.unlink(missing_ok=True)
        (self.directory / self.MANIFEST).unlink(missing_ok=True)
        try:
            self.directory.rmdir()
        except OSError:
            pass

    def _chunk_files(self):
        if not self.directory.exists():
            return []
        return sorted(self.directory.glob("chunk-*.npz"))

    @staticmethod
    def _write_json(path: Path, data: dict) -> None:
        tmp = path.with_suffix(".tmp")
        tmp.write_text(json.dumps(data, indent=1))
        os.replace(tmp, path)
