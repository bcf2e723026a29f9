"""Figures of a design chart (SPEC §15): the pass/fail region with the governing reason per cell, the
collapse margin, a cylinder's overturning count or P(overturn) bound and the superstructure's shear
coefficient over the one or two varied keys, and the
variants in the plane of the thesis's two curved-base design parameters (uplift force tan α, Eq 3.34,
and rotation capacity θc, Eq 3.56)."""
from __future__ import annotations

import numpy as np

from .. import mplfig as plt
from ..plots import STYLE

COLORS = {"PASS": "#4daf4a", "FAIL": "#e41a1c", "INVALID": "#bdbdbd", "ERROR": "#444444"}


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


def verdict_figure(data: dict):
    """The pass/fail region: one coloured cell per variant with its governing reason, the recommended
    design marked ★, and the contour ACMR = ACMR required where the margin was evaluated."""
    vars_ = data["variables"]
    rec = data.get("recommended")
    with plt.rc_context(STYLE):
        if len(vars_) == 1:
            fig, ax = plt.subplots(figsize=(6.6, 2.2))
            xs = np.arange(len(vars_[0]["values"]))
            for c in data["cells"]:
                i = c["index"][0]
                ax.add_patch(_cell_patch(i - 0.5, -0.5, c))
                ax.text(i, 0.12, _word(c), ha="center", va="center", fontsize=7, weight="bold")
                ax.text(i, -0.18, cell_reason(c), ha="center", va="center", fontsize=6)
            if rec:
                ax.plot(rec["index"][0], 0.38, "*", ms=11, color="k")
            ax.set_xlim(-0.5, len(xs) - 0.5)
            ax.set_ylim(-0.5, 0.5)
            ax.set_yticks([])
            ax.set_xticks(xs)
            ax.set_xticklabels([f"{v:.4g}" for v in vars_[0]["values"]])
            ax.set_xlabel(_axis_label(vars_[0]))
        else:
            nx, ny = len(vars_[0]["values"]), len(vars_[1]["values"])
            fig, ax = plt.subplots(figsize=(6.6, 1.6 + 0.42 * ny))
            for c in data["cells"]:
                i, j = c["index"]
                ax.add_patch(_cell_patch(i - 0.5, j - 0.5, c))
                ax.text(i, j + 0.12, _word(c), ha="center", va="center", fontsize=6.5, weight="bold")
                ax.text(i, j - 0.2, cell_reason(c), ha="center", va="center", fontsize=5.5)
            ratio = _grid(data, "acmr") / _grid(data, "acmr_required")
            if np.isfinite(ratio).sum() >= 4 and min(nx, ny) >= 2:
                masked = np.ma.masked_invalid(ratio.T)
                try:
                    cs = ax.contour(np.arange(nx), np.arange(ny), masked, levels=[1.0], colors="k", linewidths=1.2)
                    ax.clabel(cs, fmt={1.0: "ACMR = required"}, fontsize=6)
                except ValueError:      # too few finite cells to draw the line
                    pass
            if rec:
                ax.plot(rec["index"][0], rec["index"][1] + 0.36, "*", ms=10, color="k")
            ax.set_xlim(-0.5, nx - 0.5)
            ax.set_ylim(-0.5, ny - 0.5)
            ax.set_xticks(range(nx))
            ax.set_xticklabels([f"{v:.4g}" for v in vars_[0]["values"]])
            ax.set_yticks(range(ny))
            ax.set_yticklabels([f"{v:.4g}" for v in vars_[1]["values"]])
            ax.set_xlabel(_axis_label(vars_[0]))
            ax.set_ylabel(_axis_label(vars_[1]))
        ax.set_title("verdict per variant (★ recommended; the text gives the governing reason)", fontsize=8)
        fig.tight_layout()
        _legend(fig, data["cells"])
        return fig


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
        return _rect(x, y, COLORS[cell["verdict"]])
    kw = {"edgecolor": "white", "lw": 1.5, **style}
    return Rectangle((x + 0.03, y + 0.03), 0.94, 0.94, **kw)


def _legend(fig, cells) -> None:
    """The regions drawn, as a legend in a strip below the axes."""
    from matplotlib.patches import Patch
    shown = {_region(c) for c in cells}
    handles = [Patch(label=name, **{"edgecolor": "white", **style}) for name, style in REGIONS if name in shown]
    if handles:
        strip = 0.3 / fig.get_figheight()          # 0.3 inch below the axes' labels
        fig.subplots_adjust(bottom=fig.subplotpars.bottom + strip)
        fig.legend(handles=handles, fontsize=6, loc="lower center", bbox_to_anchor=(0.5, 0.0),
                   ncol=min(4, len(handles)), frameon=False)


def _rect(x, y, color):
    from matplotlib.patches import Rectangle
    return Rectangle((x, y), 1.0, 1.0, facecolor=color, edgecolor="white", lw=1.5, alpha=0.75)


def field_figure(data: dict, key: str, title: str, cmap: str = "viridis", levels=None, reference=None,
                 level_labels=None):
    """One quantity of the cells over the grid: a coloured map with the value in each cell and contour
    lines where enough cells have it (2 variables), or a line over the values (1 variable) with the
    ``reference`` lines [(value, label)] (e.g. the required ACMR); ``level_labels`` {level: text} names the
    contour lines (default: their values)."""
    vars_ = data["variables"]
    z = _grid(data, key)
    if not np.isfinite(z).any():
        return None
    with plt.rc_context(STYLE):
        if len(vars_) == 1:
            fig, ax = plt.subplots(figsize=(6.6, 2.6))
            x = np.array(vars_[0]["values"])
            ax.plot(x, z, "o-", color="C0")
            for lv, text in (reference or ()):
                ax.axhline(lv, color="C3", lw=0.8, ls="--", label=text)
            if reference:
                ax.legend(fontsize=7)
            pad = 0.05 * (x.max() - x.min() or 1.0)
            ax.set_xlim(x.min() - pad, x.max() + pad)
            ax.set_xlabel(_axis_label(vars_[0]))
            ax.set_ylabel(title, fontsize=7)
        else:
            nx, ny = z.shape
            fig, ax = plt.subplots(figsize=(6.6, 1.6 + 0.42 * ny))
            im = ax.pcolormesh(np.arange(nx + 1) - 0.5, np.arange(ny + 1) - 0.5, np.ma.masked_invalid(z.T),
                               cmap=plt.get_cmap(cmap), shading="flat")
            fig.colorbar(im, ax=ax, label=title)
            for i in range(nx):
                for j in range(ny):
                    if np.isfinite(z[i, j]):
                        ax.text(i, j, f"{z[i, j]:.3g}", ha="center", va="center", fontsize=6, color="k",
                                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.7})
            if np.isfinite(z).sum() >= 4 and min(nx, ny) >= 2:
                try:
                    cs = ax.contour(np.arange(nx), np.arange(ny), np.ma.masked_invalid(z.T), levels=levels or 5,
                                    colors="k", linewidths=0.7)
                    ax.clabel(cs, fontsize=6, fmt=level_labels or "%.3g")
                except (ValueError, TypeError):     # too few distinct finite values for contour lines
                    pass
            ax.set_xticks(range(nx))
            ax.set_xticklabels([f"{v:.4g}" for v in vars_[0]["values"]])
            ax.set_yticks(range(ny))
            ax.set_yticklabels([f"{v:.4g}" for v in vars_[1]["values"]])
            ax.set_xlabel(_axis_label(vars_[0]))
            ax.set_ylabel(_axis_label(vars_[1]))
        fig.tight_layout()
        return fig


def thesis_plane_figure(data: dict):
    """The variants in the plane of the thesis's two curved-base design parameters: the uplift base-shear
    coefficient tan α (Eq 3.34, the uplift force) against the rotation capacity θc (Eq 3.56), coloured by
    verdict — where the passing region lies in the terms of the thesis's recommendation."""
    pts = [c for c in data["cells"] if c.get("uplift_shear_coefficient") is not None and c.get("theta_c") is not None]
    if len(pts) < 2:
        return None
    rec = data.get("recommended")
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(6.0, 3.4))
        for v, col in COLORS.items():
            sel = [c for c in pts if c["verdict"] == v and c.get("analysed", True)]
            if sel:
                ax.scatter([c["uplift_shear_coefficient"] for c in sel], [c["theta_c"] for c in sel], s=36,
                           color=col, edgecolor="k", lw=0.4, label=v)
        if rec:
            best = next(c for c in pts if c["index"] == rec["index"])
            fragile = [c for c in pts if c["verdict"] == "PASS" and c.get("robust") is False]
            if fragile:
                ax.scatter([c["uplift_shear_coefficient"] for c in fragile], [c["theta_c"] for c in fragile], s=36,
                           facecolor="white", edgecolor=COLORS["PASS"], hatch="////", lw=0.8, label="PASS, not robust")
            ax.plot(best["uplift_shear_coefficient"], best["theta_c"], "*", ms=14, color="k", label="recommended")
        ax.set_xlabel("uplift base-shear coefficient tan α [-] (Eq 3.34)")
        ax.set_ylabel("rotation capacity θc [rad] (Eq 3.56)")
        ax.legend(fontsize=7)
        fig.tight_layout()
        return fig


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
    return field_figure(data, "n_unacceptable", "pairs overturning at design [-]", "magma_r",
                        levels=[a + 0.5 for a in allowed], reference=[(a, f"{a} allowed") for a in allowed],
                        level_labels={a + 0.5: f"{a} allowed" for a in allowed})


def design_figures(data: dict) -> dict:
    """All figures of a design chart (matplotlib Figures; None where a figure has no data)."""
    capacity = "θ_ot" if any(c.get("theta_overturn") is not None for c in data["cells"]) else "θc"
    return {
        "verdict": verdict_figure(data),
        "acmr": field_figure(data, "acmr", "ACMR [-] (FEMA P695, Eq 7-4 adapted)", "viridis",
                             reference=[(v, f"required {v:.3g}") for v in sorted(
                                 {c["acmr_required"] for c in data["cells"] if c.get("acmr_required")})]),
        "overturning": overturning_figure(data),
        "shear": field_figure(data, "superstructure_shear_p84", "superstructure shear coefficient, 84th pct [-]",
                              "magma_r"),
        "rotation": field_figure(data, "median_theta_max_over_theta_c", f"median θ_max/{capacity} [-]", "cividis_r"),
        "thesis_plane": thesis_plane_figure(data),
    }
