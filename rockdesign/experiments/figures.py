"""Figures of the experiment commands (matplotlib, Agg): calibration (thesis Figs 6.12, 6.24),
scaled shake-table record (a, v, d) and the Ch. 7 mixed CDFs with DKW bands (Figs 7.1, 7.2)."""
from __future__ import annotations

import numpy as np

from ..plots import STYLE, plt


def calibration_figure(history, cal, simulated=None, title: str = ""):
    """Measured θ/α (offset removed) over the simulated history with the calibrated p and c_r."""
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(8.0, 3.6))
        a = cal.alpha
        if simulated is not None:
            ax.plot(simulated[0], simulated[1] / a, lw=1.4, color="C0", alpha=0.6,
                    label=f"model: p = {cal.p:.4g} 1/s, c_r = {cal.c_r:.4f}")
        ax.plot(history.t, (history.theta - cal.offset) / a, lw=0.5, color="k", label="measured")
        used = [imp.time for imp in cal.impacts]
        ax.plot(used, np.zeros(len(used)), "|", color="C3", ms=8, label=f"impacts used ({len(used)})")
        peaks = [(hc.peak_time, hc.side * hc.theta0 / a) for hc in cal.half_cycles]
        ax.plot(*zip(*peaks), ".", color="C3", ms=4, label="peak tilts θ0")
        ax.set_xlabel("t [s]")
        ax.set_ylabel("θ/α [-]")
        ax.legend(loc="upper right", fontsize=7, ncol=2)
        if title:
            ax.set_title(title, fontsize=9, loc="left")
        return fig


def scale_model_figure(scaled, g: float, limits: dict, title: str = ""):
    """Acceleration [g], velocity [m/s] and displacement [m] of the corrected, scaled record."""
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(3, 1, figsize=(7.5, 6.0), sharex=True)
        t = scaled.t
        for ax, values, label, key, factor in ((axes[0], scaled.acceleration, "a [g]", "a", 1.0 / g),
                                               (axes[1], scaled.velocity, "v [m/s]", "v", 1.0),
                                               (axes[2], scaled.displacement, "d [m]", "d", 1.0)):
            ax.plot(t, values * factor, lw=0.7)
            if limits.get(key) is not None:
                for s in (1, -1):
                    ax.axhline(s * limits[key] * factor, color="C3", ls="--", lw=0.8,
                               label="table limit" if s == 1 else None)
                ax.legend(loc="upper right", fontsize=7)
            ax.set_ylabel(label)
        axes[-1].set_xlabel("t [s] (model time)")
        if title:
            axes[0].set_title(title, fontsize=9, loc="left")
        fig.align_ylabels(axes)
        return fig


def validation_figure(result, title: str = ""):
    """Mixed empirical CDFs of θ_max/α (Eq 7.1) with the tests' 90 % and 95 % DKW bands."""
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(7.0, 4.2))
        tests = result.samples["tests"]
        x_max = result.plot_limit
        for conf, shade in ((0.95, 0.12), (0.90, 0.22)):
            x, f = tests.step_points(x_max)
            eps = tests.dkw_epsilon(1.0 - conf)
            ax.fill_between(x, np.clip(f - eps, 0, 1), np.clip(f + eps, 0, 1), step="post", color="C0",
                            alpha=shade, lw=0, label=f"tests {int(conf * 100)} % band (DKW)")
        for name, sample in result.samples.items():
            x, f = sample.step_points(x_max)
            ax.step(x, f, where="post", lw=1.3 if name == "tests" else 1.0, label=f"{name} (n = {sample.n}, "
                    f"p_o = {sample.p_overturn:.2f})")
        ax.axvline(result.overturn_at, color="0.5", ls=":", lw=0.8)
        ax.text(result.overturn_at, 0.02, " overturned", fontsize=7, color="0.4")
        ax.set_xlim(0, 1.06 * x_max)
        ax.set_ylim(0, 1.01)
        ax.set_xlabel("θ_max/α [-]")
        ax.set_ylabel("F(θ_max/α) [-]")
        ax.legend(loc="lower right", fontsize=7)
        if title:
            ax.set_title(title, fontsize=9, loc="left")
        return fig
