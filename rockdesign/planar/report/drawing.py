"""To-scale elevation drawings of the analysed structure for the calculation report.

A solitary column is drawn with its base (flat or curved extensions on the true radius r and wedge β,
SPEC §2); a podium as a few of its double-rocking columns under the cap beam, with the
superstructure as a mass on a spring (an SDOF, Eq 4.1; not to scale).  Columns and extensions are
drawn to scale in metres; a detail of the base is added for extensions (their rise r(1 − cos β) is
often millimetres).
"""
from __future__ import annotations

import math


from ... import mplfig as plt  # noqa: E402  (pyplot-free Figures: importing never switches the backend)
import numpy as np  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

from ..design.geometry import rocking_geometry  # noqa: E402
from ...report.formatting import fmt  # noqa: E402
from ...plots import STYLE  # noqa: E402

CONCRETE = "#d9d9d9"
STEEL = "#8fa8c8"
INK = "0.15"
PODIUM_COLUMNS_DRAWN = 4


def extension_outline(column, side: float, n: int = 60) -> np.ndarray:
    """Outline (x, y) [m] of one base extension (shoe) of a column standing on y = 0, centre x = 0.

    Curved: the arc of radius r tangent to the ground at the edge of the flat base (x = s·B), with its
    centre at (s·B, r), up to the wedge angle β, i.e. to x = s·B' at height r(1 − cos β) (Eqs 3.42, 3.44);
    flat: a plate from s·B to s·B'.  The shoe's thickness is schematic (:func:`shoe_height`).
    """
    B, Be = column.half_width, column.half_width_ext
    h = shoe_height(column)
    if column.extension == "curved":
        geo = rocking_geometry(column)
        phi = np.linspace(0.0, geo.beta, n)
        arc = np.column_stack([side * (B + geo.radius * np.sin(phi)), geo.radius * (1.0 - np.cos(phi))])
        return np.vstack([arc, [[side * Be, h], [side * B, h]]])
    return np.array([[side * B, 0.0], [side * Be, 0.0], [side * Be, h], [side * B, h]])


def shoe_height(column) -> float:
    """Drawn thickness of an extension [m] (schematic): twice the rise of the arc, at least 6 % of 2H."""
    rise = 0.0
    if column.extension == "curved":
        geo = rocking_geometry(column)
        rise = geo.radius * (1.0 - math.cos(geo.beta))
    return min(max(2.5 * rise, 0.06 * column.half_height), 0.3 * column.half_height)


def _column(ax, column, x0: float = 0.0, y0: float = 0.0, both_ends: bool = False, lw: float = 0.9):
    """Draw one column (shaft 2B × 2H and its extensions) standing at (x0, y0)."""
    H2 = 2.0 * column.half_height
    B = column.half_width
    ax.add_patch(Rectangle((x0 - B, y0), 2 * B, H2, fc=CONCRETE, ec=INK, lw=lw, zorder=2))
    if column.extension == "none":
        return
    for side in (1.0, -1.0):
        pts = extension_outline(column, side)
        ax.add_patch(Polygon(pts + [x0, y0], closed=True, fc=STEEL, ec=INK, lw=lw * 0.8, zorder=3))
        if both_ends:
            top = pts.copy()
            top[:, 1] = H2 - top[:, 1]
            ax.add_patch(Polygon(top + [x0, y0], closed=True, fc=STEEL, ec=INK, lw=lw * 0.8, zorder=3))


def _dimension(ax, p1, p2, text: str, offset, *, fontsize: float = 7.5, text_offset: float = 0.0,
               rotate: bool = False):
    """A dimension line between p1 and p2 shifted by ``offset`` (dx, dy), with extension lines."""
    p1, p2, off = np.asarray(p1, float), np.asarray(p2, float), np.asarray(offset, float)
    a, b = p1 + off, p2 + off
    for p, q in ((p1, a), (p2, b)):
        ax.plot([p[0], q[0]], [p[1], q[1]], color="0.45", lw=0.4, zorder=1)
    ax.annotate("", xy=b, xytext=a, arrowprops=dict(arrowstyle="<|-|>", lw=0.6, color=INK, mutation_scale=6,
                                                    shrinkA=0, shrinkB=0), zorder=4)
    mid = (a + b) / 2.0
    vertical = abs(b[0] - a[0]) < abs(b[1] - a[1])
    if vertical:
        ax.text(mid[0] + text_offset, mid[1], text, rotation=90 if rotate else 0, ha="center" if rotate else
                ("left" if text_offset >= 0 else "right"), va="center", fontsize=fontsize, zorder=5,
                bbox=dict(fc="white", ec="none", pad=0.5))
    else:
        ax.text(mid[0], mid[1] + text_offset, text, ha="center", va="bottom" if text_offset >= 0 else "top",
                fontsize=fontsize, zorder=5, bbox=dict(fc="white", ec="none", pad=0.5))


def _ground(ax, x_lo: float, x_hi: float, y: float = 0.0, depth: float = 0.05):
    ax.plot([x_lo, x_hi], [y, y], color=INK, lw=1.0, zorder=1)
    n = 24
    xs = np.linspace(x_lo, x_hi, n)
    for x in xs[:-1]:
        ax.plot([x, x + depth], [y, y - depth], color="0.4", lw=0.4, zorder=1)


def _radius_and_wedge(ax, column, x0: float = 0.0):
    """Centre of curvature, the radii to both ends of the right-hand arc, and the wedge angle β."""
    geo = rocking_geometry(column)
    B, r, beta = column.half_width, geo.radius, geo.beta
    cx, cy = x0 + B, r
    ends = [(x0 + B, 0.0), (x0 + B + r * math.sin(beta), r * (1 - math.cos(beta)))]
    ax.plot([cx], [cy], marker="+", color="C3", ms=6, zorder=6)
    for ex, ey in ends:
        ax.plot([cx, ex], [cy, ey], color="C3", lw=0.6, ls="--", zorder=6)
    t = np.linspace(-math.pi / 2, -math.pi / 2 + beta, 20)
    rr = 0.3 * r
    ax.plot(cx + rr * np.cos(t), cy + rr * np.sin(t), color="C3", lw=0.6, zorder=6)
    label_x = x0 + column.half_width_ext + 0.03 * r
    ax.text(label_x, cy - 0.3 * r, f"β = {fmt(beta, 'rad')}", color="C3", fontsize=7, ha="left", va="top",
            zorder=6)
    ax.text(label_x, cy - 0.6 * r, f"r = {fmt(r, 'm')}", color="C3", fontsize=7, ha="left", va="top", zorder=6)


def _base_detail(ax, column, title: str = "base detail (to scale, enlarged)"):
    """Enlarged base of a column with extensions: flat contact 2B, base 2B', rise r(1 − cos β)."""
    B, Be = column.half_width, column.half_width_ext
    h = shoe_height(column)
    H2 = 2.0 * column.half_height
    top = min(3.0 * h, H2)
    ax.add_patch(Rectangle((-B, 0.0), 2 * B, top, fc=CONCRETE, ec=INK, lw=0.9, zorder=2))
    ax.plot([-B * 1.0, B * 1.0], [top, top], color="white", lw=2.0, zorder=3)  # cut of the shaft
    for side in (1.0, -1.0):
        ax.add_patch(Polygon(extension_outline(column, side, 120), closed=True, fc=STEEL, ec=INK, lw=0.8,
                             zorder=3))
    span = 1.25 * Be
    _ground(ax, -span, span, depth=0.04 * span)
    _dimension(ax, (-B, 0.0), (B, 0.0), f"2B = {fmt(2 * B, 'm')}", (0.0, -0.22 * span), text_offset=0.0)
    _dimension(ax, (-Be, 0.0), (Be, 0.0), f"2B' = {fmt(2 * Be, 'm')}", (0.0, -0.42 * span), text_offset=0.0)
    if column.extension == "curved":
        geo = rocking_geometry(column)
        rise = geo.radius * (1.0 - math.cos(geo.beta))
        ax.plot([Be, Be + 0.12 * span], [rise, rise], color="0.45", lw=0.4)
        ax.annotate(f"r(1 − cos β) = {fmt(rise, 'm')}", xy=(Be, rise), xytext=(Be + 0.05 * span, top * 0.9),
                    fontsize=7, ha="left", arrowprops=dict(arrowstyle="-|>", lw=0.5, color=INK, mutation_scale=5))
        ax.plot([B], [0.0], "o", ms=2.5, color="C3", zorder=6)   # arc tangent to the ground here
    ax.set_xlim(-span * 1.05, span * 1.6)
    ax.set_ylim(-0.55 * span, max(top * 1.15, 0.2 * span))
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=8, loc="left")


def _frame_axes(ax):
    ax.set_aspect("equal")
    ax.axis("off")


def column_drawing(system):
    """Elevation of a solitary column (to scale) with its extensions; a base detail if extended."""
    c = system.column
    H2, B, Be = 2.0 * c.half_height, c.half_width, c.half_width_ext
    extended = c.extension != "none"
    with plt.rc_context(dict(STYLE, **{"axes.grid": False})):
        if extended:
            fig, (ax, axd) = plt.subplots(1, 2, figsize=(6.8, 4.6), gridspec_kw=dict(width_ratios=[1.0, 1.25]))
        else:
            fig, ax = plt.subplots(figsize=(4.0, 4.6))
            axd = None
        _column(ax, c)
        w = max(Be, 0.12 * H2)
        _ground(ax, -2.2 * w, 2.2 * w, depth=0.03 * H2)
        _dimension(ax, (-Be - 0.0, 0.0), (-Be, H2), f"2H = {fmt(H2, 'm')}", (-0.9 * w, 0.0),
                   text_offset=-0.04 * w, rotate=True)
        _dimension(ax, (-B, H2), (B, H2), f"2B = {fmt(2 * B, 'm')}", (0.0, 0.06 * H2), text_offset=0.01 * H2)
        if c.extension == "curved":
            _radius_and_wedge(ax, c)
        # centre of mass and the half-diagonal R to the right-hand pivot
        ax.plot([0.0], [c.half_height], "o", ms=3, color=INK, zorder=6)
        ax.plot([0.0, B], [c.half_height, 0.0], color="0.35", lw=0.5, ls=":", zorder=6)
        ax.text(0.04 * w, c.half_height, "C", fontsize=7, ha="left", va="bottom")
        ax.set_xlim(-2.3 * w, 2.3 * w)
        ax.set_ylim(-0.08 * H2, 1.18 * H2)
        _frame_axes(ax)
        ax.set_title("elevation (to scale)", fontsize=8, loc="left")
        if axd is not None:
            _base_detail(axd, c)
            axd.axis("off")
        fig.set_layout_engine("tight")
        return fig


def _spring(ax, x: float, y0: float, y1: float, width: float, turns: int = 6):
    """A zig-zag spring from (x, y0) to (x, y1)."""
    n = 2 * turns + 1
    ys = np.linspace(y0, y1, n + 2)
    xs = np.full(ys.size, x)
    xs[1:-1] += width * np.array([(-1) ** k for k in range(n)]) / 2.0
    xs[1] = xs[-2] = x
    ax.plot(xs, ys, color=INK, lw=0.8, zorder=4)


def podium_drawing(system, given: dict | None = None):
    """Elevation of a rocking podium: a few columns to scale (spacing schematic) under the cap beam,
    and the superstructure as a mass on a spring (SDOF, not to scale).

    ``given``: the project file's own texts of ``cap_beam_mass``, ``superstructure_mass``,
    ``superstructure_period`` and ``superstructure_damping`` (labels echo inputs in their units)."""
    given = {k: v for k, v in (given or {}).items() if v}
    c = system.column
    H2, B, Be = 2.0 * c.half_height, c.half_width, c.half_width_ext
    N = system.n_columns
    shown = min(N, PODIUM_COLUMNS_DRAWN)
    spacing = max(6.0 * Be, 0.9 * H2)
    xs = [k * spacing for k in range(shown)]
    if N > shown:
        xs[-1] += 0.6 * spacing   # room for the break mark
    x_left, x_right = xs[0] - 0.7 * spacing, xs[-1] + 0.7 * spacing
    beam_h = 0.12 * H2
    with plt.rc_context(dict(STYLE, **{"axes.grid": False})):
        if c.extension != "none":
            fig, (ax, axd) = plt.subplots(2, 1, figsize=(6.8, 7.0), gridspec_kw=dict(height_ratios=[2.4, 1.0]))
            if c.extension == "curved":
                geo = rocking_geometry(c)
                kind = f"curved extensions r = {fmt(geo.radius, 'm')}, β = {fmt(geo.beta, 'rad')}"
            else:
                kind = "flat extensions"
            _base_detail(axd, c, f"base detail of one column, {kind} (to scale, enlarged; top end mirrored)")
            axd.axis("off")
        else:
            fig, ax = plt.subplots(figsize=(6.8, 4.8))
        for x in xs:
            _column(ax, c, x, 0.0, both_ends=True)
        _ground(ax, x_left, x_right, depth=0.03 * H2)
        ax.add_patch(Rectangle((x_left + 0.2 * spacing, H2), x_right - x_left - 0.4 * spacing, beam_h,
                               fc="#bfbfbf", ec=INK, lw=0.9, zorder=2))
        xm = 0.5 * (xs[0] + xs[-1])
        beam_mass = given.get("cap_beam_mass") or fmt(system.cap_beam_mass, "kg")
        ax.text(x_right - 0.25 * spacing, H2 + beam_h / 2, f"cap beam $m_B$ = {beam_mass}",
                fontsize=7.5, ha="right", va="center", zorder=5)
        if N > shown:
            xb = 0.5 * (xs[-2] + xs[-1])
            ax.text(xb, 0.5 * H2, "···", fontsize=14, ha="center", va="center")
        ax.text(xm, -0.16 * H2, f"N = {N} identical columns (spacing not to scale)", fontsize=7.5, ha="center",
                va="top")
        x0 = xs[0]
        _dimension(ax, (x0 - Be, 0.0), (x0 - Be, H2), f"2H = {fmt(H2, 'm')}", (-0.32 * spacing, 0.0),
                   text_offset=-0.03 * spacing, rotate=True)
        # the width across the first column, its label beside the column (centred on it, the label is wider
        # than a slender column and overlapped its outline)
        ax.annotate("", xy=(x0 + B, 0.5 * H2), xytext=(x0 - B, 0.5 * H2), zorder=4,
                    arrowprops=dict(arrowstyle="<|-|>", lw=0.6, color=INK, mutation_scale=6, shrinkA=0, shrinkB=0))
        ax.text(x0 + Be + 0.06 * spacing, 0.5 * H2, f"2B = {fmt(2 * B, 'm')}", ha="left", va="center",
                fontsize=7.5, zorder=5, bbox=dict(fc="white", ec="none", pad=0.5))
        top = H2 + beam_h
        s = system.superstructure
        if s is not None:
            stick = 0.9 * H2
            mass_w, mass_h = 1.5 * spacing, 0.35 * H2
            _spring(ax, xm, top, top + stick, 0.12 * spacing)
            ax.add_patch(Rectangle((xm - mass_w / 2, top + stick), mass_w, mass_h, fc="#f2e6c9", ec=INK, lw=0.9,
                                   zorder=3))
            rigid = s.rigid
            label = f"$m_T$ = {given.get('superstructure_mass') or fmt(s.mass, 'kg')}"
            ax.text(xm, top + stick + mass_h / 2, label, fontsize=7.5, ha="center", va="center", zorder=5)
            if rigid:
                spring_text = "rigid superstructure"
            else:
                period = given.get("superstructure_period") or fmt(2 * math.pi / s.omega_s, 's')
                damping = given.get("superstructure_damping") or fmt(s.damping)
                spring_text = (f"$T_s$ = {period} ($\\omega_s$ = {fmt(s.omega_s, '1/s')})\n"
                               f"$\\zeta_s$ = {damping}"
                               + (" (kept after uplift, Eq 4.27)" if s.damping_correction else ""))
            ax.text(xm + 0.15 * spacing, top + stick / 2, "superstructure SDOF\n(not to scale)\n" + spring_text,
                    fontsize=7, ha="left", va="center")
            y_hi = top + stick + mass_h
        else:
            y_hi = top
        ax.set_xlim(x_left - 0.1 * spacing, x_right + 0.1 * spacing)
        ax.set_ylim(-0.32 * H2, y_hi + 0.1 * H2)
        _frame_axes(ax)
        ax.set_title("elevation: columns and cap beam to scale", fontsize=8, loc="left")
        fig.set_layout_engine("tight")
        return fig


def structure_drawing(system, given: dict | None = None):
    """The drawing that fits the system: :func:`podium_drawing` (with the inputs as ``given``) or
    :func:`column_drawing`."""
    return podium_drawing(system, given) if system.kind == "podium" else column_drawing(system)
