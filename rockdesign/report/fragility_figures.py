"""The fragility figure of the calculation report (SPEC §11): capacities, fits, stripes and the
non-monotonic ("resurrection") overturning bands of every record, in the fragility's intensity measure."""
from __future__ import annotations

import matplotlib.ticker as ticker
import numpy as np
from scipy.stats import norm

from .. import mplfig as plt  # pyplot-free Figures: importing never switches the backend

from ..acceptance.rule import first_overturn_scale  # noqa: E402
from .formatting import fmt  # noqa: E402
from ..plots import STYLE, clear_position, legend_above  # noqa: E402

UNIT_LABELS = {"m/s^2": "m/s²", "m": "m"}
"""Units of the intensity measure as the figure writes them (results.json keeps "m/s^2")."""


def fragility_figure(result):
    """Two panels sharing the IM axis (log): (a) P(overturn | IM) — empirical capacities (censored
    ones as open triangles), the capacity fit, the stripe fractions and their binomial fit, the design
    level; (b) per record, the intensities at which the record overturns (bands; gaps above the first
    band are safe again)."""
    f = result.fragility
    unit = UNIT_LABELS.get(f["unit"], f["unit"])
    caps = f["capacities"]
    order = np.argsort([c["capacity"] for c in caps], kind="stable")
    x = np.array([caps[i]["capacity"] for i in order])
    cens = np.array([caps[i]["censored"] for i in order])
    n = x.size
    pos = (np.arange(n) + 0.5) / n
    design = f["design_intensity"]
    st = f["stripes"]
    levels = np.array(st["levels"])
    ims = {o.id: im for o, im in zip(result.records, _intensities(result, f))}
    lo = min(x.min(), levels.min(), design) / 1.3
    hi = max(x.max(), levels.max()) * 1.3
    grid = np.geomspace(lo, hi, 300)
    with plt.rc_context(STYLE):
        fig, (ax, bx) = plt.subplots(2, 1, figsize=(6.6, 4.6 + 0.075 * n), sharex=True,
                                     gridspec_kw={"height_ratios": [3.4, max(1.2, 0.075 * n)]})
        ax.plot(x[~cens], pos[~cens], "o", color="C0", ms=3.5, label="capacity of a record (first overturning)")
        if cens.any():
            ax.plot(x[cens], pos[cens], ">", mfc="none", color="C0", ms=5,
                    label=f"censored: no overturning up to the scan limit ({int(cens.sum())})")
        if f["median"] is not None:
            label = "censored MLE" if f["method"] == "censored-mle" else "method of moments"
            ax.plot(grid, norm.cdf(np.log(grid / f["median"]) / f["beta"]), color="C0", lw=1.4,
                    label=f"lognormal, {label}: θ = {fmt(f['median'], f['unit'])}, β = {fmt(f['beta'])}")
        keep = np.array(st["n"]) > 0
        frac = np.array(st["overturned"])[keep] / np.array(st["n"])[keep]
        ax.plot(levels[keep], frac, "s", color="C1", ms=3.5, mfc="none",
                label="fraction overturning at a stripe (raw outcomes)")
        if st["median"] is not None:
            ax.plot(grid, norm.cdf(np.log(grid / st["median"]) / st["beta"]), color="C1", lw=1.2, ls="--",
                    label=f"lognormal, stripe binomial MLE: θ = {fmt(st['median'], f['unit'])}, "
                          f"β = {fmt(st['beta'])}")
        ax.axvline(design, color="k", lw=1.0, ls=":")
        _acceptance_marks(ax, grid, design, getattr(result, "collapse_margin", None),
                          getattr(result, "acceptance", None))
        p_fit = f["p_overturn_design"]
        text = f"design {fmt(design, f['unit'])}"
        if p_fit is not None:
            text += f"\nP(fit) = {fmt(p_fit)}"
        text += f"\nP(RHA) = {fmt(f['p_overturn_empirical'])}"
        note = ax.text(0, 0, text, fontsize=7, transform=ax.transAxes)
        ax.set_xscale("log")
        ax.set_ylim(-0.02, 1.02)
        ax.set_ylabel("P(overturn) [-]")
        legend_above(ax, ncol=1, fontsize=6.5)
        by_id = {o.id: o for o in result.records}
        for row, i in enumerate(order):
            o = by_id[caps[i]["id"]]
            m, im = o.margin, ims[o.id]
            for lower, upper in m.intervals:
                top = upper if upper is not None else m.scanned_up_to
                bx.plot([lower * im, top * im], [row, row], color="C3", lw=2.0, alpha=0.55, solid_capstyle="butt")
            bx.plot([m.scanned_up_to * im], [row], "|", color="0.5", ms=3)
        bx.axvline(design, color="k", lw=1.0, ls=":")
        bx.set_yticks([])
        bx.set_ylim(-1, n)
        bx.set_ylabel("records", fontsize=7)
        bx.set_xlabel(f"{f['im_label']}" + (f" (T = {fmt(f['period'], 's')})" if f.get("period") else "")
                      + f" [{unit}]")
        bx.set_xlim(lo, hi)
        bx.set_title("overturning bands per record (sorted by capacity); gaps above the first band: safe again; "
                     "grey tick: scan limit", fontsize=7, loc="left")
        for axis in (ax, bx):
            axis.xaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
            axis.xaxis.set_minor_formatter(ticker.FuncFormatter(
                lambda v, _: f"{v:g}" if f"{v:.1e}"[0] in "25" else ""))
        fig.set_layout_engine("tight")
        at = ax.transAxes.inverted().transform(ax.transData.transform((design, 0.0)))[0]
        clear_position(ax, note, [(at + 0.01, 0.97, "left", "top"), (at - 0.01, 0.97, "right", "top"),
                                  (0.99, 0.03, "right", "bottom"), (0.01, 0.97, "left", "top")])
        return fig


def _acceptance_marks(ax, grid, design, cm, acc) -> None:
    """The acceptance rule on the fragility panel: the collapse fragility of the margin (median Ŝ_CT
    counted as FEMA P695 §6.4 defines it, dispersion β_TOT), its P(collapse) at the design level and the
    risk category's target probability."""
    if not cm or not acc:
        return
    target = acc["target_p_collapse"]
    ax.axhline(target, color="C3", lw=0.9, ls="-.",
               label=f"target P(collapse | design) {fmt(100 * target)} % (risk category {acc['risk_category']})")
    if not cm["CMR_is_lower_bound"]:
        ax.plot(grid, norm.cdf(np.log(grid / cm["median_capacity"]) / cm["beta_tot"]), color="C3", lw=1.0,
                label=r"collapse margin: $\hat{S}_{CT}$ counted (half the records overturn) "
                      f"{fmt(cm['median_capacity'], cm['unit'])}, " + r"$\beta_{TOT}$" + f" = {fmt(cm['beta_tot'])}")
    ax.plot([design], [cm["p_collapse_design"]], "D", color="C3", ms=4.5,
            label=f"P(collapse | design) = {fmt(100 * cm['p_collapse_design'])} %"
                  + (" (upper bound)" if cm["CMR_is_lower_bound"] else "") + f", ACMR {fmt(cm['ACMR'])}")


def _intensities(result, f) -> list[float]:
    """IM of each design-level record, recovered from capacity/first overturning factor (or the censoring)."""
    out = []
    for o, c in zip(result.records, f["capacities"]):
        s = first_overturn_scale(o)
        out.append(c["capacity"] / (s if s is not None else o.margin.scanned_up_to))
    return out
