"""Figures without pyplot: the small pyplot-like surface rockdesign's plotting modules use.

rockdesign's figures are :class:`matplotlib.figure.Figure` objects created directly, never through
``matplotlib.pyplot``: importing rockdesign does not call ``matplotlib.use`` (which would switch a
notebook's backend), no global figure registry keeps figures alive, and ``fig.savefig`` picks the
Agg/SVG/PDF canvas from the file type.  A notebook displays a returned figure as usual.

Plotting modules import this module as ``plt`` (``from .. import mplfig as plt``), so the calls read
like pyplot's: ``plt.subplots``, ``plt.rc_context``, ``plt.get_cmap``, ``plt.Line2D``, ``plt.close``.
"""
from __future__ import annotations

import matplotlib
from matplotlib import rc_context  # noqa: F401  (re-exported: style context for figure creation)
from matplotlib.figure import Figure
from matplotlib.lines import Line2D  # noqa: F401  (re-exported: legend handles)


def figure(**kwargs) -> Figure:
    """A new :class:`~matplotlib.figure.Figure` (``figsize`` in inches, ``dpi``...), not registered with pyplot."""
    return Figure(**kwargs)


def subplots(nrows: int = 1, ncols: int = 1, *, figsize=None, dpi=None, **kwargs):
    """``(fig, axes)`` as :func:`matplotlib.pyplot.subplots` returns them, on a pyplot-free Figure.

    ``kwargs`` go to :meth:`Figure.subplots` (``sharex``, ``gridspec_kw``, ``squeeze``...)."""
    fig = Figure(figsize=figsize, dpi=dpi)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def get_cmap(name: str):
    """A registered colormap by name."""
    return matplotlib.colormaps[name]


def close(fig: Figure | None = None) -> None:
    """Nothing to release: a pyplot-free figure is freed when it is no longer referenced."""
