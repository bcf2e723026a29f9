"""Report figures of the superstructure demand (SPEC §13): rocking vs fixed-base shear coefficient per
record with the force ratio, and the governing record's superstructure acceleration and drift history."""
from __future__ import annotations

import numpy as np

from ... import mplfig as plt
from ...plots import STYLE
from ...report.formatting import fmt


def demand_figure(result):
    """Per record: peak shear coefficient |f_s|/g of the superstructure on the rocking storey (2DOF podium)
    and on a fixed base (top), and their ratio (bottom); overturned records are left out. None without an
    elastic superstructure."""
    rows = [o for o in result.records if o.superstructure is not None and not o.run.overturned]
    if not rows:
        return None
    g = result.project.system.g
    ids = [o.id for o in rows]
    rock = np.array([o.superstructure["shear_coefficient_max"] for o in rows])
    fixed = np.array([o.superstructure["fixed_base_acceleration_max"] / g for o in rows])
    ratio = rock / fixed
    x = np.arange(len(rows))
    up = result.statistics["superstructure"]["uplift_base_shear_coefficient"]
    with plt.rc_context(STYLE):
        fig, (ax, ax2) = plt.subplots(2, 1, figsize=(6.6, 4.6), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
        ax.plot(x, fixed, "s", ms=3.5, color="C7", label="fixed base")
        ax.plot(x, rock, "o", ms=3.5, color="C0", label="on the rocking storey (2DOF podium)")
        ax.vlines(x, np.minimum(rock, fixed), np.maximum(rock, fixed), color="C7", lw=0.5)
        ax.axhline(up, color="C3", lw=0.8, ls="--", label=f"uplift, tan α = {fmt(up)}")
        ax.set_ylabel("peak |f$_s$|/g [-]")
        ax.set_ylim(0.0, None)
        # above the axes: inside, it hid the markers of the records under it
        ax.legend(fontsize=7, loc="lower left", bbox_to_anchor=(0.0, 1.01), ncol=3, frameon=False,
                  borderaxespad=0.0, handletextpad=0.4, columnspacing=1.2)
        ax2.bar(x, ratio, color=np.where(ratio <= 1.0, "C2", "C3"), width=0.7)
        ax2.axhline(1.0, color="k", lw=0.7)
        ax2.set_ylabel("force ratio [-]")
        ax2.set_xticks(x)
        ax2.set_xticklabels([i.split("/")[-1] for i in ids], rotation=90, fontsize=5)
        ax2.set_xlabel("record")
        fig.set_layout_engine("tight")
        return fig


def demand_history_figure(result):
    """Time history of the superstructure's absolute acceleration a_T/g (= −f_s/g) and drift u_T − u_B of the
    record with the largest demand (2DOF podium); None without one."""
    if not result.demand_history:
        return None
    rid, r = result.demand_history
    g = result.project.system.g
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(3, 1, figsize=(6.6, 4.8), sharex=True)
        axes[0].plot(r.t, r.ground_acceleration / g, color="C7", lw=0.6)
        axes[0].set_ylabel("ü$_g$/g [-]")
        axes[0].set_title(f"{rid}: superstructure demand (2DOF podium)", fontsize=8)
        axes[1].plot(r.t, r.a_T_abs / g, color="C0", lw=0.6)
        peak = r.superstructure_acceleration_max / g
        for s in (1, -1):
            axes[1].axhline(s * peak, color="C0", lw=0.5, ls=":")
        if r.fixed_base_acceleration_max:
            for s in (1, -1):
                axes[1].axhline(s * r.fixed_base_acceleration_max / g, color="C7", lw=0.6, ls="--")
        axes[1].set_ylabel("a$_T$/g [-]")
        # the peaks above the panel, beside the lines they name (on the panel the words sat on the trace)
        axes[1].set_title(f"peak ±{fmt(peak)} (dotted); on a fixed base ±"
                          f"{fmt((r.fixed_base_acceleration_max or 0.0) / g)} (dashed)", fontsize=7, loc="left")
        axes[2].plot(r.t, r.u_rel * 1e3, color="C1", lw=0.6)
        axes[2].set_ylabel("u$_T$ − u$_B$ [mm]")
        axes[2].set_xlabel("t [s]")
        fig.set_layout_engine("tight")
        return fig
