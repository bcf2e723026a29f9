"""Matplotlib figures shared by the CLI and the report (Agg backend, no screen needed), and the layout rules every
report figure follows: a legend or a note never sits on the data (:func:`legend_above`, :func:`clear_position`),
tick labels never touch (:func:`upright_ticks_if_crowded`), a text fits its cell (:func:`fit_text`).  The rules
measure the texts as matplotlib lays them out (``Figure.draw_without_rendering``); tests/report/figure_layout.py
reads the drawn figures back and fails on a collision."""
from __future__ import annotations


from . import mplfig as plt  # noqa: E402  (pyplot-free Figures: importing never switches the backend)
import numpy as np  # noqa: E402

STYLE = {"figure.dpi": 110, "font.size": 9, "axes.grid": True, "grid.alpha": 0.3, "axes.spines.top": False,
         "axes.spines.right": False, "savefig.bbox": "tight"}

TICK_GAP_PT = 2.0
"""Neighbouring tick labels closer than this [pt] are turned upright (they read as one number otherwise)."""


def legend_above(ax, *, ncol: int = 3, fontsize: float = 7, handles=None, **kwargs):
    """The axes' legend in a band above it, outside the data (the layout engine makes room for it)."""
    options = dict(loc="lower left", bbox_to_anchor=(0.0, 1.01), ncol=ncol, fontsize=fontsize, frameon=False,
                   borderaxespad=0.0, handlelength=1.8, handletextpad=0.5, columnspacing=1.2)
    options.update(kwargs)
    if handles is not None:
        options["handles"] = handles
    return ax.legend(**options)


def _renderer(fig):
    fig.draw_without_rendering()
    return fig._get_renderer()


def upright_ticks_if_crowded(fig, ax, gap_pt: float = TICK_GAP_PT) -> bool:
    """Turn the x tick labels of ``ax`` upright when two neighbours come closer than ``gap_pt`` (after the
    figure's layout); True when it did.  Call it after the figure is laid out (``tight_layout``)."""
    renderer = _renderer(fig)
    boxes = sorted((t.get_window_extent(renderer) for t in ax.get_xticklabels() if t.get_text().strip()),
                   key=lambda b: b.x0)
    gap = gap_pt * fig.dpi / 72.0
    if all(b.x0 - a.x1 >= gap for a, b in zip(boxes, boxes[1:])):
        return False
    for t in ax.get_xticklabels():
        t.set_rotation(90)
    return True


def fit_text(text, width_px: float, *, renderer=None, smallest: float = 4.5) -> bool:
    """Shrink a text until it is at most ``width_px`` wide, down to ``smallest`` pt, then break it at its middle
    space onto two lines; False when it still does not fit (the caller leaves it out)."""
    renderer = renderer or _renderer(text.figure)
    if text.get_window_extent(renderer).width <= width_px:
        return True
    size = text.get_fontsize()
    text.set_fontsize(max(smallest, size * width_px / text.get_window_extent(renderer).width))
    if text.get_window_extent(renderer).width <= width_px:
        return True
    words = text.get_text().split(" ")
    if len(words) > 1:
        cut = min(range(1, len(words)), key=lambda k: abs(len(" ".join(words[:k])) - len(" ".join(words[k:]))))
        text.set_text(" ".join(words[:cut]) + "\n" + " ".join(words[cut:]))
        text.set_fontsize(size)
        width = text.get_window_extent(renderer).width
        text.set_fontsize(max(smallest, min(size, size * width_px / width)))
    return bool(text.get_window_extent(renderer).width <= width_px)


def _data_under(ax, box, margin: float) -> bool:
    """Whether a line (any segment, steps included) or a marker/scatter point of ``ax`` lies under ``box`` [px],
    grown by ``margin`` [px]."""
    from matplotlib import cbook
    from matplotlib.collections import LineCollection, PathCollection
    from matplotlib.path import Path
    from matplotlib.transforms import Bbox
    grown = Bbox.from_extents(box.x0 - margin, box.y0 - margin, box.x1 + margin, box.y1 + margin)

    def crosses(xy) -> bool:
        ok = np.all(np.isfinite(xy), axis=1)
        return any(Path(xy[a:b]).intersects_bbox(grown, filled=False) for a, b in _finite_runs(ok) if b - a >= 2)

    def inside(xy) -> bool:
        return bool(np.any((xy[:, 0] >= grown.x0) & (xy[:, 0] <= grown.x1) & (xy[:, 1] >= grown.y0)
                           & (xy[:, 1] <= grown.y1)))

    for line in ax.get_lines():
        xy = np.asarray(line.get_xydata(), dtype=float)
        if not line.get_visible() or not xy.size:
            continue
        xy = line.get_transform().transform(xy)
        if line.get_drawstyle() != "default":
            xy = np.column_stack(cbook.STEP_LOOKUP_MAP[line.get_drawstyle()](xy[:, 0], xy[:, 1]))
        drawn = line.get_linestyle() not in ("None", "none", "", " ") and line.get_linewidth() > 0
        if drawn and crosses(xy) or line.get_marker() not in (None, "None", "none", "", " ") and inside(xy):
            return True
    for c in ax.collections:
        if isinstance(c, PathCollection) and len(c.get_offsets()):
            if inside(c.get_offset_transform().transform(np.asarray(c.get_offsets(), dtype=float))):
                return True
        elif isinstance(c, LineCollection):
            if any(crosses(c.get_transform().transform(np.asarray(seg, dtype=float))) for seg in c.get_segments()):
                return True
    return False


def _finite_runs(ok: np.ndarray):
    edges = np.flatnonzero(np.diff(np.concatenate([[0], ok.astype(int), [0]])))
    return zip(edges[::2], edges[1::2])


def clear_position(ax, text, candidates, margin_pt: float = 2.0) -> bool:
    """Move ``text`` to the first of ``candidates`` — (x, y, ha, va) in the text's coordinates — where no line or
    marker of ``ax`` lies under it (within ``margin_pt``); True when one was clear (else it stays at the last)."""
    fig = ax.figure
    renderer = _renderer(fig)
    margin = margin_pt * fig.dpi / 72.0
    for x, y, ha, va in candidates:
        text.set_position((x, y))
        text.set_ha(ha)
        text.set_va(va)
        if not _data_under(ax, text.get_window_extent(renderer), margin):
            return True
    return False


def save(fig, path, dpi: float | None = None) -> None:
    """Save a figure (format from the extension; raster at ``dpi``) into its folder, made if missing,
    and close it."""
    from pathlib import Path
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, **({"dpi": dpi} if dpi else {}))
    plt.close(fig)
