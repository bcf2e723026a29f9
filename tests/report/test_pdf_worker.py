"""The PDF worker of ``rockdesign check`` (report.pdf_worker): the same PDF as in this process, and a
worker that fails or dies costs time only (this process writes the PDF)."""
from __future__ import annotations

from pathlib import Path

import pytest
from pypdf import PdfReader

from rockdesign.report import render
from rockdesign.report.pdf_worker import PdfWorker, WorkerFailed

PAGE = ("<html><head><style>{css}</style></head><body><h1>Verdict: FAIL</h1>"
        "<p>SD<sub>max</sub> = 0.123 m; θ<sub>max</sub>/θc = 0.689</p>"
        "<table><tr><th>Record</th><td>p695-ff/11a</td></tr></table>{figure}</body></html>")


def _page() -> str:
    return PAGE.format(css=render.stylesheet(), figure=render.svg_image(render.WARM_UP_SVG))


def _text(path: Path) -> str:
    return "".join(page.extract_text() for page in PdfReader(str(path)).pages)


@pytest.fixture
def worker():
    w = PdfWorker.start()
    if w is None:
        pytest.skip("one core: rockdesign check writes the PDF itself")
    yield w
    w.close()


def test_the_worker_writes_the_pdf_this_process_would(worker, tmp_path):
    html = _page()
    assert worker.write_pdf(html, tmp_path / "worker.pdf") == tmp_path / "worker.pdf"
    render.html_to_pdf(html, tmp_path / "here.pdf")
    text = _text(tmp_path / "worker.pdf")
    assert "Verdict: FAIL" in text and "p695-ff/11a" in text and "θ [rad]" in text
    assert text == _text(tmp_path / "here.pdf")


def test_a_failed_job_is_reported_and_the_worker_goes_on(worker, tmp_path):
    with pytest.raises(WorkerFailed, match="FileNotFoundError"):
        worker.write_pdf(_page(), tmp_path / "no such folder" / "report.pdf")
    assert worker.write_pdf(_page(), tmp_path / "report.pdf").stat().st_size > 1000


def test_a_dead_worker_costs_time_only(worker, tmp_path):
    worker.process.kill()
    worker.process.wait()
    with pytest.raises(WorkerFailed):
        worker.write_pdf(_page(), tmp_path / "never.pdf")
    written = render.write_report(None, tmp_path, html=False, render=lambda _: _page(), pdf_worker=worker)
    assert "Verdict: FAIL" in _text(written["pdf"])


def test_closing_ends_the_worker(worker):
    worker.close()
    assert worker.process.poll() is not None
    worker.close()     # twice is harmless (the check closes it in a finally)
