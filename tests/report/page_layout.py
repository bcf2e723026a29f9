"""A report's pages as a reader turns them, read back from the PDF with pypdf: table headers broken inside a word,
headings stranded at the foot of a page, figure captions on a page without their figure.

The HTML gives what to look for (the headers, headings and captions), the PDF where it landed:

    broken_headers(html, pdf)       header words of the tables that no page prints whole
    stranded_headings(html, pdf)    headings followed by fewer than MIN_LINES_AFTER_HEADING lines on their page
    captions_apart(html, pdf)       captions printed on a page that does not show their figure (its text)

A header word may break only where a reader expects it: at a space, after a hyphen or a slash (``demand/`` /
``limit``), or after a dot of a dotted key (``podium.`` / ``curvature``, marked ``<wbr>`` in the HTML).  A unit
(``[m/`` / ``s²]``) or a word (``podium.widt`` / ``h``) split over two lines is broken.
"""
from __future__ import annotations

import base64
import html as html_lib
import re
from pathlib import Path

import pypdf

MIN_LINES_AFTER_HEADING = 2
"""A heading needs this many lines of its section (text, a table's rows or a figure's labels) on its page: a
heading with one line under it at a page foot, its section going on over the page, is stranded."""

_TAG = re.compile(r"<[^>]+>")


def _text(fragment: str) -> str:
    """The text of an HTML fragment: tags dropped (a subscript joins its symbol, ``SD<sub>max</sub>`` → SDmax; a
    line break is a space), entities decoded, whitespace collapsed."""
    fragment = re.sub(r"<br\s*/?>", " ", fragment.replace("<wbr>", ""))
    return re.sub(r"\s+", " ", html_lib.unescape(_TAG.sub("", fragment))).strip()


def pages_text(pdf: Path) -> list[str]:
    """The text of every page in reading order (pypdf)."""
    return [page.extract_text() or "" for page in pypdf.PdfReader(str(pdf)).pages]


def _flat(text: str) -> str:
    """Whitespace collapsed."""
    return re.sub(r"\s+", " ", text)


def _bare(text: str) -> str:
    """Without any whitespace."""
    return re.sub(r"\s+", "", text)


def header_words(html: str) -> list[str]:
    """Every word of every table header cell (``<th>``) of the HTML."""
    words = []
    for cell in re.findall(r"<th\b[^>]*>(.*?)</th>", html, flags=re.S):
        words += _text(cell).split(" ")
    return [w for w in words if len(w) >= 3]


def broken_headers(html: str, pdf: Path) -> list[str]:
    """Header words that a page prints split over two lines at a place that is no break: "podium.widt|h",
    "[m/|s²]" (a break at a space, or after the dot of a dotted key, is a break)."""
    text = "\n".join(pages_text(pdf))
    found = set()
    for word in set(header_words(html)):
        for i in range(1, len(word)):
            if word[i - 1] in ".-" or word[i - 1] == "/" and word[:i].count("[") <= word[:i].count("]"):
                continue            # after a dotted key's dot, a hyphen or a slash (not inside a [unit])
            if re.search(rf"(?:^|\s){re.escape(word[:i])}\n{re.escape(word[i:])}(?:\s|$)", text):
                found.add(f"{word[:i]}|{word[i:]}")
    return sorted(found)


def headings(html: str) -> list[str]:
    """The texts of the section headings (``<h2>``, ``<h3>``) of the HTML."""
    return [_text(h) for h in re.findall(r"<h[23]\b[^>]*>(.*?)</h[23]>", html, flags=re.S)]


def _page_lines(pdf: Path) -> list[list[str]]:
    """The non-empty lines of every page in layout order, without the running header and footer."""
    out = []
    for page in pypdf.PdfReader(str(pdf)).pages:
        lines = [re.sub(r"\s+", " ", line).strip() for line in
                 (page.extract_text(extraction_mode="layout") or "").splitlines()]
        lines = [line for line in lines if line]
        out.append(lines[1:-1])         # the running header (project, date) and footer (tool, page n of m)
    return out


def stranded_headings(html: str, pdf: Path) -> list[str]:
    """Headings left at the foot of a page: fewer than :data:`MIN_LINES_AFTER_HEADING` lines after them on
    their page while their section goes on over the page (the next page does not open with a heading) —
    "page 10: '10 Time histories …' + 1 line(s)"."""
    wanted = {re.sub(r"\s+", " ", h) for h in headings(html)}
    pages = _page_lines(pdf)
    found = []
    for number, lines in enumerate(pages, 1):
        following = pages[number] if number < len(pages) else []
        goes_on = bool(following) and following[0] not in wanted
        for k, line in enumerate(lines):
            after = len(lines) - k - 1
            if line in wanted and after < MIN_LINES_AFTER_HEADING and goes_on:
                found.append(f"page {number}: {line!r} + {after} line(s)")
    return found


def captions(html: str) -> list[str]:
    """The first words of every figure caption (``<figcaption>``)."""
    return [" ".join(_text(c).split(" ")[:6]) for c in re.findall(r"<figcaption\b[^>]*>(.*?)</figcaption>", html,
                                                                   flags=re.S) if _text(c)]


def figure_texts(html: str) -> list[tuple[str, str]]:
    """(caption's first words, the longest text drawn in the figure) of every ``<figure>`` whose SVG keeps its
    text as text (an axis label, a title): the text a page must show beside its caption."""
    out = []
    for block in re.findall(r"<figure\b[^>]*>(.*?)</figure>", html, flags=re.S):
        caption = re.search(r"<figcaption\b[^>]*>(.*?)</figcaption>", block, flags=re.S)
        image = re.search(r'src="data:image/svg\+xml;base64,([^"]+)"', block)
        if not caption or not image:
            continue
        svg = base64.b64decode(image.group(1)).decode("utf-8")
        texts = [_text(t) for t in re.findall(r"<text\b[^>]*>(.*?)</text>", svg, flags=re.S)]
        texts = [t for t in texts if len(t) >= 6 and "$" not in t]
        if texts:
            out.append((" ".join(_text(caption.group(1)).split(" ")[:6]), max(texts, key=len)))
    return out


def captions_apart(html: str, pdf: Path) -> list[str]:
    """Captions printed on a page that does not show their figure (the figure's longest text is not on it):
    "page 4: 'Figure 5. The variants in the'"."""
    texts = [_bare(t) for t in pages_text(pdf)]        # an SVG's text comes out letter by letter: compare bare
    found = []
    for caption, drawn in figure_texts(html):
        pages = [k for k, text in enumerate(texts, 1) if _bare(caption) in text]
        for number in pages:
            if _bare(drawn) not in texts[number - 1]:
                found.append(f"page {number}: {caption!r} without its figure ({drawn!r})")
        if not pages:
            found.append(f"caption {caption!r} not found")
    return found
