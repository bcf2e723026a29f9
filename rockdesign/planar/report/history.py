"""The time-history figure of a planar analysis (``simulate --plot`` and the report's governing records): ground
acceleration, θ/α against ±θc/α with the impacts and uplifts, the column top's and the superstructure's drift."""
from __future__ import annotations

from ... import mplfig as plt  # noqa: E402  (pyplot-free Figures: importing never switches the backend)
import numpy as np  # noqa: E402

from ...plots import STYLE, legend_above  # noqa: E402


def time_history_figure(response, g: float, title: str = ""):
    """Three panels: ground acceleration [g], θ/α with ±θc/α, column-top and superstructure drift [m]; each
    panel's legend in a band above it, off the traces."""
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(3, 1, figsize=(7.0, 6.6), sharex=True)
        t = response.t
        axes[0].plot(t, response.ground_acceleration / g, lw=0.8, color="0.3")
        axes[0].set_ylabel("ü$_g$ [g]")
        a = response.alpha
        axes[1].plot(t, response.theta / a, lw=1.0, color="C0", label="θ/α")
        for s in (1, -1):
            axes[1].axhline(s * response.theta_c / a, color="C3", lw=0.8, ls="--",
                            label="±θc/α" if s == 1 else None)
        imp = [e.time for e in response.events if e.kind == "impact"]
        if imp:
            axes[1].plot(imp, np.zeros(len(imp)), "k|", ms=6, label=f"impacts ({len(imp)})")
        ups = [e.time for e in response.events if e.kind == "uplift"]
        if ups:
            axes[1].plot(ups, np.zeros(len(ups)), "g^", ms=4, label="uplift")
        axes[1].set_ylabel("θ/α [-]")
        legend_above(axes[1], ncol=4)
        axes[2].plot(t, response.u_B, lw=1.0, color="C1", label=r"$u_B$ (column top)")
        if np.any(response.u_rel != 0):
            axes[2].plot(t, response.u_rel, lw=0.8, color="C2", label=r"$u_T - u_B$ (superstructure drift)")
        axes[2].set_ylabel("displacement [m]")
        axes[2].set_xlabel("t [s]")
        legend_above(axes[2], ncol=2)
        if title:
            axes[0].set_title(title, fontsize=9, loc="left")
        fig.align_ylabels(axes)
        fig.set_layout_engine("tight")      # (laid out when drawn: it fills its figure size)
        return fig
