"""Figures of the work-precision study (PNG + SVG): per-problem charts, overviews, error histories.

Work-precision charts plot an error (y) against the median wall time of the public call (x), both
logarithmic, one line per method through its tolerance sweep (labels: log10 rtol).  Errors that are
exactly zero (e.g. θ_max of free vibration, which is θ0) are drawn at :data:`FLOOR`.  The dashed
grey line is the estimated error of the reference: errors below it are not resolved.
"""
from __future__ import annotations

import math
from pathlib import Path


from .. import mplfig as plt  # noqa: E402  (pyplot-free Figures: importing never switches the backend)
import numpy as np  # noqa: E402

from ..plots import STYLE  # noqa: E402

FLOOR = 1e-16
COLORS = {"rockdesign": "C3", "rockdesign linear-exact": "k", "rockdesign DP5(4)": "C5", "rockdesign DOP853": "C6",
          "scipy RK45": "C0", "scipy DOP853": "C2", "scipy LSODA": "C4", "scipy Radau": "C1"}
MARKERS = {"rockdesign": "o", "rockdesign linear-exact": "*", "rockdesign DP5(4)": "<", "rockdesign DOP853": ">",
           "scipy RK45": "s", "scipy DOP853": "D", "scipy LSODA": "v", "scipy Radau": "^"}
PANELS = (("error_theta", "max |Δθ| over the history [rad]", "theta"),
          ("error_theta_max", "|Δθ_max| [rad]", "theta_max"),
          ("error_impact_times", "max |Δt| of the first impacts [s]", "impact_times"))


def save_both(fig, out_dir: Path, stem: str) -> list[Path]:
    """Write ``stem.png`` and ``stem.svg`` in ``out_dir`` and close the figure; returns the paths."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = [out_dir / f"{stem}.png", out_dir / f"{stem}.svg"]
    for p in paths:
        fig.savefig(p)
    plt.close(fig)
    return paths


def _floor(values):
    return [max(v, FLOOR) if v is not None and math.isfinite(v) else np.nan for v in values]


def _draw_method_lines(ax, prob: dict, key: str, label_tolerances: bool) -> None:
    for m in prob["methods"]:
        pts = sorted(m["points"], key=lambda q: -q["tolerance"])
        if not pts and not m["failures"]:
            continue
        name = m["name"]
        label = name + (f" ({len(m['failures'])} crashed)" if m["failures"] else "")
        if not pts:
            ax.plot([], [], color=COLORS.get(name, "0.5"), marker=MARKERS.get(name, "o"), ls="", label=label)
            continue
        x = [q["seconds"] for q in pts]
        y = _floor([q[key] for q in pts])
        single = len(pts) == 1
        ax.plot(x, y, color=COLORS.get(name, "0.5"), marker=MARKERS.get(name, "o"), ms=9 if single else 4,
                lw=1.2, ls="" if single else "-", label=label)
        if label_tolerances and m["family"] != "closed-form":
            for q, xx, yy in zip(pts, x, y):
                ax.annotate(f"{math.log10(q['tolerance']):.0f}", (xx, yy), textcoords="offset points",
                            xytext=(3, 2), fontsize=6, color=COLORS.get(name, "0.5"))


def problem_figure(prob: dict):
    """Three work-precision panels (θ history, θ_max, impact times) of one bench.json problem."""
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(1, 3, figsize=(12.0, 3.8))
        bound = prob["reference"]["error_bound"]
        for ax, (key, ylabel, bkey) in zip(axes, PANELS):
            _draw_method_lines(ax, prob, key, label_tolerances=key == "error_theta")
            b = bound.get(bkey)
            if isinstance(b, (int, float)) and b > 0:
                ax.axhline(max(b, FLOOR), color="0.5", ls="--", lw=0.8, label="reference error bound")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("median wall time [s]")
            ax.set_ylabel(ylabel)
            values = [q[key] for m in prob["methods"] for q in m["points"]]
            if values and all(v == 0.0 for v in values):
                ax.text(0.5, 0.6, "all errors exactly 0\n(drawn at 1e-16)", transform=ax.transAxes, ha="center",
                        fontsize=8, color="0.4")
        axes[0].legend(fontsize=6.5, loc="best")
        fig.suptitle(f"{prob['name']} — {prob['system']}: {prob['description']} "
                     f"(reference: {prob['reference']['kind']})", fontsize=9, x=0.01, ha="left")
        fig.tight_layout()
        return fig


def overview_figure(problems: list[dict], title: str):
    """Grid of error_theta charts: rows = systems, columns = excitations."""
    systems = list(dict.fromkeys(p["system"] for p in problems))
    names = list(dict.fromkeys(p["name"] for p in problems))
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(len(systems), len(names), figsize=(3.8 * len(names), 3.0 * len(systems)),
                                 squeeze=False)
        for i, s in enumerate(systems):
            for j, n in enumerate(names):
                ax = axes[i][j]
                prob = next((p for p in problems if p["system"] == s and p["name"] == n), None)
                if prob is None:
                    ax.set_visible(False)
                    continue
                _draw_method_lines(ax, prob, "error_theta", label_tolerances=False)
                b = prob["reference"]["error_bound"].get("theta")
                if isinstance(b, (int, float)) and b > 0:
                    ax.axhline(max(b, FLOOR), color="0.5", ls="--", lw=0.8)
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.set_title(f"{n} / {s}", fontsize=8)
                if j == 0:
                    ax.set_ylabel("max |Δθ| [rad]")
                if i == len(systems) - 1:
                    ax.set_xlabel("median wall time [s]")
        handles, labels = [], []
        for ax in axes.flat:
            for h, lab in zip(*ax.get_legend_handles_labels()):
                base = lab.split(" (")[0]
                if base not in labels:
                    handles.append(h)
                    labels.append(base)
        fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8, frameon=False)
        fig.suptitle(title, fontsize=10)
        fig.tight_layout(rect=(0, 0.04, 1, 0.97))
        return fig


def error_history_figure(histories: dict, title: str):
    """|Δθ|(t) of each method at several tolerances — the analogue of thesis Fig B.3."""
    methods = list(dict.fromkeys(k[0] for k in histories))
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(len(methods), 1, figsize=(7.5, 1.7 * len(methods) + 0.6), sharex=True,
                                 sharey=True, squeeze=False)
        for ax, name in zip(axes[:, 0], methods):
            keys = sorted((k for k in histories if k[0] == name), key=lambda k: -k[1])
            for n, k in enumerate(keys):
                t, err = histories[k]
                lab = "closed form" if k[1] < 1e-15 else f"rtol = 1e{math.log10(k[1]):.0f}"
                ax.semilogy(t, np.maximum(err, FLOOR), lw=0.7, color=f"C{n}", label=lab)
            ax.set_title(name, fontsize=8, loc="left")
            ax.set_ylabel("|Δθ| [rad]")
            ax.legend(fontsize=6.5, loc="lower right", ncol=3)
        axes[-1, 0].set_xlabel("t [s]")
        fig.suptitle(title, fontsize=9)
        fig.tight_layout()
        return fig


def write_study_figures(study: dict, out_dir: Path, histories: dict | None = None) -> list[Path]:
    """All work-precision figures of a study into ``out_dir`` (PNG + SVG); returns the written paths."""
    out_dir = Path(out_dir)
    written: list[Path] = []
    for prob in study["problems"]:
        stem = f"wp_{prob['name']}_{prob['system']}"
        written += save_both(problem_figure(prob), out_dir, stem)
    for eq, label in (("exact", "exact equations, converged reference"),
                      ("linear", "linearized equations, closed-form reference")):
        probs = [p for p in study["problems"] if p["equations"] == eq]
        if probs:
            fig = overview_figure(probs, f"Work-precision: {label} (error in θ against median wall time)")
            written += save_both(fig, out_dir, f"wp_overview_{eq}")
    if histories:
        from .runner import HISTORY_PROBLEM
        fig = error_history_figure(histories, f"Error against time, {HISTORY_PROBLEM} (cf. thesis Fig B.3)")
        written += save_both(fig, out_dir, "wp_error_history")
    return written
