"""A figure's layout as matplotlib draws it: the box of every text on the canvas and what the data occupy, for
tests that fail when two texts collide, when a legend or a note sits on the data, or when a text is cut off.

Everything is read from the figure after ``canvas.draw()`` (Agg), in display pixels:

    overlapping_texts(fig)    pairs of drawn texts (tick labels, legend entries, titles, axis labels, notes,
                              annotations, contour labels, colour-bar labels) whose boxes overlap or touch
    covered_data(fig)         legends and free texts (notes, annotations, contour labels) that cover a data line,
                              marker or scatter point of their axes
    texts_cut_off(fig)        texts reaching outside the figure (cut off when it is saved at its size)
    layout_problems(fig)      all three, as readable lines ([] when the figure is clean)

A tick label counts only when its tick is drawn (inside the view limits); a text with an empty string or an
invisible one does not count.  Data are the axes' lines (each drawn segment and each marker), scatter points
and line collections (e.g. vertical lines per record); filled areas, bars, images and contour lines are not:
a text may sit on a coloured cell, not on a curve.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib import cbook
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.contour import ContourSet
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.path import Path
from matplotlib.text import Text
from matplotlib.transforms import Bbox

MIN_GAP_PT = 1.0
"""Two texts closer than this [pt] read as one ("0.33330.3667"): their boxes collide."""
TOLERANCE_PT = 0.5
"""A text reaching this far [pt] beyond the canvas is cut off; a box covers a mark it reaches within this."""


@dataclass(frozen=True)
class DrawnText:
    """One text as drawn: its string, its box [px], what it is (tick, legend, free, label) and its axes."""

    text: str
    box: Bbox
    role: str
    artist: Text
    axes: object

    def __str__(self) -> str:
        return f"{self.role} {self.text!r}"


def draw(fig):
    """Lay the figure out and draw it on an Agg canvas; returns the renderer."""
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    canvas.draw()
    return canvas.get_renderer()


def _tick_labels(fig) -> tuple[set[int], set[int]]:
    """(every tick label's id, the ids of the tick labels drawn)."""
    every, drawn = set(), set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                every |= {id(tick.label1), id(tick.label2)}
            if not ax.axison or not axis.get_visible():
                continue                             # an axes drawn without its axes (a drawing): no tick labels
            for tick in axis._update_ticks():        # the ticks inside the view limits, as drawn
                drawn |= {id(t) for t in (tick.label1, tick.label2) if t.get_visible()}
    return every, drawn


def _role(t: Text, fig, ticks: set[int]) -> str:
    """What a text is: a tick label, a legend entry, a title, an axis label, an offset, a free text (a note,
    an annotation, a contour label, a cell value) or other (e.g. a colour bar's label)."""
    if id(t) in ticks:
        return "tick label"
    for legend in _legends(fig):
        if any(t is x for x in legend.get_texts()) or t is legend.get_title():
            return "legend"
    for ax in fig.axes:
        if any(t is x for x in (ax.title, ax._left_title, ax._right_title)):
            return "title"
        if t is ax.xaxis.label or t is ax.yaxis.label:
            return "axis label"
        if t is ax.xaxis.offsetText or t is ax.yaxis.offsetText:
            return "offset"
        if any(t is x for x in ax.texts):
            return "free"
    return "free" if any(t is x for x in fig.texts) else "other"


def _legends(fig) -> list[Legend]:
    out = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)
    return [legend for legend in out if legend.get_visible()]


def drawn_texts(fig, renderer=None) -> list[DrawnText]:
    """Every text the figure draws, with its box in display pixels."""
    renderer = renderer or draw(fig)
    every, drawn = _tick_labels(fig)
    out = []
    for t in fig.findobj(match=Text):
        if not t.get_visible() or not t.get_text().strip() or (id(t) in every and id(t) not in drawn):
            continue
        box = t.get_window_extent(renderer)
        if box.width <= 0 or box.height <= 0:
            continue
        out.append(DrawnText(t.get_text(), box, _role(t, fig, drawn), t, t.axes))
    return out


def _collide(a: Bbox, b: Bbox, gap: float) -> bool:
    """The boxes overlap, or come closer than ``gap`` [px]."""
    return min(a.x1, b.x1) - max(a.x0, b.x0) > -gap and min(a.y1, b.y1) - max(a.y0, b.y0) > -gap


def overlapping_texts(fig, renderer=None) -> list[tuple[DrawnText, DrawnText]]:
    """Pairs of drawn texts whose boxes overlap or come closer than :data:`MIN_GAP_PT`."""
    renderer = renderer or draw(fig)
    gap = MIN_GAP_PT * fig.dpi / 72.0
    texts = drawn_texts(fig, renderer)
    return [(a, b) for i, a in enumerate(texts) for b in texts[i + 1:] if _collide(a.box, b.box, gap)]


def texts_cut_off(fig, renderer=None) -> list[DrawnText]:
    """Texts reaching outside the figure's canvas."""
    renderer = renderer or draw(fig)
    tol = TOLERANCE_PT * fig.dpi / 72.0
    frame = fig.bbox
    return [t for t in drawn_texts(fig, renderer) if t.box.x0 < frame.x0 - tol or t.box.y0 < frame.y0 - tol
            or t.box.x1 > frame.x1 + tol or t.box.y1 > frame.y1 + tol]


def _runs(xy: np.ndarray):
    """The finite stretches of a polyline (NaN breaks a line)."""
    ok = np.all(np.isfinite(xy), axis=1)
    if ok.all():
        yield xy
        return
    edges = np.flatnonzero(np.diff(np.concatenate([[0], ok.astype(int), [0]])))
    for start, stop in zip(edges[::2], edges[1::2]):
        yield xy[start:stop]


def _line_marks(line: Line2D, dpi: float):
    """(polylines, points, point radius) of a Line2D in display pixels, as drawn (steps included)."""
    xy = np.asarray(line.get_xydata(), dtype=float)
    if xy.size == 0:
        return [], np.empty((0, 2)), 0.0
    xy = line.get_transform().transform(xy)
    polylines = []
    if line.get_linestyle() not in ("None", "none", "", " ") and line.get_linewidth() > 0:
        steps = cbook.STEP_LOOKUP_MAP[line.get_drawstyle()]
        drawn = np.column_stack(steps(xy[:, 0], xy[:, 1])) if line.get_drawstyle() != "default" else xy
        polylines = [run for run in _runs(drawn) if len(run) >= 2]
    points = np.empty((0, 2))
    if line.get_marker() not in (None, "None", "none", "", " "):
        points = xy[np.all(np.isfinite(xy), axis=1)]
    return polylines, points, 0.5 * line.get_markersize() * dpi / 72.0


def data_marks(ax):
    """What the data of ``ax`` occupy: (polylines, [(points, radius)]) in display pixels."""
    dpi = ax.figure.dpi
    polylines, points = [], []
    for line in ax.get_lines():
        if not line.get_visible():
            continue
        lines, pts, radius = _line_marks(line, dpi)
        polylines += lines
        if len(pts):
            points.append((pts, radius))
    for c in ax.collections:
        if not c.get_visible() or isinstance(c, ContourSet):
            continue
        if isinstance(c, PathCollection) and len(c.get_offsets()):
            pts = c.get_offset_transform().transform(np.asarray(c.get_offsets(), dtype=float))
            sizes = c.get_sizes()
            radius = 0.5 * float(np.sqrt(np.max(sizes))) * dpi / 72.0 if len(sizes) else 0.0
            points.append((pts[np.all(np.isfinite(pts), axis=1)], radius))
        elif isinstance(c, LineCollection):
            transform = c.get_transform()
            for seg in c.get_segments():
                polylines += [run for run in _runs(transform.transform(np.asarray(seg, dtype=float))) if len(run) >= 2]
    return polylines, points


def _covers(box: Bbox, polylines, points) -> int:
    """How many marks of the data lie under ``box`` (a polyline crossing it counts once)."""
    hits = 0
    for run in polylines:
        if Path(run).intersects_bbox(box, filled=False):
            hits += 1
    for pts, radius in points:
        inside = ((pts[:, 0] >= box.x0 - radius) & (pts[:, 0] <= box.x1 + radius)
                  & (pts[:, 1] >= box.y0 - radius) & (pts[:, 1] <= box.y1 + radius))
        hits += int(inside.sum())
    return hits


def covered_data(fig, renderer=None) -> list[tuple[str, int]]:
    """Legends and free texts that sit on the data of an axes: (what, how many marks they cover)."""
    renderer = renderer or draw(fig)
    out = []
    for ax in fig.axes:
        frame = ax.get_window_extent(renderer)
        polylines, points = data_marks(ax)
        if not polylines and not points:
            continue
        boxes = [(f"legend of {ax.get_title() or ax.get_ylabel() or 'an axes'}", legend.get_window_extent(renderer))
                 for legend in _legends(fig) if legend.axes is ax or any(legend is f for f in fig.legends)]
        boxes += [(str(t), t.box) for t in drawn_texts(fig, renderer) if t.role == "free" and t.axes is ax]
        for what, box in boxes:
            inner = Bbox.intersection(box, frame)
            if inner is None or inner.width <= 0 or inner.height <= 0:
                continue
            hits = _covers(inner, polylines, points)
            if hits:
                out.append((what, hits))
    return out


def layout_problems(fig) -> list[str]:
    """Every collision, covered datum and cut-off text of ``fig``, as lines a test failure prints."""
    renderer = draw(fig)
    problems = [f"overlap: {a} and {b}" for a, b in overlapping_texts(fig, renderer)]
    problems += [f"covers the data: {what} ({n} marks)" for what, n in covered_data(fig, renderer)]
    problems += [f"cut off: {t}" for t in texts_cut_off(fig, renderer)]
    return problems


def marker_centres(ax) -> list[tuple[np.ndarray, float]]:
    """The display centres of every marker and scatter point of ``ax`` with their radius [px]."""
    return data_marks(ax)[1]
