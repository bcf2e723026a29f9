"""The figures of the calculation report (matplotlib, Agg), returned as inline SVG text.

Each ``*_figure`` function takes the :class:`~rockdesign.planar.checks.check.CheckResult` (or the data of one
figure the check computed, ``result.figure_data``) and returns a matplotlib figure: it draws, it computes no
physics (tests/report/test_renders_only.py); :func:`svg` turns a figure into SVG markup that can be pasted into
the HTML report (ids prefixed so several figures can share one document, no date metadata, so the
markup is reproducible).  Numbers on the figures use :func:`rockdesign.report.formatting.fmt`.
"""
from __future__ import annotations

import math


from ... import mplfig as plt  # noqa: E402  (pyplot-free Figures: importing never switches the backend)
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

from ..checks.polyakov import CLASS_MEANING, CLASSES  # noqa: E402
from ...report.formatting import fmt, number, plural  # noqa: E402
from ...plots import STYLE, clear_position, legend_above  # noqa: E402
from .history import time_history_figure  # noqa: E402

CLASS_COLOURS = {"a1": "#2c7fb8", "a2": "#7fcdbb", "b": "#d7301f", "c": "#fdae61", "d": "#7f2704"}
"""Colours of the Fig 4.9 classes."""
HISTORY_CLIP = 2.0
"""Time histories of overturning records are drawn up to ±HISTORY_CLIP·θc (and ±HISTORY_CLIP·u_B(θc))."""
SCATTER_Y_TOP = 1.6
"""Top of the Fig 4.9 scatter (overturned records are drawn at min(y, top) with their own marker)."""


def pushover_figure(curve: dict):
    """Static pushover curve F_R/(m_C g) against θ (Fig 3.15), with uplift, β and θc marked: ``curve`` is the
    check's :func:`~rockdesign.planar.checks.figure_data.pushover_data` (``theta``, ``force``, ``theta_c``,
    ``beta``, ``radius``)."""
    theta, force = np.asarray(curve["theta"], float), np.asarray(curve["force"], float)
    theta_c, beta, radius = curve["theta_c"], curve["beta"], curve["radius"]
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(6.4, 3.4))
        ax.plot(theta, force, color="C0", lw=1.4, label=r"$F_R/(m_C\,g)$, exact kinematics")
        ax.plot([0.0], [force[0]], "o", color="C2", ms=5, zorder=5,
                label=f"uplift: $F_R/(m_C\\,g)$ = {fmt(force[0])} at θ = 0")
        ax.plot([theta_c], [0.0], "s", color="C3", ms=5, zorder=5, label=f"θc = {fmt(theta_c, 'rad')}")
        ax.axvline(theta_c, color="C3", lw=0.8, ls="--")
        if radius > 0.0 and 0.0 < beta < theta_c:
            f_beta = float(np.interp(beta, theta, force))
            ax.axvline(beta, color="C1", lw=0.8, ls=":")
            ax.plot([beta], [f_beta], "D", color="C1", ms=4, zorder=5,
                    label=f"β = {fmt(beta, 'rad')} (rolling → rocking)")
        elif radius > 0.0:
            ax.plot([], [], " ", label=f"β = {fmt(beta, 'rad')} ≥ θc: unstable while rolling")
        ax.axhline(0.0, color="0.3", lw=0.6)
        ax.set_xlabel("θ [rad]")
        ax.set_ylabel(r"$F_R/(m_C\,g)$ [-]")
        ax.set_xlim(0.0, theta_c * 1.08)
        ax.set_ylim(min(0.0, force.min()) - 0.05 * max(force.max(), 1e-9), force.max() * 1.15)
        legend_above(ax, ncol=2)
        fig.set_layout_engine("tight")
        return fig


def spectra_figure(result):
    """Elastic SD spectra of the scaled records (ζ, band stated) with the capacity line u_B(θc), as the check
    computed them (``result.figure_data["spectra"]``)."""
    rule = result.rule
    spectra = result.figure_data["spectra"]
    periods, sds = np.asarray(spectra["periods"], float), np.asarray(spectra["sd"], float)
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(6.6, 3.8))
        for k, sd in enumerate(sds):
            ax.plot(periods, sd, color="0.55", lw=0.5, alpha=0.7, label="records (scaled)" if k == 0 else None)
        if len(sds) > 1:
            ax.plot(periods, np.median(sds, axis=0), color="C0", lw=1.6, label="median")
        xs = [o.sd_period for o in result.records]
        ys = [o.sd_max for o in result.records]
        ax.plot(xs, ys, "o", ms=2.5, color="k", label="SD$_{max}$ of each record")
        ax.axhline(rule.capacity, color="C3", lw=1.2, ls="--",
                   label=f"capacity $u_B$(θc) = {fmt(rule.capacity, 'm')} (Polyakov's 2B)")
        ax.set_xscale("log")
        ax.set_xlim(rule.band)
        ax.set_ylim(0.0, max(float(np.max(sds)) if sds.size else 0.0, rule.capacity) * 1.08)
        ax.set_xlabel("period T [s]")
        ax.set_ylabel("SD [m]")
        fig.suptitle(f"elastic displacement spectra, ζ = {fmt(100 * rule.damping)} %, "
                     f"band {fmt(rule.band[0])}–{fmt(rule.band[1])} s", fontsize=8, x=0.02, ha="left")
        legend_above(ax, ncol=2)
        fig.set_layout_engine("tight")
        return fig


def scatter_point(outcome) -> tuple[float, float]:
    """(x, y) of one record in the Fig 4.9 plane: SD_max/2B and u_B,max/2B (≥ 1 if it overturned)."""
    y = outcome.run.u_B_max_over_capacity
    if outcome.run.overturned:
        y = max(y, 1.0)
    return outcome.polyakov_ratio, y


def polyakov_scatter_figure(result):
    """Thesis Fig 4.9: u_B,max/2B against SD_max/2B per record, with the regions a1, a2, b, c, d."""
    pts = [scatter_point(o) for o in result.records]
    x_top = max(2.0, 1.08 * max(p[0] for p in pts))
    y_top = SCATTER_Y_TOP
    with plt.rc_context(dict(STYLE, **{"axes.grid": False})):
        fig, ax = plt.subplots(figsize=(6.4, 5.2))
        ax.fill_between([0, 1], [1, 1], [y_top, y_top], color=CLASS_COLOURS["b"], alpha=0.10, lw=0)
        ax.plot([0, 1], [0, 1], color="0.4", lw=0.8, ls="--")
        ax.axvline(1.0, color="0.2", lw=0.9)
        ax.axhline(1.0, color="0.2", lw=0.9)
        labels = {k: ax.text(0, 0, k, fontsize=11, fontweight="bold", color=CLASS_COLOURS[k], zorder=1)
                  for k in CLASS_COLOURS}
        counts = {c: 0 for c in CLASSES}
        for o, (x, y) in zip(result.records, pts):
            counts[o.klass] += 1
        for k in CLASSES:
            safe = [(x, y) for o, (x, y) in zip(result.records, pts) if o.klass == k and not o.run.overturned]
            ot = [(x, min(y, y_top * 0.97)) for o, (x, y) in zip(result.records, pts)
                  if o.klass == k and o.run.overturned]
            if safe:
                ax.plot(*zip(*safe), "o", ms=4.5, color=CLASS_COLOURS[k], mec="k", mew=0.4, zorder=4,
                        label=f"{k}: {CLASS_MEANING[k]} ({counts[k]})")
            if ot:
                ax.plot(*zip(*ot), "^", ms=5.5, color=CLASS_COLOURS[k], mec="k", mew=0.4, zorder=4,
                        label=None if safe else f"{k}: {CLASS_MEANING[k]} ({counts[k]})")
        if any(o.run.overturned for o in result.records):   # a legend entry only for a marker on the plot
            ax.plot([], [], "^", ms=5.5, color="white", mec="k", mew=0.4,
                    label=f"overturned (drawn at ≤ {fmt(y_top)})")
        ax.set_xlim(0.0, x_top)
        ax.set_ylim(0.0, y_top)
        ax.set_xlabel(f"SD$_{{max}}$ / $u_B$(θc)  (ζ = {fmt(100 * result.rule.damping)} %)")
        ax.set_ylabel("$u_{B,max}$ / $u_B$(θc)  (RHA)")
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
        fig.set_layout_engine("tight")
        _place_class_labels(ax, labels, x_top, y_top)
        return fig


def _place_class_labels(ax, labels: dict, x_top: float, y_top: float) -> None:
    """Each region's letter (thesis Fig 4.9) at the first place inside its region where no record's marker lies
    under it: its usual corner first, then over a grid of the region."""
    d = 0.03
    first = {"a1": (1 - d, d, "right", "bottom"), "a2": (d, 1 - d, "left", "top"),
             "b": (0.5, 0.5 * (1 + y_top), "center", "center"), "c": (x_top - d, 1 - d, "right", "top"),
             "d": (x_top - d, 1 + d, "right", "bottom")}
    inside = {"a1": lambda x, y: y < x - 0.08, "a2": lambda x, y: x < 1 and y < 1 and y > x + 0.08,
              "b": lambda x, y: x < 1 and y > 1, "c": lambda x, y: x > 1 and y < 1, "d": lambda x, y: x > 1 and y > 1}
    xs, ys = np.linspace(0.05, x_top - 0.05, 14), np.linspace(0.05, y_top - 0.05, 10)
    for k, text in labels.items():
        grid = [(x, y, "center", "center") for y in ys for x in xs if inside[k](x, y)]
        clear_position(ax, text, [first[k]] + grid)


def margin_figure(result):
    """Per record: RHA overturning factor and bands vs Polyakov's factor u_B(θc)/SD_max; design level 1."""
    recs = list(result.records)
    have_margins = any(o.margin is not None for o in recs)
    max_scale = result.settings.get("margin_max_scale", 8.0)

    def key(o):
        if o.margin is None or o.margin.overturn_scale is None:
            return (math.inf, o.polyakov_scale)
        return (o.margin.overturn_scale, o.polyakov_scale)

    recs.sort(key=key)
    n = len(recs)
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(6.6, max(3.0, 0.9 + 0.14 * n)))
        # one artist per kind of mark (not one per record): the same drawing, a fifth of the time
        bands, open_ends, first, unbounded, polyakov = [], [], [], [], []
        for i, o in enumerate(recs):
            y = n - 1 - i
            m = o.margin
            if m is not None:
                for lo, hi in m.intervals:
                    top = hi if hi is not None else max(m.scanned_up_to, lo)
                    bands.append([(lo, y), (top, y)])
                    if hi is None:
                        open_ends.append((top, y))
                if m.overturn_scale is not None:
                    first.append((m.overturn_scale, y))
                else:
                    unbounded.append((m.scanned_up_to, y))
            polyakov.append((o.polyakov_scale, y))
        if bands:
            ax.add_collection(LineCollection(bands, colors="C3", linewidths=3.0, alpha=0.35, capstyle="butt"))
        for points, marker, kw in ((open_ends, ">", dict(color="C3", ms=3, alpha=0.6)),
                                   (first, "|", dict(color="C3", ms=8, mew=1.6)),
                                   (unbounded, ">", dict(color="0.4", ms=4)),
                                   (polyakov, "D", dict(color="C0", ms=3.5))):
            if points:
                ax.plot(*zip(*points), marker, ls="", **kw)
        ax.axvline(1.0, color="k", lw=1.0, ls="--")
        ax.text(1.0, n - 0.2, " design level", fontsize=7, ha="left", va="bottom", clip_on=False)
        ax.set_yticks(range(n))
        ax.set_yticklabels([o.id for o in reversed(recs)], fontsize=5.5 if n > 30 else 7)
        ax.set_ylim(-0.8, n + 0.9)       # room above the top row for the "design level" label
        ax.set_xscale("log")
        lo = min([o.polyakov_scale for o in recs] + [m.overturn_scale for o in recs
                  if (m := o.margin) is not None and m.overturn_scale is not None] + [1.0])
        ax.set_xlim(lo / 1.5, max_scale * 1.5)
        ax.set_xlabel("amplitude factor on the design-level record [-]")
        handles = [plt.Line2D([], [], color="C3", marker="|", ls="", ms=8, mew=1.6,
                              label="RHA: smallest overturning factor"),
                   plt.Line2D([], [], color="C3", lw=3.0, alpha=0.35, label="RHA: overturning bands"),
                   plt.Line2D([], [], color="C0", marker="D", ls="", ms=3.5,
                              label="Polyakov: $u_B$(θc)/SD$_{max}$"),
                   plt.Line2D([], [], color="0.4", marker=">", ls="", ms=4,
                              label="no overturning up to the scan limit")]
        if not have_margins:
            handles = handles[2:3]
        ax.legend(handles=handles, fontsize=7, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, frameon=False)
        ax.grid(True, axis="x", which="both", alpha=0.3)
        ax.grid(False, axis="y")
        fig.set_layout_engine("tight")
        return fig


def ecdf_figure(result):
    """Empirical distribution of θ_max/α over the suite, with θc/α marked."""
    e = result.statistics["theta_max_over_alpha_ecdf"]
    x, f = np.asarray(e["x"], float), np.asarray(e["F"], float)
    alpha = result.quantities["alpha"].value
    theta_c = result.quantities["theta_c"].value
    limit = theta_c / alpha
    x_top = 1.5 * limit
    beyond = int(np.sum(x >= limit))
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(6.0, 3.2))
        xs = np.concatenate([[0.0], np.minimum(x, x_top)])
        fs = np.concatenate([[0.0], f])
        ax.step(xs, fs, where="post", color="C0", lw=1.3, label=f"ECDF of θ$_{{max}}$/α ({len(x)} records)")
        ax.axvline(limit, color="C3", lw=1.0, ls="--", label=f"θc/α = {fmt(limit)}")
        ax.set_xlim(0.0, x_top)
        ax.set_ylim(0.0, 1.02)
        ax.set_xlabel("θ$_{max}$/α [-]")
        ax.set_ylabel("F [-]")
        legend_above(ax, ncol=2)
        fig.set_layout_engine("tight")
        if beyond:
            note = ax.text(0, 0, f"{plural(beyond, 'record')} with θ$_{{max}}$ ≥ θc\n(drawn at the right edge)",
                           fontsize=7, color="C3", transform=ax.transAxes)
            clear_position(ax, note, [(0.98, 0.04, "right", "bottom"), (0.98, 0.5, "right", "center"),
                                      (0.02, 0.96, "left", "top")])
        return fig


def history_figure(result, record_id: str):
    """Time histories (ground acceleration, θ/α, drifts) of one governing record."""
    response = result.histories[record_id]
    o = next(r for r in result.records if r.id == record_id)
    meta = {**getattr(o.motion, "meta", {}), **o.meta}
    where = ", ".join(str(v) for v in (meta.get("event"), meta.get("station"), meta.get("component")) if v)
    title = f"{record_id}: {where} × {number(o.scale)}" if where else f"{record_id} × {number(o.scale)}"
    fig = time_history_figure(response, result.project.system.g, title)
    # an overturning body runs away to π/2: keep the scale of the capacity readable
    axes = fig.axes
    limit = response.theta_c / response.alpha
    peak = float(np.max(np.abs(response.theta))) / response.alpha if response.theta.size else limit
    if peak > HISTORY_CLIP * limit:
        top = HISTORY_CLIP * limit
        axes[1].set_ylim(-top, top)
        handles, _ = axes[1].get_legend_handles_labels()
        note = plt.Line2D([], [], ls="", label=f"θ/α clipped at ±{fmt(HISTORY_CLIP)} θc/α (peak {fmt(peak)})")
        legend_above(axes[1], handles=handles + [note], ncol=3)
        u_top = HISTORY_CLIP * response.u_capacity
        axes[2].set_ylim(-u_top, u_top)
    return fig
