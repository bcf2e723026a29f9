"""Rocking spectra of the cylinder for one record pair (thesis Figs 5.16–5.17).

The abscissa is the size R (the cylinder's slenderness tan α is the project's), the ordinate the
resultant PGA over the uplift acceleration, max|ü_g|/(g tan α) (Eq 5.43); each grid point is one 3D
analysis (:func:`rockdesign.cylinder.kernel.integrate`), run in parallel over both cores by a numba
``prange`` loop whose threads take the points one at a time (:mod:`rockdesign.execution.scheduling`).
The value is θ_max/α, set to θ_ot/α where the cylinder overturns.  A relative spectrum subtracts the
same spectrum of a second project (e.g. damped minus undamped, Fig 5.17): where it is negative the
first project performs better.
"""
from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from ..execution.executor import chunk_size
from ..execution.scheduling import take, worker_count
from ..errors import RockdesignError
from .eom import parameters
from .kernel import ST_OVERTURNED, integrate

AXIS = re.compile(r"^\s*(R|pga/up)\s*:\s*([^:]+):([^:]+):(\d+)\s*$")


class CylinderSpectrumError(RockdesignError):
    """Bad spectrum axes or options for a cylinder."""


def parse_cylinder_axis(text: str, which: str) -> tuple[str, np.ndarray]:
    """``R:lo:hi:n`` (size [m]) or ``pga/up:lo:hi:n`` (resultant PGA over g tan α), inclusive, n points."""
    m = AXIS.match(text)
    expected = {"x": "R:lo:hi:n, e.g. R:0.5:30:60", "y": "pga/up:lo:hi:n, e.g. pga/up:1:6:51"}[which]
    want = "R" if which == "x" else "pga/up"
    if not m or m.group(1) != want:
        raise CylinderSpectrumError("invalid axis for a cylinder spectrum", key=which, expected=expected,
                                    found=repr(text))
    try:
        lo, hi, n = float(m.group(2)), float(m.group(3)), int(m.group(4))
    except ValueError:
        raise CylinderSpectrumError("invalid axis numbers", key=which, expected=expected,
                                    found=repr(text)) from None
    if not (0 < lo <= hi) or n < 1 or (n > 1 and lo == hi):
        raise CylinderSpectrumError("invalid axis range", key=which, expected="0 < lo < hi and n ≥ 1",
                                    found=repr(text))
    return want, np.linspace(lo, hi, n)


@njit(cache=True, parallel=True)
def _grid(pars, scales, params0, sx, sy, t_end, t_exc_end, rtol, atol, seeds, theta_ot, quasi_tilt,
          rest_energy, planar_restitution, ups, out_theta, out_ot, out_qi, workers):
    """All grid points: pars[i], seeds[i], rest_energy[i], ups[i] per size, scales[j] per amplitude; θ_max,
    overturned, quasi-impacts.

    ``workers`` workers (one per numba thread) take the points one at a time from a shared counter
    (:mod:`rockdesign.execution.scheduling`), so a busy core does not hold up the grid."""
    nx = pars.shape[0]
    ny = scales.shape[0]
    counter = np.zeros(1, dtype=np.int64)
    for _ in prange(workers):
        k = take(counter)
        while k < nx * ny:
            i = k % nx
            j = k // nx
            params = params0.copy()
            params[0] = scales[j]
            y0 = np.zeros(6)
            hist, events, stats = integrate(y0, 0.0, t_end, t_exc_end, pars[i], 0, params, sx, sy, 1.0, 1.0, rtol,
                                            atol, seeds[i], theta_ot, quasi_tilt, rest_energy[i],
                                            planar_restitution, ups[i], 20_000_000, 0.0, True)
            th = 0.0
            for r in range(hist.shape[0]):
                th = max(th, hist[r, 1])
            nq = 0
            for e in range(events.shape[0]):
                if events[e, 0] == 2.0:
                    th = max(th, events[e, 2])
                elif events[e, 0] == 1.0 or events[e, 0] == 3.0:
                    nq += 1
            out_theta[j, i] = th
            out_ot[j, i] = stats[4] == ST_OVERTURNED
            out_qi[j, i] = nq
            k = take(counter)


@dataclass(frozen=True)
class CylinderSpectrum:
    """θ_max/α (θ_ot/α where overturned) on the grid (len(y) × len(x)), with the axes and timings."""

    x: np.ndarray
    y: np.ndarray
    theta_max_over_alpha: np.ndarray
    overturned: np.ndarray
    quasi_impacts: np.ndarray
    seconds: float
    model: str


PROGRESS_STEPS = 20
"""With a progress callback the grid runs in about this many blocks of amplitude rows (one parallel
kernel call each, so the bar moves; the points and their results are the same)."""


def grid_rows(pars, params0, sx, sy, t_end, t_exc_end, rtol, atol, seeds, theta_ot, quasi_tilt, rest, restitution,
              ups, scales) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """θ_max, overturned and quasi-impacts of a block of amplitude rows (``scales``, last: an executor passes the
    shared arguments first) over every size: one parallel kernel call on this process's numba threads — in this
    process or as one task of an executor (module-level, callback-free)."""
    shape = (scales.size, pars.shape[0])
    theta, ot, qi = np.zeros(shape), np.zeros(shape, dtype=np.bool_), np.zeros(shape, dtype=np.int64)
    _grid(pars, scales, params0, sx, sy, t_end, t_exc_end, rtol, atol, seeds, theta_ot, quasi_tilt, rest,
          restitution, ups, theta, ot, qi, worker_count(theta.size))
    return theta, ot, qi


def cylinder_spectrum(cyl, pair, R_values, pga_over_up, *, rtol: float = 1e-10, atol: float = 1e-12,
                      free_vibration: float = 10.0, rest_velocity: float = 5e-4,
                      progress=None, executor=None) -> CylinderSpectrum:
    """The spectrum of ``cyl``'s slenderness and contact under ``pair`` (any size R [m] of the grid).

    ``progress(done, total)`` is called as blocks of grid points finish (points done, all points).  ``executor``:
    None (this process, every core) or an executor object (:mod:`rockdesign.execution.executor`): the blocks of
    amplitude rows (:func:`grid_rows`, about four per slot) run there; every point is the same analysis either
    way."""
    from .engine import QUASI_IMPACT_TILT, rest_energy, seed_tilt, uplift_level
    from .quantities import restitution_root
    if not pair.is_record or pair.planar:
        raise CylinderSpectrumError("a cylinder spectrum needs a record pair", key="record",
                                    expected="both components, e.g. p695-ff/11", found=pair.name)
    alpha, g = cyl.alpha, cyl.g
    up = g * math.tan(alpha)
    R_values = np.asarray(R_values, dtype=float)
    pars = np.array([parameters(R, alpha, g, cyl.contact_frequency, cyl.contact_damping, cyl.damped) for R in R_values])
    # the engine's rest rule, seed and uplift level (engine.simulate_cylinder) at every size
    rest = np.array([rest_energy(R, alpha, rest_velocity) for R in R_values])
    seeds = np.array([seed_tilt(R, alpha, g, rest_velocity) for R in R_values])
    ups = np.full(R_values.size, uplift_level(alpha, g))
    base = pair.resultant_pga / pair.scale
    scales = np.asarray(pga_over_up, dtype=float) * up / base
    ny, nx = scales.size, R_values.size
    theta = np.zeros((ny, nx))
    ot = np.zeros((ny, nx), dtype=np.bool_)
    qi = np.zeros((ny, nx), dtype=np.int64)
    t0 = time.perf_counter()
    common = (pars, np.array([1.0, pair.dt]), pair.x, pair.y, pair.duration + free_vibration, pair.duration,
              rtol, atol, seeds, cyl.theta_overturn, QUASI_IMPACT_TILT * alpha, rest,
              restitution_root(alpha) if cyl.damped else 1.0, ups)
    if executor is None:
        rows = ny if progress is None else max(1, math.ceil(ny / PROGRESS_STEPS))
        blocks = ((k, grid_rows(*common, scales[a:a + rows])) for k, a in enumerate(range(0, ny, rows)))
    else:
        rows = chunk_size(ny, executor)
        executor.start()
        blocks = executor.map(grid_rows, common, {k: (scales[a:a + rows],) for k, a in enumerate(range(0, ny, rows))})
    done = 0
    for k, (th, o, q) in blocks:
        a = k * rows
        theta[a:a + th.shape[0]], ot[a:a + th.shape[0]], qi[a:a + th.shape[0]] = th, o, q
        done += th.size
        if progress is not None:
            progress(done, ny * nx)
    seconds = time.perf_counter() - t0
    ratio = np.where(ot, cyl.overturn_tilt, theta / alpha)
    return CylinderSpectrum(R_values, np.asarray(pga_over_up, dtype=float), ratio, ot, qi, seconds,
                            "damped" if cyl.damped else "undamped")


def spectrum_figure(spec: CylinderSpectrum, title: str, reference: CylinderSpectrum | None = None,
                    overturn_tilt: float = 1.5):
    """Fig 5.16a (θ_max/α, overturned in black) or, with ``reference``, the relative spectrum (Fig 5.16b/5.17)."""
    from ..plots import STYLE, plt
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=(6.4, 4.6))
        if reference is None:
            data = np.ma.masked_where(spec.overturned, spec.theta_max_over_alpha)
            mesh = ax.pcolormesh(spec.x, spec.y, data, shading="nearest", cmap="viridis", vmin=0,
                                 vmax=overturn_tilt)
            ax.pcolormesh(spec.x, spec.y, np.ma.masked_where(~spec.overturned, np.ones(spec.overturned.shape)), shading="nearest",
                          cmap="gray", vmin=0, vmax=2)
            fig.colorbar(mesh, ax=ax, label="θ_max/α (dark grey: overturned)")
        else:
            diff = spec.theta_max_over_alpha - reference.theta_max_over_alpha
            lim = max(float(np.max(np.abs(diff))), 1e-9)
            mesh = ax.pcolormesh(spec.x, spec.y, diff, shading="nearest", cmap="RdBu_r", vmin=-lim, vmax=lim)
            fig.colorbar(mesh, ax=ax, label=f"Δ θ_max/α ({spec.model} − {reference.model}); blue: first better")
        ax.set_xlabel("R [m]")
        ax.set_ylabel("max|ü_g| / (g tan α) [-]")
        ax.set_title(title, fontsize=9, loc="left")
        return fig
