"""The ASCE 7-22 §16.2 figure of a check report (every kind): the suite-average maximum-direction (RotD100) 5 %
spectrum of the scaled ground motions against the target spectrum and 90 % of it over the period range, with the
governing period — where the average comes closest to the 90 % floor — marked.

It renders results.json ``excitation.scaling`` (:mod:`rockdesign.motions.scaling_report`, CONTRACT §7.1): the
periods [s], the target's and the suite average's PSA [m/s²] on the comparison grid, the period range and the
smallest ratio.  Nothing is recomputed: the ratio panel divides the two curves it is given, and the governing
period is the grid period where that quotient is smallest (the scaling puts its refined minimum on the grid).
"""
from __future__ import annotations

import matplotlib.ticker as ticker
import numpy as np

from .. import mplfig as plt
from ..plots import STYLE, legend_above

FLOOR = 0.9
"""ASCE 7-22 §16.2.3.2: the suite average is not below 90 % of the target over the period range."""


def has_target(block: dict | None) -> bool:
    """Whether a scaling block carries what the figure draws: a target and the suite average over a period range."""
    return bool(block and block.get("target") and block.get("suite_average_max_direction")
                and block.get("period_range"))


def governing_period(block: dict) -> tuple[float, float]:
    """(period [s], ratio [-]) of the comparison grid where the suite average over the target is smallest."""
    periods = np.asarray(block["target"]["periods"], dtype=float)
    ratio = np.asarray(block["suite_average_max_direction"]["psa"], dtype=float) / np.asarray(
        block["target"]["psa"], dtype=float)
    k = int(np.argmin(ratio))
    return float(periods[k]), float(ratio[k])


def scaling_figure(block: dict, gravity: float):
    """Two panels over the period range (log period axis): (a) the suite-average RotD100 5 % PSA [g] of the scaled
    ground motions, the target and 90 % of it, the period range shaded; (b) their ratio with the 90 % floor.  The
    governing period is marked on both.  ``block``: results.json ``excitation.scaling``; ``gravity`` [m/s²]."""
    periods = np.asarray(block["target"]["periods"], dtype=float)
    target = np.asarray(block["target"]["psa"], dtype=float) / gravity
    average = np.asarray(block["suite_average_max_direction"]["psa"], dtype=float) / gravity
    lo, hi = block["period_range"]
    t_gov, r_gov = governing_period(block)
    a_gov = float(np.interp(t_gov, periods, average))
    ratio = average / target
    n = len(block.get("factors") or {})
    with plt.rc_context(STYLE):
        fig, (ax, bx) = plt.subplots(2, 1, figsize=(6.6, 5.2), sharex=True, gridspec_kw={"height_ratios": [3, 1.6]})
        for axis in (ax, bx):
            axis.axvspan(lo, hi, color="C0", alpha=0.06, lw=0)
            axis.axvline(t_gov, color="C3", lw=0.8, ls=":")
        ax.plot(periods, target, color="k", lw=1.4,
                label="target: MCE$_R$ spectrum (5 %)" if block.get("standard") else "target spectrum (5 %)")
        ax.plot(periods, FLOOR * target, color="k", lw=1.0, ls="--", label="90 % of the target")
        ax.plot(periods, average, color="C0", lw=1.6,
                label=f"suite average of the RotD100 spectra ({n} ground motions, scaled)" if n else
                "suite average of the RotD100 spectra (scaled)")
        ax.plot([t_gov], [a_gov], "o", color="C3", ms=5,
                label=f"governing period {t_gov:.3g} s: average {r_gov:.3f} × target (the lowest ratio)")
        ax.plot([], [], " ", label=f"period range {lo:.3g}–{hi:.3g} s (shaded; ASCE 7-22 §16.2.1)")
        ax.set_xscale("log")
        ax.set_xlim(lo / 1.15, hi * 1.15)
        ax.set_ylim(0.0, 1.12 * max(float(np.max(average)), float(np.max(target))))
        ax.set_ylabel("PSA [g]")
        legend_above(ax, ncol=1)
        bx.plot(periods, ratio, color="C0", lw=1.3)
        bx.axhline(FLOOR, color="k", lw=1.0, ls="--")
        bx.plot([t_gov], [r_gov], "o", color="C3", ms=5)
        bx.set_ylabel("average /\ntarget [-]")
        bx.set_ylim(min(FLOOR, float(np.min(ratio))) - 0.1, max(1.2, float(np.max(ratio)) + 0.1))
        bx.set_xlabel("period T [s]")
        bx.xaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        bx.xaxis.set_minor_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}" if f"{v:.1e}"[0] in "25" else ""))
        fig.set_layout_engine("tight")
        return fig
