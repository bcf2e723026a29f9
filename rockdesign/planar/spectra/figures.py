"""Figures of rocking spectra (matplotlib Agg; each written as PNG and SVG).

* ``theta_max`` — θ_max/α over the grid (thesis Figs 3.19a–3.20a, 4.6–4.7) with the limit-state
  contours I–III, the overturning boundary (IV) and Polyakov's overturning line (white dashes).
* ``overturning`` — safe / overturned with 0, 1, 2+ impacts (Figs 2.4a, 3.19b–3.20b), the minimum
  overturning acceleration line and Polyakov's line.
* ``limit_states`` — the limit-state lines I–IV of Table 3.5 (Fig 3.21), with Polyakov's line.
* ``relative`` — Δθ_max/α against a reference system (Eq 3.64, Fig 3.22), both overturning lines
  and the Eq 3.65 reading points.

Maps are drawn as images (one pixel per grid point), so the SVG files stay small.
"""
from __future__ import annotations

import math
from pathlib import Path


from ... import mplfig as plt  # noqa: E402  (pyplot-free Figures: importing never switches the backend)
import numpy as np  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from .lines import LIMIT_STATES  # noqa: E402

STYLE = {"figure.dpi": 110, "font.size": 9, "axes.grid": False, "savefig.bbox": "tight",
         "svg.fonttype": "none"}
LS_COLORS = {"I": "#1b9e77", "II": "#d95f02", "III": "#7570b3", "IV": "#000000"}
OT_COLORS = ["#ffffff", "#4d4d4d", "#b2182b", "#f4a582"]  # safe, 0, 1, 2+ impacts


def _extent(x, y):
    def edges(v):
        if v.size == 1:
            return v[0] - 0.5, v[0] + 0.5
        d = (v[-1] - v[0]) / (v.size - 1)
        return v[0] - d / 2, v[-1] + d / 2
    x0, x1 = edges(np.asarray(x, float))
    y0, y1 = edges(np.asarray(y, float))
    return [x0, x1, y0, y1]


def _image(ax, x, y, data, **kw):
    return ax.imshow(data, origin="lower", extent=_extent(x, y), aspect="auto", interpolation="nearest", **kw)


def _period_axis(ax, ctx):
    """A secondary x axis in T_p [s] for frequency axes (as thesis Figs 4.6–4.7)."""
    if ctx["x_name"] == "Tp":
        return
    p = ctx["p_axis"]

    def f(x):
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(x > 0, 2 * math.pi / (np.maximum(x, 1e-12) * p), np.inf)

    sec = ax.secondary_xaxis("top", functions=(f, f))
    t_lo, t_hi = sorted(f(np.array([ctx["x"][0], ctx["x"][-1]])))
    nice = [0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 20.0, 50.0]
    span = abs(ctx["x"][-1] - ctx["x"][0])
    ticks, last = [], None
    for t in sorted((t for t in nice if t_lo <= t <= t_hi), key=lambda t: -float(f(t))):
        xt = float(f(t))
        if last is None or abs(last - xt) >= span / 14:   # T_p ∝ 1/x crowds at small x
            ticks.append(t)
            last = xt
    if len(ticks) >= 2:
        from matplotlib.ticker import FixedLocator, FuncFormatter
        sec.xaxis.set_major_locator(FixedLocator(sorted(ticks)))
        sec.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    sec.set_xlabel("T_p [s]")


def polyakov_label(u_capacity: float | None) -> str:
    """Legend of Polyakov's line: SD_max equals the displacement capacity u_B(θc) (2B only for a flat
    block; docs/model.md §6)."""
    if u_capacity is None:
        return "Polyakov: SD_max = u_B(θc)"
    return f"Polyakov: SD_max = u_B(θc) = {u_capacity:.3g} m"


def _overlay_polyakov(ax, x, polyakov, y_hi, color="white", u_capacity=None):
    if polyakov is None:
        return None
    py = np.where(np.asarray(polyakov) <= y_hi * 1.05, polyakov, np.nan)
    (h,) = ax.plot(x, py, ls="--", color=color, lw=1.3, label=polyakov_label(u_capacity))
    return h


def _finish(ax, ctx, title):
    ax.set_xlabel(ctx["x_label"])
    ax.set_ylabel(ctx["y_label"])
    ax.set_xlim(ctx["x"][0], ctx["x"][-1])
    ax.set_ylim(ctx["y"][0], ctx["y"][-1])
    ax.set_title(title, fontsize=9, loc="left")
    _period_axis(ax, ctx)


def theta_max_figure(ctx: dict):
    """θ_max/α map with limit-state contours, overturning boundary and Polyakov's line."""
    x, y = ctx["x"], ctx["y"]
    cap = ctx["cap"]
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(7.2, 4.8))
        psi = np.ma.masked_where(ctx["overturned"], np.minimum(ctx["psi"], cap))
        cmap = plt.get_cmap("viridis").with_extremes(bad="black")
        im = _image(ax, x, y, psi, cmap=cmap, vmin=0.0, vmax=cap)
        cb = fig.colorbar(im, ax=ax, pad=0.02)
        cb.set_label("θ_max / α  (overturned: black)")
        handles = []
        for name, level in LIMIT_STATES:
            paths = ctx["contours"].get(name, [])
            for k, pth in enumerate(paths):
                ax.plot(pth[:, 0], pth[:, 1], color="white" if name == "IV" else LS_COLORS[name], lw=0.9,
                        ls="-" if name != "IV" else ":")
            label = f"{name}: θ_max = {level:g}α" if level is not None else "IV: overturning"
            handles.append(Line2D([], [], color=LS_COLORS[name] if name != "IV" else "0.6", lw=1.2,
                                  ls="-" if name != "IV" else ":", label=label))
        h = _overlay_polyakov(ax, x, ctx.get("polyakov"), y[-1], u_capacity=ctx.get("u_capacity"))
        if h is not None:
            handles.append(Line2D([], [], color="0.4", ls="--", label=h.get_label()))
        ax.legend(handles=handles, loc="upper right", fontsize=7, framealpha=0.8)
        _finish(ax, ctx, ctx["title"] + " — maximum tilt θ_max/α")
        return fig


def overturning_figure(ctx: dict):
    """Safe / overturned with 0, 1, 2+ impacts, minimum overturning line, Polyakov's line."""
    x, y = ctx["x"], ctx["y"]
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(7.2, 4.8))
        cls = ctx["classes"].astype(float) + 1.0  # 0 safe, 1: 0 impacts, 2: 1 impact, 3: 2+
        cmap = ListedColormap(OT_COLORS)
        norm = BoundaryNorm([-0.5, 0.5, 1.5, 2.5, 3.5], cmap.N)
        _image(ax, x, y, cls, cmap=cmap, norm=norm)
        ax.plot(x, ctx["min_overturn"], color="black", lw=1.0, label="minimum overturning acceleration")
        h = _overlay_polyakov(ax, x, ctx.get("polyakov"), y[-1], color="#2166ac",
                          u_capacity=ctx.get("u_capacity"))
        counts = ctx["class_counts"]
        handles = [Patch(facecolor=OT_COLORS[0], edgecolor="0.5", label=f"safe ({counts['safe']})"),
                   Patch(facecolor=OT_COLORS[1], label=f"overturn, 0 impacts ({counts['0']})"),
                   Patch(facecolor=OT_COLORS[2], label=f"overturn, 1 impact ({counts['1']})"),
                   Patch(facecolor=OT_COLORS[3], label=f"overturn, 2+ impacts ({counts['2+']})"),
                   Line2D([], [], color="black", label="minimum overturning acceleration")]
        if h is not None:
            handles.append(h)
        ax.legend(handles=handles, loc="upper right", fontsize=7, framealpha=0.85)
        _finish(ax, ctx, ctx["title"] + f" — overturning ({ctx['criterion']})")
        return fig


def limit_states_figure(ctx: dict):
    """Limit-state lines I–IV (thesis Table 3.5, Fig 3.21) and Polyakov's line."""
    x, y = ctx["x"], ctx["y"]
    with plt.rc_context(dict(STYLE, **{"axes.grid": True, "grid.alpha": 0.3})):
        fig, ax = plt.subplots(figsize=(7.2, 4.8))
        for name, level in LIMIT_STATES:
            label = f"{name}: θ_max = {level:g}α" if level is not None else "IV: overturning"
            ax.plot(x, ctx["limit_states"][name], color=LS_COLORS[name], lw=1.2, label=label)
            if ctx.get("reference_limit_states") is not None:
                ax.plot(x, ctx["reference_limit_states"][name], color=LS_COLORS[name], lw=0.9, ls="--")
        if ctx.get("reference_limit_states") is not None:
            ax.plot([], [], color="0.4", ls="--", label=f"reference: {ctx['reference_title']}")
        _overlay_polyakov(ax, x, ctx.get("polyakov"), y[-1], color="#2166ac",
                          u_capacity=ctx.get("u_capacity"))
        ax.legend(loc="upper left", fontsize=7)
        _finish(ax, ctx, ctx["title"] + " — limit-state lines (Table 3.5)")
        return fig


def relative_figure(ctx: dict):
    """Δθ_max/α against the reference (Eq 3.64, Fig 3.22) with both overturning lines (Eq 3.65 points)."""
    x, y = ctx["x"], ctx["y"]
    lim = ctx["cap"] - 1.0 if ctx["cap"] > 1.0 else 0.5
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(7.2, 4.8))
        im = _image(ax, x, y, ctx["delta"], cmap="RdBu_r", vmin=-max(lim, 0.5), vmax=max(lim, 0.5))
        cb = fig.colorbar(im, ax=ax, pad=0.02)
        cb.set_label("Δθ_max/α = project − reference (overturned = %.2g)" % ctx["cap"])
        ax.plot(x, ctx["limit_states"]["IV"], color="black", lw=1.1, label="overturning: project")
        ax.plot(x, ctx["reference_limit_states"]["IV"], color="black", lw=1.1, ls="--",
                label=f"overturning: {ctx['reference_title']}")
        eq = ctx.get("equivalent") or {}
        for y0, a, b, r in zip(eq.get("ordinates", []), eq.get("x_reference", []), eq.get("x_project", []),
                               eq.get("R_hat_over_R", [])):
            if a is not None and b is not None:
                ax.plot([b, a], [y0, y0], "o-", color="0.35", ms=3.5, lw=0.8)
                ax.annotate(f"R̂/R = {r:.3g}", (max(a, b), y0), xytext=(4, 2), textcoords="offset points",
                            fontsize=6.5)
        ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
        _finish(ax, ctx, ctx["title"] + " — relative spectrum (Eq 3.64)")
        return fig


def save_both(fig, out_dir: Path, stem: str) -> list[str]:
    """Write ``stem.png`` and ``stem.svg`` in ``out_dir``; returns the file names."""
    names = []
    for ext in ("png", "svg"):
        path = Path(out_dir) / f"{stem}.{ext}"
        fig.savefig(path, dpi=150 if ext == "png" else None)
        names.append(path.name)
    plt.close(fig)
    return names
