"""Figures of a design chart (SPEC §15), one function per figure: the pass/fail region with the governing reason
per cell (:func:`verdict_figure`), one quantity of the cells over the grid (:func:`field_figure`: the collapse
margin, a cylinder's overturning count or P(overturn) bound, the superstructure's shear coefficient, the
rotation) and the variants in the plane of the thesis's two curved-base design parameters (uplift force tan α,
Eq 3.34, and rotation capacity θc, Eq 3.56; :func:`thesis_plane_figure`).  :func:`design_figures` lists them;
a new chart is one more function and one more entry there.

Layout rules (tests/report/test_design_chart_layout.py reads them back): tick labels use the fewest digits that
tell neighbouring values apart and turn upright when they would touch; a cell's texts shrink (or break onto two
lines) to fit the cell; contour lines are named in the legend and marked on the colour bar, not labelled on the
map, where their labels fell on the cell values; variants at one point of the thesis plane are drawn side by
side, each with its own mark.
"""
from __future__ import annotations

import re

import numpy as np

from .. import mplfig as plt
from ..plots import STYLE, fit_text, legend_above, upright_ticks_if_crowded

COLORS = {"PASS": "#4daf4a", "FAIL": "#e41a1c", "INVALID": "#bdbdbd", "ERROR": "#444444"}
RECOMMENDED = {"edgecolor": "black", "lw": 2.2}
"""How the verdict chart frames the recommended cell."""


def cell_reason(cell: dict) -> str:
    """The governing reason of a cell in a few characters: "invalid", "failed", "3 unacc." (count rule),
    "ACMR 1.7" (collapse margin short), "2 incr." (pairs overturning at some intensity up to the design
    level, a cylinder's incremental count), "P ≤ 0.97" (the binomial bound of a cylinder under
    ``acceptance = "binomial"``; "P incr." when the incremental bound fails), or for a PASS the governing
    criterion's margin ("ACMR ×1.5", "0/1 unacc.", "P ≤ 0.78"); a PASS that is not robust "fails 1/3 draws"
    (or "margin ≈ req." when its ACMR is at its requirement); "not analysed" for a cell left out."""
    v = cell["verdict"]
    if not cell.get("analysed", True):
        return "not analysed"
    if v == "INVALID":
        return "invalid"
    if v == "ERROR" or cell.get("n_failed_analyses"):
        return "failed"
    k, a = cell.get("n_unacceptable"), cell.get("allowed_unacceptable")
    acmr, need = cell.get("acmr"), cell.get("acmr_required")
    bound = cell.get("p_overturn_bound") if cell.get("acceptance") == "binomial" else None
    if bound is not None:                      # the binomial rule decides (a cylinder under acceptance = "binomial")
        return f"P ≤ {bound:.2g}" if v == "PASS" or bound > cell["binomial_limit"] else "P incr."
    incremental = cell.get("n_incremental_unacceptable")
    if v == "FAIL":
        if k is not None and a is not None and k > a:
            return f"{k} unacc."
        if acmr is not None and need is not None and acmr < need:
            return f"ACMR {acmr:.2g}"
        if incremental is not None and a is not None and incremental > a:
            return f"{incremental} incr."
        return "fail"
    if cell.get("robust") is False:
        d = cell.get("draws") or {}
        return f"fails {d.get('failed', 0)}/{d.get('n', 0)} draws" if d.get("failed") else "margin ≈ req."
    if acmr is not None and need:
        return f"ACMR ×{acmr / need:.2g}"
    if k is not None and a is not None:
        return f"{k}/{a} unacc."
    return "pass"


def tick_labels(values) -> list[str]:
    """Labels of a variable's values with the fewest significant digits (2 to 4) that tell neighbours apart:
    0.2, 0.233, 0.267 … rather than 0.2333, 0.2667 (four digits made neighbouring ticks run together)."""
    for digits in (2, 3, 4):
        labels = [f"{v:.{digits}g}" for v in values]
        if len(set(labels)) == len(labels):
            return labels
    return [f"{v:.6g}" for v in values]


def _grid(data: dict, key: str) -> np.ndarray:
    shape = tuple(len(v["values"]) for v in data["variables"])
    out = np.full(shape, np.nan)
    for c in data["cells"]:
        x = c.get(key)
        if x is not None:
            out[tuple(c["index"])] = float(x)
    return out


def _axis_label(var: dict) -> str:
    return f"{var['key']} [{var['unit']}]" if var["unit"] not in ("", "1") else var["key"]


def _cell_axes(fig, ax, vars_) -> None:
    """Ticks at the cells of a one- or two-variable grid, labelled by :func:`tick_labels`."""
    nx = len(vars_[0]["values"])
    ax.set_xlim(-0.5, nx - 0.5)
    ax.set_xticks(range(nx))
    ax.set_xticklabels(tick_labels(vars_[0]["values"]))
    ax.set_xlabel(_axis_label(vars_[0]))
    if len(vars_) > 1:
        ny = len(vars_[1]["values"])
        ax.set_ylim(-0.5, ny - 0.5)
        ax.set_yticks(range(ny))
        ax.set_yticklabels(tick_labels(vars_[1]["values"]))
        ax.set_ylabel(_axis_label(vars_[1]))


def _lay_out(fig, ax) -> None:
    """Tight layout, then upright x tick labels if they would touch (and the layout again)."""
    fig.tight_layout()
    if upright_ticks_if_crowded(fig, ax):
        fig.tight_layout()


def verdict_figure(data: dict):
    """The pass/fail region: one coloured cell per variant with its verdict and governing reason, the recommended
    design framed in black, and the contour ACMR = ACMR required where the margin was evaluated."""
    vars_ = data["variables"]
    rec = data.get("recommended")
    one = len(vars_) == 1
    nx = len(vars_[0]["values"])
    ny = 1 if one else len(vars_[1]["values"])
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(6.6, 2.4 if one else 1.9 + 0.42 * ny))
        ax.grid(False)
        pairs = []
        for c in data["cells"]:
            i, j = (c["index"][0], 0) if one else c["index"]
            ax.add_patch(_cell_patch(i - 0.5, j - 0.5, c))
            pairs.append((ax.text(i, j + 0.17, _word(c), ha="center", va="center", fontsize=6.5, weight="bold"),
                          ax.text(i, j - 0.17, cell_reason(c), ha="center", va="center", fontsize=5.5)))
            if rec and list(c["index"]) == list(rec["index"]):
                from matplotlib.patches import Rectangle
                ax.add_patch(Rectangle((i - 0.47, j - 0.47), 0.94, 0.94, facecolor="none", zorder=3, **RECOMMENDED))
        _cell_axes(fig, ax, vars_)
        if one:
            ax.set_ylim(-0.5, 0.5)
            ax.set_yticks([])
        extra = []
        ratio = _grid(data, "acmr") / _grid(data, "acmr_required")
        if not one and np.isfinite(ratio).sum() >= 4 and min(nx, ny) >= 2:
            try:
                ax.contour(np.arange(nx), np.arange(ny), np.ma.masked_invalid(ratio.T), levels=[1.0], colors="k",
                           linewidths=1.2)
                extra.append(plt.Line2D([], [], color="k", lw=1.2, label="contour ACMR = ACMR required"))
            except ValueError:      # too few finite cells to draw the line
                pass
        ax.set_title("verdict per variant (black frame: recommended; under the verdict: the governing reason)",
                     fontsize=8)
        _lay_out(fig, ax)
        _legend(fig, data["cells"], extra + ([_recommended_handle()] if rec else []))
        _fit_cells(fig, ax, pairs, nx, ny)
        return fig


def _fit_cells(fig, ax, pairs, nx: int, ny: int) -> None:
    """Each cell's verdict and reason shrunk (or the reason broken onto two lines) to fit the cell; a reason that
    still does not fit is left out (the variants table gives it)."""
    fig.draw_without_rendering()
    renderer = fig._get_renderer()
    box = ax.get_window_extent(renderer)
    width = 0.9 * box.width / nx
    for word, reason in pairs:
        fit_text(word, width, renderer=renderer)
        if not fit_text(reason, width, renderer=renderer):
            reason.set_visible(False)
        elif "\n" in reason.get_text():
            x, y = word.get_position()
            word.set_y(y + 0.08)
            reason.set_y(y - 0.42)


def _word(cell: dict) -> str:
    """The word drawn in a cell: PASS, PASS?, FAIL, INVALID, ERROR, or "·" (not analysed)."""
    if not cell.get("analysed", True):
        return "·"
    if cell["verdict"] == "PASS" and cell.get("robust") is False:
        return "PASS?"
    return cell["verdict"]


REGIONS = (("robust PASS", {"facecolor": COLORS["PASS"], "alpha": 0.75}),
           ("PASS, not robust (fails in a perturbation draw)",
            {"facecolor": "white", "hatch": "////", "edgecolor": COLORS["PASS"], "alpha": 0.9}),
           ("FAIL", {"facecolor": COLORS["FAIL"], "alpha": 0.75}),
           ("not analysed (neighbours agree)", {"facecolor": "white", "edgecolor": "#999999", "linestyle": ":"}))
"""How the verdict chart draws each region (its legend)."""


def _region(cell: dict) -> str | None:
    if not cell.get("analysed", True):
        return REGIONS[3][0]
    if cell["verdict"] == "PASS":
        return REGIONS[0][0] if cell.get("robust") is not False else REGIONS[1][0]
    if cell["verdict"] == "FAIL":
        return REGIONS[2][0]
    return None


def _cell_patch(x, y, cell: dict):
    """The patch of one cell: filled (robust PASS, FAIL, INVALID, ERROR), hatched (PASS, not robust) or a
    dotted outline (not analysed)."""
    from matplotlib.patches import Rectangle
    style = dict(REGIONS).get(_region(cell))
    if style is None:
        return Rectangle((x, y), 1.0, 1.0, facecolor=COLORS[cell["verdict"]], edgecolor="white", lw=1.5, alpha=0.75)
    kw = {"edgecolor": "white", "lw": 1.5, **style}
    return Rectangle((x + 0.03, y + 0.03), 0.94, 0.94, **kw)


def _recommended_handle():
    from matplotlib.patches import Patch
    return Patch(facecolor="none", label="recommended design", **RECOMMENDED)


def _legend(fig, cells, extra=()) -> None:
    """The regions drawn (and ``extra`` handles), as a legend in a strip below the axes."""
    from matplotlib.patches import Patch
    shown = {_region(c) for c in cells}
    handles = [Patch(label=name, **{"edgecolor": "white", **style}) for name, style in REGIONS if name in shown]
    handles += list(extra)
    if handles:
        rows = -(-len(handles) // 3)
        strip = (0.18 + 0.14 * rows) / fig.get_figheight()          # below the axes' labels
        fig.subplots_adjust(bottom=fig.subplotpars.bottom + strip)
        fig.legend(handles=handles, fontsize=6, loc="lower center", bbox_to_anchor=(0.5, 0.0), ncol=3,
                   frameon=False)


def field_figure(data: dict, key: str, label: str, cmap: str = "viridis", levels=None, reference=None,
                 level_labels=None, title: str = ""):
    """One quantity of the cells over the grid: a coloured map with the value in each cell and contour lines where
    enough cells have it (2 variables; the lines marked on the colour bar and named in a legend below), or a line
    over the values (1 variable) with the ``reference`` lines [(value, text)] (e.g. the required ACMR).
    ``label``: the quantity with its unit (colour bar, y axis); ``title``: what it is, above the chart;
    ``level_labels`` {level: text} names the contour lines (default: "contours at the colour bar's lines")."""
    vars_ = data["variables"]
    z = _grid(data, key)
    if not np.isfinite(z).any():
        return None
    with plt.rc_context(STYLE):
        if len(vars_) == 1:
            fig, ax = plt.subplots(figsize=(6.6, 2.8))
            x = np.arange(len(vars_[0]["values"]))
            ax.plot(x, z, "o-", color="C0", label=label)
            for lv, text in (reference or ()):
                ax.axhline(lv, color="C3", lw=0.8, ls="--", label=text)
            legend_above(ax, ncol=3)
            _cell_axes(fig, ax, vars_)
            ax.set_ylabel(label, fontsize=7)
        else:
            nx, ny = z.shape
            fig, ax = plt.subplots(figsize=(6.6, max(2.8, 1.9 + 0.42 * ny)))
            ax.grid(False)
            im = ax.pcolormesh(np.arange(nx + 1) - 0.5, np.arange(ny + 1) - 0.5, np.ma.masked_invalid(z.T),
                               cmap=plt.get_cmap(cmap), shading="flat")
            bar = fig.colorbar(im, ax=ax)
            bar.set_label(label, fontsize=7)
            for i in range(nx):
                for j in range(ny):
                    if np.isfinite(z[i, j]):
                        ax.text(i, j, f"{z[i, j]:.3g}", ha="center", va="center", fontsize=6, color="k",
                                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.7})
            _cell_axes(fig, ax, vars_)
            handles = _contours(ax, bar, z, levels, level_labels)
            if handles:
                legend_above(ax, handles=handles, ncol=2)
        if title:
            fig.suptitle(title, fontsize=8, x=0.02, ha="left")
        _lay_out(fig, ax)
        return fig


CONTOUR_MIN_CELLS = 4
"""Contour lines of a field need this many cells along each variable: on a 3 × 3 grid they cut across the cells
between three values and read as more than the grid says."""


def _contours(ax, bar, z: np.ndarray, levels, level_labels) -> list:
    """Contour lines of ``z`` (where at least four cells have a value and each variable has
    :data:`CONTOUR_MIN_CELLS` values), marked on the colour bar; the legend handles that name them."""
    nx, ny = z.shape
    if np.isfinite(z).sum() < 4 or min(nx, ny) < CONTOUR_MIN_CELLS:
        return []
    styles = (["-", "--", ":", "-."] * 2)[:len(levels)] if levels else "-"
    try:
        cs = ax.contour(np.arange(nx), np.arange(ny), np.ma.masked_invalid(z.T), levels=levels or 5, colors="k",
                        linewidths=0.7, linestyles=styles)
    except (ValueError, TypeError):     # too few distinct finite values for contour lines
        return []
    if not len(cs.levels):
        return []
    bar.add_lines(cs)
    if level_labels:       # each named level its own line style (first solid, then dashed, dotted …)
        return [plt.Line2D([], [], color="k", lw=0.7, ls=styles[k] if levels else "-", label=f"contour: {text}")
                for k, text in enumerate(level_labels.values())]
    return [plt.Line2D([], [], color="k", lw=0.7, label="contours at the colour bar's black lines")]


def thesis_plane_figure(data: dict):
    """The variants in the plane of two of the kind's numbers (design.json ``plane``: for a planar kind the thesis's
    two curved-base design parameters, the uplift base-shear coefficient tan α, Eq 3.34, against the rotation
    capacity θc, Eq 3.56), one mark per analysed variant coloured by verdict (★ the recommended design) — where the
    passing region lies in the terms of the thesis's recommendation.  Variants that fall on one point (equal tan α,
    θc capped) are drawn as a small block of marks around it (:func:`_clustered`), each variant with a mark of its
    own.  None without a plane or with fewer than two variants in it."""
    plane = data.get("plane")
    if not plane:
        return None
    x, y = plane["x"], plane["y"]
    pts = [c for c in data["cells"] if c.get(x) is not None and c.get(y) is not None and c.get("analysed", True)]
    if len(pts) < 2:
        return None
    rec = data.get("recommended")
    best = [k for k, c in enumerate(pts) if rec and list(c["index"]) == list(rec["index"])]
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(6.0, 3.8))
        xy = np.array([[c[x], c[y]] for c in pts])
        _limits(ax, xy)
        ax.set_xlabel(plane["x_label"])
        ax.set_ylabel(plane["y_label"])
        styles = _plane_styles()
        for name in styles:                          # legend entries, in this order, for the styles drawn
            if any(_plane_style(c) == name for c in pts):
                ax.scatter([], [], label=name, **styles[name])
        if best:
            ax.scatter([], [], marker="*", s=STAR, facecolor="white", edgecolor="k", lw=0.8, label="recommended (★)")
        legend_above(ax, ncol=3)
        placed = _clustered(fig, ax, xy, step_pt=0.5 * (np.sqrt(MARK) + np.sqrt(STAR)) + 1.0)
        for name, style in styles.items():
            sel = [k for k, c in enumerate(pts) if _plane_style(c) == name and k not in best]
            if sel:
                ax.scatter(placed[sel, 0], placed[sel, 1], clip_on=False, **style)
            star = [k for k in best if _plane_style(pts[k]) == name]
            if star:
                ax.scatter(placed[star, 0], placed[star, 1], clip_on=False, **{**style, "marker": "*", "s": STAR})
        return fig


MARK = 18.0
"""Area [pt²] of a variant's mark in the thesis-plane chart."""
STAR = 60.0
"""Area [pt²] of the recommended design's ★ (the largest mark of the thesis-plane chart)."""


def _plane_styles() -> dict:
    return {"robust PASS": {"s": MARK, "color": COLORS["PASS"], "edgecolor": "k", "lw": 0.4},
            "PASS, not robust": {"s": MARK, "facecolor": "white", "edgecolor": COLORS["PASS"], "hatch": "////",
                                 "lw": 0.8},
            "FAIL": {"s": MARK, "color": COLORS["FAIL"], "edgecolor": "k", "lw": 0.4},
            "INVALID": {"s": MARK, "color": COLORS["INVALID"], "edgecolor": "k", "lw": 0.4},
            "ERROR": {"s": MARK, "color": COLORS["ERROR"], "edgecolor": "k", "lw": 0.4}}


def _plane_style(cell: dict) -> str:
    if cell["verdict"] == "PASS":
        return "robust PASS" if cell.get("robust") is not False else "PASS, not robust"
    return cell["verdict"] if cell["verdict"] in COLORS else "ERROR"


def _limits(ax, xy: np.ndarray) -> None:
    for setter, values in ((ax.set_xlim, xy[:, 0]), (ax.set_ylim, xy[:, 1])):
        lo, hi = float(values.min()), float(values.max())
        pad = 0.08 * (hi - lo) if hi > lo else 0.05 * abs(hi) or 0.05
        setter(lo - pad, hi + pad)


def _clustered(fig, ax, xy: np.ndarray, step_pt: float) -> np.ndarray:
    """The points ``xy`` (data) placed so that no two marks touch: each group of points closer than ``step_pt``
    (a mark's width and a gap) is drawn as a compact block of marks (⌈√k⌉ columns) centred on the group's mean
    position, ``step_pt`` apart, highest θc first — a mark stays within about one mark width of its point."""
    fig.tight_layout()
    step = step_pt * fig.dpi / 72.0
    screen = ax.transData.transform(xy)
    out = screen.copy()
    for group in _groups(screen, step):
        if len(group) < 2:
            continue
        group = sorted(group, key=lambda m: (-xy[m, 1], xy[m, 0]))
        cols = int(np.ceil(np.sqrt(len(group))))
        rows = int(np.ceil(len(group) / cols))
        centre = screen[group].mean(axis=0)
        for n, k in enumerate(group):
            row, col = divmod(n, cols)
            out[k] = (centre[0] + (col - (cols - 1) / 2) * step, centre[1] - (row - (rows - 1) / 2) * step)
    return ax.transData.inverted().transform(out)


def _groups(screen: np.ndarray, step: float) -> list[list[int]]:
    """Points [px] chained together by distances below ``step``."""
    groups: list[list[int]] = []
    for k in np.lexsort((screen[:, 1], screen[:, 0])):
        near = [g for g in groups if any(np.hypot(*(screen[k] - screen[m])) < step for m in g)]
        merged = [int(k)] + [m for g in near for m in g]
        groups = [g for g in groups if g not in near] + [merged]
    return groups


def overturning_figure(data: dict):
    """The overturning numbers of cells that carry them (a cylinder's record pairs, thesis Sec 5.5.1): under
    ``acceptance = "binomial"`` the one-sided 95 % bound of P(overturn) with the limit as reference and
    contour (the pass/fail boundary of the design level), otherwise the pairs that overturn at the design
    level with the allowance (ASCE 7-22 §16.4.1.1); None when no cell has them."""
    cells = [c for c in data["cells"] if c.get("p_overturn_bound") is not None]
    if not cells:
        return None
    if all(c.get("acceptance") == "binomial" for c in cells):
        limits = sorted({c["binomial_limit"] for c in cells})
        return field_figure(data, "p_overturn_bound", "P(overturn), 95 % bound [-]", "magma_r",
                            levels=limits, reference=[(v, f"limit {v:.3g}") for v in limits],
                            level_labels={v: f"limit {v:.3g}" for v in limits})
    allowed = sorted({c["allowed_unacceptable"] for c in cells if c.get("allowed_unacceptable") is not None})
    return field_figure(data, "n_unacceptable", "pairs overturning [-]", "magma_r",
                        levels=[a + 0.5 for a in allowed], reference=[(a, f"{a} allowed") for a in allowed],
                        level_labels={a + 0.5: f"{a} allowed" for a in allowed},
                        title="record pairs overturning at the design level")


def flip_figure(data: dict):
    """The distance of each analysed cell's verdict to its flip (:mod:`rockdesign.acceptance.flip`): the factor λ
    on the design intensity at which it changes, with the contour λ = 1 (the edge between passing and failing) and
    λ = FAR (far from the flip: where the grid may infer a cell)."""
    from ..acceptance.flip import FAR
    return field_figure(data, "flip_margin", "λ at the flip [× design intensity]", "RdYlGn",
                        levels=[1.0, FAR], reference=[(1.0, "the flip: λ = 1"), (FAR, f"far: λ = {FAR:g}")],
                        level_labels={1.0: "the flip: λ = 1", FAR: f"far from the flip: λ = {FAR:g}"},
                        title="distance of the verdict to its flip (> 1 passes)")


def design_figures(data: dict) -> dict:
    """All figures of a design chart (matplotlib Figures; None where a figure has no data)."""
    symbol = re.sub(r"_([A-Za-z0-9]+)", r"$_{\1}$", (data.get("response") or {}).get("symbol") or "response ratio")
    required = sorted({c["acmr_required"] for c in data["cells"] if c.get("acmr_required")})
    return {
        "verdict": verdict_figure(data),
        "acmr": field_figure(data, "acmr", "ACMR [-]", "viridis",
                             reference=[(v, f"required {v:.3g}") for v in required],
                             title="adjusted collapse margin ratio (FEMA P695 Eq 7-4, adapted)"),
        "flip": flip_figure(data),
        "overturning": overturning_figure(data),
        "shear": field_figure(data, "superstructure_shear_p84", "|f$_s$|/g, 84th pct [-]", "magma_r",
                              title="superstructure shear coefficient, 84th percentile"),
        "rotation": field_figure(data, "median_theta_max_over_theta_c", f"median {symbol} [-]",
                                 "cividis_r", title="median peak response over the capacity"),
        "thesis_plane": thesis_plane_figure(data),
    }
