"""Figures of a ground-motion record: its time histories and its elastic response spectrum
(``rockdesign records show --plot`` / ``records spectrum --plot``)."""
from __future__ import annotations

import numpy as np

from .. import mplfig as plt  # (pyplot-free Figures: importing never switches the backend)
from .measures import velocity_displacement


def record_history_figure(motion):
    """Ground acceleration, velocity and displacement (no baseline correction) of a record against t [s]."""
    t, accel = motion.sampled()
    velocity, displacement = velocity_displacement(np.ascontiguousarray(accel), motion.dt)
    fig, axes = plt.subplots(3, 1, figsize=(8, 6.5), sharex=True)
    for ax, values, label in zip(axes, (accel, velocity, displacement),
                                 ("ü_g [m/s²]", "u̇_g [m/s]", "u_g [m] (uncorrected)")):
        ax.plot(t, values, lw=0.7)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(motion.name)
    fig.tight_layout()
    return fig


def record_spectrum_figure(result: dict, gravity: float = 9.81):
    """SD [m] and PSA [g] against T [s] of ``records spectrum`` (``result``: its JSON object)."""
    fig, (ax_sd, ax_psa) = plt.subplots(1, 2, figsize=(10, 4))
    ax_sd.plot(result["periods"], result["SD"], lw=1)
    ax_sd.plot([result["t_sd_max"]], [result["sd_max"]], "o", label=f"SD_max = {result['sd_max']:.3f} m")
    ax_sd.set_xlabel("T [s]")
    ax_sd.set_ylabel("SD [m]")
    ax_sd.legend()
    ax_psa.plot(result["periods"], np.asarray(result["PSA"]) / gravity, lw=1)
    ax_psa.set_xlabel("T [s]")
    ax_psa.set_ylabel("PSA [g]")
    for ax in (ax_sd, ax_psa):
        ax.set_xscale("log")
        ax.grid(alpha=0.3, which="both")
    fig.suptitle(f"{result['id']} — {100 * result['damping']:g} % damping")
    fig.tight_layout()
    return fig
