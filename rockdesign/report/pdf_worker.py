"""A second process that lays out the calculation report's PDF for ``rockdesign check``.

WeasyPrint's import and the first page a process renders (fonts, the style sheet, the text paths)
cost ≈ 1 s. A warm ``check`` keeps one core idle while it starts (imports, the project, the
records), so it starts this worker first. The worker loads WeasyPrint and renders a small page into
memory (:func:`rockdesign.report.render.warm_up_pdf`) on that idle core, at low priority. When the
analyses end, the check sends the report's HTML with an empty box per figure
(:mod:`rockdesign.report.stamped_pdf`); the worker writes that PDF and answers where the boxes
landed, while the check draws the figures it then stamps in. The check itself never imports
WeasyPrint. Measurements: docs/engine.md, "Speed".

The protocol is length-prefixed pickles over the worker's stdin and stdout. A request is
``(html_text, path)``; a reply is ``("ok", slots)`` (a list of
:class:`~rockdesign.report.stamped_pdf.Slot`) or ``("error", traceback_text)``.

The worker is a help, never a dependency. When it cannot start, dies or fails, the caller writes the
PDF itself (:class:`WorkerFailed`). A failure then costs time only, and WeasyPrint's own error is
raised in the calling process, with its traceback.

Written by hand because ``multiprocessing`` and ``concurrent.futures`` fork on Linux, and GNU OpenMP
kills a child forked after numba's parallel kernels ran. Their spawn start method would also
re-import the calling CLI's ``__main__``.
"""
from __future__ import annotations

import atexit
import contextlib
import os
import pickle
import struct
import subprocess
import sys
import threading
from pathlib import Path

NICE = 10
"""The worker's niceness: it warms up while the check keeps both cores busy, and should take only
what the check leaves idle."""

_HEADER = struct.Struct("<Q")


class WorkerFailed(RuntimeError):
    """The worker could not write the PDF (it died or raised): the caller writes it itself."""


def _write(stream, obj) -> None:
    data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    stream.write(_HEADER.pack(len(data)))
    stream.write(data)
    stream.flush()


def _read(stream):
    head = stream.read(_HEADER.size)
    if len(head) < _HEADER.size:
        return None
    (n,) = _HEADER.unpack(head)
    data = stream.read(n)
    return pickle.loads(data) if len(data) == n else None


class PdfWorker:
    """The worker process, as seen by ``rockdesign check``: :meth:`start` it, :meth:`begin_layout` a PDF
    (which falls back to this process; :meth:`send` and :meth:`receive` raise instead), and
    :meth:`close` it at the end."""

    def __init__(self, process: subprocess.Popen):
        self.process = process
        atexit.register(self.close)

    @classmethod
    def start(cls) -> "PdfWorker | None":
        """Start a worker. Returns None on one core, or when no process can be started."""
        from ..execution.executor import usable_cores
        if usable_cores() < 2:
            return None
        from ..paths import child_environment
        code = "from rockdesign.report.pdf_worker import serve; serve()"
        try:
            return cls(subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                        stderr=subprocess.DEVNULL, env=child_environment()))
        except OSError:
            return None

    def send(self, html_text: str, path: Path) -> None:
        """Ask for the layout of ``html_text`` (figures as empty boxes) into the PDF ``path``; returns at
        once (:meth:`receive` the answer). Raises :class:`WorkerFailed` if the worker has gone."""
        try:
            _write(self.process.stdin, (html_text, str(path)))
        except (OSError, ValueError) as exc:
            raise WorkerFailed(f"PDF worker: {exc}") from exc

    def receive(self) -> list:
        """The figure slots of the last :meth:`send` (waits for them). Raises :class:`WorkerFailed` if the
        worker has gone or failed."""
        try:
            answer = _read(self.process.stdout)
        except (OSError, ValueError, pickle.UnpicklingError, EOFError) as exc:
            raise WorkerFailed(f"PDF worker: {exc}") from exc
        if answer is None:
            raise WorkerFailed(f"PDF worker ended (exit code {self.process.poll()})")
        status, value = answer
        if status != "ok":
            raise WorkerFailed(f"PDF worker failed:\n{value}")
        return value

    def begin_layout(self, html_text: str, path: Path) -> "LayoutJob":
        """Start laying out ``html_text`` (from :func:`~rockdesign.report.stamped_pdf.slot_html`) into the
        PDF ``path``; the job's :meth:`~LayoutJob.result` is the figure slots, laid out in this process
        if the worker fails."""
        return LayoutJob(self, html_text, Path(path))

    def close(self) -> None:
        """End the worker. It holds nothing that needs saving; one busy writing is killed."""
        if self.process.poll() is None:
            with contextlib.suppress(OSError, ValueError):
                self.process.stdin.close()
            try:
                self.process.wait(timeout=1.0)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        with contextlib.suppress(OSError, ValueError):
            self.process.stdout.close()
        atexit.unregister(self.close)


class LayoutJob:
    """A layout the worker is doing (:meth:`PdfWorker.begin_layout`)."""

    def __init__(self, worker: PdfWorker, html_text: str, path: Path):
        self.html_text, self.path = html_text, path
        try:
            worker.send(html_text, path)
            self.worker = worker
        except WorkerFailed:
            self.worker = None

    def result(self) -> list:
        """The figure slots (:func:`~rockdesign.report.stamped_pdf.layout_pdf`): the worker's, or laid out
        here when it has failed (the file is the same)."""
        if self.worker is not None:
            try:
                return self.worker.receive()
            except WorkerFailed:
                pass    # (a help, never a dependency: the PDF is written here instead)
        from .stamped_pdf import layout_pdf
        return layout_pdf(self.html_text, self.path)


def serve() -> None:
    """The worker's main loop (run as ``python -c``): warm up, write PDFs until stdin closes, then end the
    process (``os._exit``: never call it in a process that has other work)."""
    import queue
    import signal
    import traceback
    signal.signal(signal.SIGINT, signal.SIG_IGN)     # Ctrl-C is the check's to handle; it ends this process
    if hasattr(os, "nice"):      # (not on Windows)
        with contextlib.suppress(OSError):
            os.nice(NICE)
    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr                          # stray prints must not corrupt the replies
    requests: queue.Queue = queue.Queue()

    def reader() -> None:   # reads at once: the check's write of the HTML never waits for the warm-up
        while True:
            try:
                request = _read(stdin)
            except Exception:   # noqa: BLE001 — a broken request ends the worker like a closed pipe
                request = None
            requests.put(request)
            if request is None:
                return

    threading.Thread(target=reader, daemon=True).start()
    from . import render
    from .stamped_pdf import layout_pdf
    render.warm_up_pdf()
    while (request := requests.get()) is not None:
        try:
            html_text, path = request
            answer = ("ok", layout_pdf(html_text, Path(path)))
        except Exception:   # noqa: BLE001 — reported to the caller, which writes the PDF itself
            answer = ("error", traceback.format_exc())
        try:
            _write(stdout, answer)
        except (OSError, ValueError):
            break
    # nothing is left to flush (every reply was): skip the interpreter's teardown of WeasyPrint, which
    # the check would wait ≈ 0.2 s for when it closes this process
    os._exit(0)
