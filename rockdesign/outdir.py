"""An output folder written completely or not at all, by one run at a time.

``check -o DIR`` (and :func:`rockdesign.write_report`) never leave a folder that mixes two runs or
holds half a run:

* :meth:`OutputFolder.validate` refuses, before any analysis, a target that is a file, a folder or
  parent that cannot be written, or a folder holding files rockdesign did not write (it replaces
  the whole folder, so it will not take over a folder with other content such as ``.`` or ``~``);
* :meth:`OutputFolder.locked` takes an exclusive lock (``.DIR.lock`` beside the folder, an OS file
  lock released even if the process is killed) for the whole run, so a second run into the same
  folder stops at once with a clear error;
* :meth:`OutputFolder.staging` yields a temporary folder beside the target; when the block
  completes, the old folder is swapped out and the new one moved into place with two renames
  (interrupts deferred meanwhile) — files a run does not rewrite (a previous run's ``report.pdf``
  next to a new ``--no-pdf`` results.json) disappear with the old folder.  On an error or Ctrl-C
  the temporary folder is removed and the target is left as it was.
"""
from __future__ import annotations

import contextlib
import os
import shutil
import signal
import tempfile
import threading
from pathlib import Path

from .errors import RockdesignError
from .paths import expand_user, user_path_errors

RUN_FILES = frozenset({"report.pdf", "report.html", "results.json", "results.csv"})
"""The files a design check writes (CONTRACT §4); a folder holding only these may be replaced."""

OS_METADATA = frozenset({".DS_Store", "Thumbs.db", "desktop.ini"})
"""Files a file browser leaves in any folder; they do not make a folder 'foreign'."""

try:   # POSIX advisory locks; Windows falls back to msvcrt
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None


class OutputError(RockdesignError):
    """An output folder that cannot be written (a file, read-only, foreign content, in use)."""


class OutputFolder:
    """The folder a run writes into; ``key`` names the parameter in error messages.

    Args:
        target: the folder to create or replace.
        key: how the caller names it (``out_dir`` for the library, ``-o/--out`` for the CLI).
        owned: file names a previous run may have left there (replaced without asking).
    """

    def __init__(self, target, *, key: str = "out_dir", owned=RUN_FILES):
        self.target = expand_user(target, key, error=OutputError)
        self.key = key
        self.owned = frozenset(owned) | OS_METADATA
        self._lock_fd: int | None = None
        self._lock_path: Path | None = None

    # --- checks before the work -------------------------------------------------------------
    def _error(self, detail: str, expected: str, found: str) -> OutputError:
        return OutputError(detail, key=self.key, expected=expected, found=found)

    def validate(self) -> None:
        """Raise :class:`OutputError` unless the run can write the folder (call before analysing); a name too long
        for the file system or a folder on the way that cannot be read is refused too."""
        with user_path_errors(self.key, self.target, error=OutputError):
            self._validate()

    def _validate(self) -> None:
        t = self.target
        if t.is_symlink() and not t.exists():
            refuse_wrong_type(t, self.key, folder=True)
        if t.exists() and not t.is_dir():
            raise self._error("output folder is a file", "a folder (new or from an earlier run)", f"file '{t}'")
        parent = self._parent()
        if not parent.is_dir():
            raise self._error("cannot create the output folder", "a folder whose parent exists or can be created",
                              f"'{parent}' is not a folder")
        if not _writable(parent):
            raise self._error("cannot write beside the output folder", f"a writable folder to hold '{t.name}'",
                              f"'{parent}' is read-only")
        if t.is_dir():
            cwd = Path.cwd().resolve()
            if cwd == t.resolve() or t.resolve() in cwd.parents:
                raise self._error("output folder holds the working directory (it replaces the folder)",
                                  "a folder beside or below the working directory", f"'{t}'")
            if not _writable(t):
                raise self._error("output folder is read-only", "a writable folder", f"'{t}'")
            foreign = sorted(p.name for p in t.iterdir() if not self.owns(p))
            if foreign:
                shown = ", ".join(foreign[:4]) + (f" and {len(foreign) - 4} more" if len(foreign) > 4 else "")
                raise self._error("output folder holds files rockdesign did not write (it replaces the folder)",
                                  "a new folder or one from an earlier check", f"{shown} in '{t}'")

    def owns(self, entry: Path) -> bool:
        """True when ``entry`` (in the target folder) is a file an earlier run of this kind may have left."""
        return entry.name in self.owned and (entry.is_file() or entry.name in OS_METADATA)

    def _parent(self) -> Path:
        """The nearest existing ancestor of the target (the folders between are created on commit)."""
        p = self.target.absolute().parent
        while not p.exists() and p != p.parent:
            p = p.parent
        return p

    # --- one run at a time ------------------------------------------------------------------
    @property
    def held(self) -> bool:
        """True while this object holds the folder's lock."""
        return self._lock_fd is not None

    @contextlib.contextmanager
    def locked(self):
        """Hold the folder's exclusive lock for the block (validates first)."""
        if self.held:
            yield self
            return
        self.validate()
        parent = self.target.absolute().parent
        missing = [p for p in [parent, *parent.parents] if not p.exists()]
        parent.mkdir(parents=True, exist_ok=True)
        self._acquire()
        try:
            yield self
        except BaseException:
            self._release()
            for p in missing:            # a failed run leaves none of the folders it created empty
                with contextlib.suppress(OSError):
                    p.rmdir()
            raise
        else:
            self._release()

    def _acquire(self) -> None:
        path = self.target.absolute().parent / f".{self.target.name}.lock"
        while True:
            fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
            try:
                _lock(fd)
            except OSError:
                os.close(fd)
                raise self._error("output folder is in use by another rockdesign run",
                                  "one run at a time per output folder (wait, or choose another folder)",
                                  f"lock '{path}' held") from None
            try:   # the previous holder may have removed the lock file between our open and lock
                same = os.fstat(fd).st_ino == os.stat(path).st_ino
            except FileNotFoundError:
                same = False
            if same:
                break
            os.close(fd)
        self._lock_fd, self._lock_path = fd, path

    def _release(self) -> None:
        fd, path = self._lock_fd, self._lock_path
        self._lock_fd = self._lock_path = None
        if fd is None:
            return
        with contextlib.suppress(OSError):
            path.unlink()
        os.close(fd)   # closing releases the lock

    # --- all or nothing ---------------------------------------------------------------------
    @contextlib.contextmanager
    def staging(self):
        """Yield a temporary folder beside the target; move it into place when the block completes."""
        with self.locked():
            parent = self.target.absolute().parent
            tmp = Path(tempfile.mkdtemp(prefix=f".{self.target.name}.tmp-", dir=parent))
            try:
                yield tmp
                self._commit(tmp)
            except BaseException:
                shutil.rmtree(tmp, ignore_errors=True)
                raise

    def _commit(self, tmp: Path) -> None:
        target = self.target.absolute()
        os.chmod(tmp, 0o777 & ~_umask())   # mkdtemp makes 0700; a finished folder gets the usual mode
        with _interrupts_deferred():
            if target.exists():
                old = Path(tempfile.mkdtemp(prefix=f".{target.name}.old-", dir=target.parent))
                os.rmdir(old)
                os.rename(target, old)
                try:
                    os.rename(tmp, target)
                except BaseException:
                    os.rename(old, target)
                    raise
                shutil.rmtree(old, ignore_errors=True)
            else:
                os.rename(tmp, target)


DESIGN_FILES = frozenset({"design.json", "design.csv", "design.pdf", "design.html"})
"""The files ``rockdesign design`` writes (CONTRACT §6.3), besides its figures ``design_<name>.svg``."""
STORE = "variants"
"""The folder of stored variants inside a design's output folder (:mod:`rockdesign.design_space.store`)."""


class DesignFolder(OutputFolder):
    """The output folder of ``rockdesign design``: :class:`OutputFolder`'s guarantees (refused before any
    analysis when it is a file, read-only, in use or holds files rockdesign did not write; locked for the
    run; written all or nothing) plus the store of finished variants, ``DIR/variants/``, which is written as
    each variant ends (an interrupted run resumes from it) and carried over into the new folder when the
    run completes.  A ``variants`` that is not a folder of ``*.json`` files is foreign content."""

    def __init__(self, target, *, key: str = "out_dir"):
        super().__init__(target, key=key, owned=DESIGN_FILES)

    @property
    def store(self) -> Path:
        """Where the finished variants are stored (created with the first one)."""
        return self.target / STORE

    def owns(self, entry: Path) -> bool:
        name = entry.name
        if name == STORE:
            return entry.is_dir() and not entry.is_symlink() and all(
                p.is_file() and not p.is_symlink() and (p.suffix in (".json", ".tmp") or p.name in OS_METADATA)
                for p in entry.iterdir())
        if name.startswith("design_") and name.endswith(".svg"):
            return entry.is_file()
        return super().owns(entry)

    def validate(self) -> None:
        super().validate()
        store = self.store
        if store.is_dir() and not _writable(store):
            raise self._error("the stored variants cannot be written", "a writable folder of stored variants",
                              f"'{store}' is read-only")

    def _commit(self, tmp: Path) -> None:
        store = self.store.absolute()
        if store.is_dir():      # the stored variants stay with the folder (a later run resumes from them)
            shutil.rmtree(tmp / STORE, ignore_errors=True)
            os.rename(store, tmp / STORE)
        try:
            super()._commit(tmp)
        except BaseException:
            if (tmp / STORE).is_dir() and not store.exists():
                os.rename(tmp / STORE, store)
            raise


_CREATED: list[Path] = []
"""Folders :func:`created_folder` made in this run (the CLI discards the empty ones when the run fails)."""


def created_folder(path, key: str) -> Path:
    """Create the output folder ``path`` (and missing parents) for a run that writes into it as it goes.

    Refuses a path that exists as something other than a folder (a file, a dangling symbolic link)
    naming ``key``.  The topmost folder this call creates is remembered: when the run fails,
    :func:`discard_unfinished` removes it again if no file was written in it — a failed run leaves
    no empty folder (files kept on purpose, such as the chunks a spectrum resumes from, stay).
    """
    path = expand_user(path, key, error=OutputError)
    with user_path_errors(key, path, error=OutputError):
        for p in [path, *path.parents]:
            refuse_wrong_type(p, key, folder=True)
        missing = [p for p in [path, *path.parents] if not p.exists()]
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError("cannot create the output folder", key=key, expected="a folder that can be created",
                          found=f"'{path}': {exc.strerror or exc}") from None
    if missing:
        _CREATED.append(missing[-1])
    return path


def refuse_wrong_type(path, key: str, *, folder: bool) -> None:
    """Raise :class:`OutputError` if the output ``path`` exists as the wrong type: a dangling symbolic
    link, a file where a folder goes (``folder=True``), a folder where a file goes."""
    path = Path(path)
    expected = "a folder (new or existing)" if folder else "a file name"
    if path.is_symlink() and not path.exists():
        raise OutputError("the output path is a dangling symbolic link", key=key, expected=expected,
                          found=f"'{path}' → '{os.readlink(path)}' (does not exist)")
    if folder and path.exists() and not path.is_dir():
        raise OutputError("the output path is a file, not a folder", key=key, expected=expected,
                          found=f"'{path}' (an existing file)")
    if not folder and path.is_dir():
        raise OutputError("the output path is a folder", key=key, expected=expected,
                          found=f"'{path}' (an existing folder)")


def discard_unfinished() -> list[Path]:
    """Remove the folders :func:`created_folder` made in this run that hold no file (call when it fails);
    returns the removed folders."""
    removed = []
    while _CREATED:
        folder = _CREATED.pop()
        if folder.is_dir() and not any(p.is_file() or p.is_symlink() for p in folder.rglob("*")):
            shutil.rmtree(folder, ignore_errors=True)
            removed.append(folder)
    return removed


def forget_created() -> None:
    """Start a new run: the folders of an earlier (finished) run are no longer discarded."""
    _CREATED.clear()


def _writable(folder: Path) -> bool:
    """True if a file can be created in ``folder`` (tried: permissions, ACLs, read-only mounts, immutable flags)."""
    try:
        with tempfile.TemporaryFile(dir=folder):
            return True
    except OSError:
        return False


def _lock(fd: int) -> None:
    if fcntl is not None:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    else:  # pragma: no cover - Windows
        import msvcrt
        msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def _interrupts_deferred():
    """Hold back SIGINT during the two renames of a commit (re-raised right after)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    received = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: received.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if received:
        raise KeyboardInterrupt
