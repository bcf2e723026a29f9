"""The PDF worker of ``rockdesign check`` (report.pdf_worker): the same pages and figure boxes as in
this process, and a worker that fails or dies costs time only (this process lays out the PDF)."""
from __future__ import annotations

from pathlib import Path

import pytest
from pypdf import PdfReader

from rockdesign.report import render, stamped_pdf
from rockdesign.report.pdf_worker import PdfWorker, WorkerFailed

PAGE = ("<html><head><style>{css}</style></head><body><h1>Verdict: FAIL</h1>"
        "<p>SD<sub>max</sub> = 0.123 m; θ<sub>max</sub>/θc = 0.689</p>"
        "<table><tr><th>Record</th><td>p695-ff/11a</td></tr></table>{figure}</body></html>")


FIGURE = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
          'viewBox="0 0 144 108"><defs><path id="m" d="M 0 -3 L 3 3 L -3 3 z"/></defs>'
          '<path d="M 10 90 L 130 20" style="fill: none; stroke: #1f77b4; stroke-width: 1.5"/>'
          '<use xlink:href="#m" x="10" y="90" style="fill: #1f77b4"/>'
          '<text style="font: 10px \'DejaVu Sans\'; text-anchor: middle" x="72" y="104">θ [rad]</text></svg>')


def _page() -> str:
    return PAGE.format(css=render.stylesheet(), figure=render.svg_image(FIGURE))


def _slotted() -> str:
    return stamped_pdf.slot_html(_page())[0]


def _layout(worker, path: Path) -> list:
    worker.send(_slotted(), path)
    return worker.receive()


def _text(path: Path) -> str:
    return "".join(page.extract_text() for page in PdfReader(str(path)).pages)


@pytest.fixture
def worker():
    w = PdfWorker.start()
    if w is None:
        pytest.skip("one core: rockdesign check writes the PDF itself")
    yield w
    w.close()


def test_the_worker_lays_out_the_pdf_this_process_would(worker, tmp_path):
    slots = _layout(worker, tmp_path / "worker.pdf")
    assert slots == stamped_pdf.layout_pdf(_slotted(), tmp_path / "here.pdf")
    assert len(slots) == 1 and slots[0].width > 100
    text = _text(tmp_path / "worker.pdf")
    assert "Verdict: FAIL" in text and "p695-ff/11a" in text
    assert text == _text(tmp_path / "here.pdf")
    written = render.write_report(None, tmp_path / "out", html=False, render=lambda _: _page(), pdf_worker=worker)
    assert "θ [rad]" in _text(written["pdf"])       # the figure, stamped in


def test_a_failed_job_is_reported_and_the_worker_goes_on(worker, tmp_path):
    with pytest.raises(WorkerFailed, match="FileNotFoundError"):
        _layout(worker, tmp_path / "no such folder" / "report.pdf")
    assert len(_layout(worker, tmp_path / "report.pdf")) == 1
    assert (tmp_path / "report.pdf").stat().st_size > 1000


def test_a_dead_worker_costs_time_only(worker, tmp_path):
    worker.process.kill()
    worker.process.wait()
    with pytest.raises(WorkerFailed):
        _layout(worker, tmp_path / "never.pdf")
    written = render.write_report(None, tmp_path, html=False, render=lambda _: _page(), pdf_worker=worker)
    assert "Verdict: FAIL" in _text(written["pdf"]) and "θ [rad]" in _text(written["pdf"])


def test_closing_ends_the_worker(worker):
    worker.close()
    assert worker.process.poll() is not None
    worker.close()     # twice is harmless (the check closes it in a finally)
