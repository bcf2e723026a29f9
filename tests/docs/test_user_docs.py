"""User-facing documentation describes what the tool is and does now, not how it was developed.

README.md, docs/*.md and benchmarks/README.md must not cite commit ids, issue numbers or earlier
development runs ("879dbb1 …", "issue 16", "the previous session's run"): measurement history belongs in
git and in CHANGELOG.md.  README's "Speed and accuracy" section must fit on one screen.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
USER_DOCS = sorted([ROOT / "README.md", ROOT / "benchmarks" / "README.md", *(ROOT / "docs").glob("*.md")])

# a commit id: 7–40 lowercase hex characters, word-bounded, with at least one digit and one letter a–f
# (so "decade", "facade", "1234567" and "1e-10" are not commit ids)
COMMIT_ID = re.compile(r"(?<![\w.#/-])(?=[0-9a-f]*[0-9])(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}(?![\w.-])")
# "issue 16", "issues 3 and 4", "Issue #27", "#27", "PR 5", "pull request 5"
ISSUE_REF = re.compile(r"\b(?:issues?|pull requests?|PRs?)\s*#?\s*\d+|(?<![\w&/#])#\d+\b", re.IGNORECASE)
# talk of earlier development runs: an explicit list of phrases (case-insensitive)
HISTORY_PHRASES = (
    "earlier run", "earlier measurement", "earlier session", "earlier the same day", "earlier today",
    "previous run", "previous session", "previous measurement", "previous file", "previous main",
    "last session", "this session", "that session", "the session before", "sessions ago",
    "before this change", "after this change", "the engine before", "the old engine", "than before",
    "instead of before", "measured again", "re-measured", "remeasured", "later that session",
    "later the same day", "until 2026", "since 2026", "no longer", "used to be", "went from",
    "in the same session", "not landed", "was landed", "this round", "last round",
)
HISTORY = re.compile(r"(?<!\w)(?:" + "|".join(re.escape(p) for p in HISTORY_PHRASES) + r")(?!\w)", re.IGNORECASE)
# what is not prose: link targets, URLs, inline HTML anchors and HTML character references
NOT_PROSE = re.compile(r"\]\([^)]*\)|https?://\S+|<a [^>]*>|&#\d+;")


def _prose(path: Path) -> list[tuple[int, str]]:
    return [(n, NOT_PROSE.sub(" ", line)) for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)]


def _findings(path: Path, root: Path = ROOT) -> list[str]:
    out = []
    for n, line in _prose(path):
        for kind, pattern in (("commit id", COMMIT_ID), ("issue reference", ISSUE_REF), ("history", HISTORY)):
            out += [f"{path.relative_to(root)}:{n}: {kind} {m.group(0)!r}" for m in pattern.finditer(line)]
    return out


@pytest.mark.parametrize("path", USER_DOCS, ids=lambda p: str(p.relative_to(ROOT)))
def test_user_docs_describe_what_is(path):
    findings = _findings(path)
    assert not findings, "development history in user-facing text (move it to CHANGELOG.md):\n" + "\n".join(findings)


@pytest.mark.parametrize("text, kind", [
    ("879dbb1 14.1–14.2 s interleaved", "commit id"), ("against 451a0e6", "commit id"),
    ("commit 8fc7802b9c0d1e2f3a4b5c6d7e8f9a0b1c2d3e4f", "commit id"),
    ("issue 16 is marked blocked on it", "issue reference"), ("see #27", "issue reference"),
    ("(issue #5)", "issue reference"), ("150× in the previous session's run", "history"),
    ("44.3 s earlier the same day", "history"), ("90 s four sessions ago", "history"),
])
def test_the_scan_finds_history(tmp_path, text, kind):
    doc = tmp_path / "doc.md"
    doc.write_text(f"A line.\n{text}\n", encoding="utf-8")
    assert any(f": {kind} " in f for f in _findings(doc, tmp_path)), text


@pytest.mark.parametrize("text", [
    "a decade of records, a facade", "rtol 1e-10, 2.4e-9 rad", "seed 20090601", "colour #1f77b4 in a figure",
    "[§9](#9-corrections-to-the-printed-thesis)", "<a id=\"drift\"></a>", "before overturning",
    "impacts before and after", "https://github.com/scipy/scipy/issues/14480", "its error is measured against",
    "t* = 4.474460593 s",
    "FEMA P695 far-field record 11a", "the ratio of kinetic energies after/before an impact",
])
def test_the_scan_leaves_technical_text_alone(tmp_path, text):
    doc = tmp_path / "doc.md"
    doc.write_text(text + "\n", encoding="utf-8")
    assert _findings(doc, tmp_path) == []


def _section(text: str, title: str) -> list[str]:
    lines = text.splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith("## ") and title in ln)
    end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
    return lines[start:end]


def test_readme_speed_section_fits_on_one_screen():
    section = _section((ROOT / "README.md").read_text(encoding="utf-8"), "Speed and accuracy")
    body = [ln for ln in section if ln.strip()]
    assert len(section) <= 40, f"{len(section)} lines"
    # a screen is ~160 characters wide: a cell of a paragraph does not fit
    long = [ln[:60] + "…" for ln in body if not ln.startswith("![") and len(ln) > 400]
    assert not long, f"lines too long to read at a glance: {long}"


def test_changelog_has_unreleased_and_the_current_version():
    import tomllib
    version = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    heads = re.findall(r"^## \[([^\]]+)\]", text, flags=re.MULTILINE)
    assert heads[:2] == ["Unreleased", version], heads
    unreleased, current = text.split("## [Unreleased]", 1)[1].split(f"## [{version}]", 1)
    for sub in ("### Added", "### Changed", "### Fixed"):  # where merged work adds its lines
        assert sub in unreleased, sub
    assert "### Added" in current
