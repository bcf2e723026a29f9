"""Figures of the cylinder: the time history with the plan-view orbit (thesis Figs 5.9–5.15), the
wobbling period against the tilt (Fig 5.2) and the check's 3D against planar θ_max/α per record pair.  They draw
the data the check computed; they compute none (tests/report/test_renders_only.py)."""
from __future__ import annotations

import numpy as np

from .engine import SPIN_TILT_MIN
from ..plots import STYLE, legend_above, plt


CONTACT_FORCE_TOP = 4.0
"""Top of the N/(mg) axis: quasi-impacts make short spikes (the impact force of the contact spring, set by
ω_n, in the damped model; the body's accelerations as the contact point whirls, with a rigid contact); they
are clipped there and their peak is written on the panel."""


def cylinder_history_figure(response, g: float, title: str = "", pair=None):
    """Panels against t: ground accelerations [g] (of ``pair`` when given, else at the history's times),
    θ/α (with θ_ot/α and the quasi-impacts), the spin φ̇ [rad/s] where θ ≥ SPIN_TILT_MIN·α (near θ = 0 the
    contact point whirls round the rim and φ̇ is unbounded), the contact force N/(mg) (spikes clipped at
    :data:`CONTACT_FORCE_TOP`); and the plan view of the path of the centre of mass [m] (Figs 5.9–5.15)."""
    r = response
    with plt.rc_context(STYLE):
        fig = plt.figure(figsize=(10.0, 7.6))
        grid = fig.add_gridspec(4, 2, width_ratios=(1.7, 1.0))
        axes = [fig.add_subplot(grid[i, 0]) for i in range(4)]
        for ax in axes[1:]:
            ax.sharex(axes[0])
        t = r.t
        tg, gx, gy = (t, r.ground_x, r.ground_y) if pair is None else pair.sampled()
        keep = tg <= t[-1]
        axes[0].plot(tg[keep], gx[keep] / g, lw=0.7, color="0.2", label="ü$_{gx}$")
        axes[0].plot(tg[keep], gy[keep] / g, lw=0.7, color="C1", alpha=0.8, label="ü$_{gy}$")
        axes[0].set_ylabel("ü$_g$ [g]")
        legend_above(axes[0], ncol=2, loc="lower right", bbox_to_anchor=(1.0, 1.01))
        axes[1].plot(t, r.theta / r.alpha, lw=0.9, color="C0")
        axes[1].axhline(1.0, color="0.5", lw=0.7, ls=":", label="θ = α")
        axes[1].axhline(r.theta_overturn / r.alpha, color="C3", lw=0.8, ls="--", label=r"$\theta_{ot}$")
        axes[1].axhline(SPIN_TILT_MIN, color="C2", lw=0.6, ls="-.", label=f"θ = {SPIN_TILT_MIN:g}α")
        qi = r.quasi_impact_times
        if qi.size:
            axes[1].plot(qi, np.zeros(qi.size), "k|", ms=6, label=f"quasi-impacts ({qi.size})")
        axes[1].set_ylabel("θ/α [-]")
        legend_above(axes[1], ncol=4)
        spin = r.spin()
        axes[2].plot(t, spin, lw=0.8, color="C2")
        axes[2].axhline(0.0, color="0.5", lw=0.5)
        axes[2].set_ylabel(r"$\dot{\varphi}$ [rad/s]")
        if not np.any(np.isfinite(spin)):
            axes[2].set_ylim(-1.0, 1.0)
        axes[2].set_title(f"spin where θ ≥ {SPIN_TILT_MIN:g}α (below it the contact point whirls round the rim)",
                          fontsize=7, loc="left")
        force = np.minimum(r.contact_force, CONTACT_FORCE_TOP)
        axes[3].plot(t, force, lw=0.8, color="C4")
        axes[3].axhline(0.0, color="C3", lw=0.7, ls="--")
        axes[3].axhline(1.0, color="0.5", lw=0.5, ls=":")
        peak = float(np.max(r.contact_force)) if r.contact_force.size else 0.0
        if peak > CONTACT_FORCE_TOP:
            axes[3].set_title(f"contact force: spikes at quasi-impacts up to {peak:.3g} (clipped at "
                              f"{CONTACT_FORCE_TOP:g})", fontsize=7, loc="left")
        axes[3].set_ylim(min(0.0, float(np.min(force))) - 0.1, CONTACT_FORCE_TOP * 1.05 if peak > CONTACT_FORCE_TOP
                         else max(1.5, peak * 1.1))
        axes[3].set_ylabel("N/(m g) [-]")
        axes[3].set_xlabel("t [s]")
        orbit = fig.add_subplot(grid[:, 1])
        x, y = r.orbit
        orbit.plot(x, y, lw=0.6, color="C0", label="path of the centre of mass")
        lim = r.R * (np.sin(r.alpha) - np.sin(r.alpha - r.theta_overturn))
        circle = np.linspace(0, 2 * np.pi, 200)
        orbit.plot(lim * np.cos(circle), lim * np.sin(circle), color="C3", lw=0.8, ls="--", label=r"$\theta_{ot}$")
        rim = r.base_radius
        orbit.plot(rim * np.cos(circle), rim * np.sin(circle), color="0.5", lw=0.8, label="footprint")
        orbit.set_aspect("equal")
        orbit.set_xlabel("x [m]")
        orbit.set_ylabel("y [m]")
        orbit.set_title("plan view: path of the centre of mass", fontsize=8)
        orbit.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=7, ncol=1, frameon=False)
        if title:
            axes[0].set_title(title, fontsize=9, loc="left")
        fig.align_ylabels(axes)
        fig.set_layout_engine("tight")
        return fig


def wobbling_figure(curve: dict, tan_alpha: float):
    """T_w p against θ/α (Eq 5.29) next to Housner's planar period (Eq 2.8), as thesis Fig 5.2: ``curve`` holds the
    arrays ``theta_over_alpha``, ``Tw_p`` and ``T_housner_p`` the check computed (``result.figure_data["wobbling"]``,
    :func:`~rockdesign.cylinder.quantities.wobbling_curve`) for a cylinder of slenderness ``tan_alpha``."""
    ratio, tw_p, housner_p = (np.asarray(curve[k], float) for k in ("theta_over_alpha", "Tw_p", "T_housner_p"))
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(5.5, 3.8))
        ax.plot(ratio, tw_p, color="C0", label=f"wobbling cylinder, tan α = {tan_alpha:.3g} (Eq 5.29)")
        ax.plot(ratio, housner_p, color="0.3", ls="--", label="planar rocking, Housner (Eq 2.8)")
        ax.set_xlabel("θ/α [-]")
        ax.set_ylabel("T p [-]")
        ax.set_ylim(0, min(60.0, float(np.nanmax(tw_p)) * 1.05))
        ax.legend(fontsize=7)
        return fig


def comparison_figure(data: dict, cap: float = 2.0):
    """3D θ_max/α against the planar Housner θ_max/α (worse component) per record pair (results.json
    ``data`` of a cylinder check); planar values beyond ``cap`` (the planar block overturned) are drawn at ``cap``."""
    tilt = data.get("cylinder", {}).get("overturn_tilt")
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(5.0, 4.6))
        x = np.minimum([r["planar_theta_max_over_alpha"] for r in data["records"]], cap)
        y = np.array([r["theta_max_over_alpha"] for r in data["records"]])
        ot = np.array([r["overturned"] for r in data["records"]], dtype=bool)
        top = max(cap, float(np.max(y)) * 1.05 if y.size else cap)
        ax.plot([0, cap], [0, cap], color="0.6", lw=0.8)
        ax.axvline(1.0, color="0.3", lw=0.7, ls=":", label=r"planar overturning ($\theta_{max}$ = α)")
        if tilt:
            ax.axhline(tilt, color="C3", lw=0.7, ls="--", label=r"$\theta_{ot}$ (3D overturning)")
        ax.scatter(x[~ot], y[~ot], s=14, color="C0", label="3D survives")
        ax.scatter(x[ot], y[ot], s=18, color="C3", marker="x", label=r"3D overturns ($\theta_{ot}$)")
        ax.set_xlim(0, cap * 1.03)
        ax.set_ylim(0, top * 1.03)
        ax.set_xlabel(f"planar Housner $\\theta_{{max}}$/α (worse component; drawn at {cap:g} beyond)")
        ax.set_ylabel(r"3D cylinder $\theta_{max}$/α")
        ax.legend(fontsize=7, loc="upper left")
        return fig
