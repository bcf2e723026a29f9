"""Where the ground motion acts along one line: the cylinder's planar reduction (thesis Sec 5.2.6, Eq 5.26).

A body that uplifts from rest has no angular momentum about the vertical, ℓ = R² J φ̇ = 0 (Eq 5.23 is
d(Jφ̇)/dt = (sinα − sin(α−θ))(ü_gx sinφ − ü_gy cosφ)/R, K = dJ/dθ).  While the ground acceleration stays on
the line of the tilt, the right-hand side of Eq 5.23 is zero, ℓ stays zero, and Eqs 5.22–5.23 are exactly the
planar rocking of Housner's cylinder (Eq 5.26 with the ground term): φ̇ ≡ 0, and at θ = 0 the body passes to
the opposite rim point (φ → φ + π).  The 3D equations cannot carry that motion numerically: the torque
term vanishes on the line only in exact arithmetic (sin and cos of the azimuth of a diagonal force differ in
their last bit), so ℓ picks up round-off, and its first return to θ = 0 is a quasi-impact whose smallest tilt
(∝ ℓ) lies far below what the step control resolves (θ ≈ 1e-15 rad, φ̇ ≈ 1e8 rad/s: "step size collapsed").
The limit is singular besides: as ℓ → 0± a quasi-impact turns the azimuth by ±(2π − Δφ) of Eq 5.38, not by π,
so a round-off spin would throw the body off the line.  The thesis says as much (Sec 5.2.6): the 3D
equations apply "when one can be sure that a 3D rocking and wobbling motion is initiated".

So the integrator (:mod:`.kernel`) uses the planar reduction wherever it is exact: from an uplift (ℓ = 0)
for as long as every piece of the excitation lies on the line of the uplift, whatever the azimuth of that
line and however the motion was given (one component, a pulse, two equal or proportional components, a
rotated record, the one-directional tail of a pair whose other component has ended); where a piece leaves
the line the 3D equations take over from the planar state.  "On the line" is a round-off statement:
the component across the line is at most :data:`LINE_TOLERANCE` of the sample's size.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..motions.excitation import EXC_NONE, EXC_SAMPLES

LINE_TOLERANCE = 1e-12
"""A sample (ü_gx, ü_gy) lies on a line when its component across it is at most this fraction of |ü_g|.

Rounding puts a rotated record off its line by at most 1.05 ε = 2.3e-16 of each sample (measured: three
records × ten azimuths × three scales; the line read from one sample), two equal components by less; a
record file carries 2–8 significant digits (the FEMA P695 AT2 files 7–8), so a component across the line that
a file can carry is of order 1e-8 of the sample or more.  1e-12 lies four decades above the first and four
below the second."""


@njit(cache=True, inline="always")
def off_line(x, y, lx, ly):
    """True when the vector (x, y) has a component across the unit line (lx, ly) above
    :data:`LINE_TOLERANCE` of its length (a zero vector is on every line)."""
    return abs(x * ly - y * lx) > LINE_TOLERANCE * math.sqrt(x * x + y * y)


@njit(cache=True)
def piece_line(t, kind, params, sx, sy, dirx, diry):
    """(l_x, l_y): the unit direction of the ground acceleration on the piece of the excitation at t [s]
    (a record: the larger of the two samples that bound the piece — a sample, not an interpolated value,
    so the line carries no more than the samples' own rounding; a pulse: its direction).  (1, 0) where
    the excitation is zero there."""
    if kind == EXC_SAMPLES:
        n = sx.shape[0]
        i = min(max(int(math.floor(t / params[1] + 1e-9)), 0), n - 1)
        j = min(i + 1, n - 1)
        xi, yi, xj, yj = sx[i], sy[i], sx[j], sy[j]
        if xj * xj + yj * yj > xi * xi + yi * yi:
            xi, yi = xj, yj
        m = math.sqrt(xi * xi + yi * yi)
        if m == 0.0:
            return 1.0, 0.0
        return xi / m, yi / m
    if kind == EXC_NONE:
        return 1.0, 0.0
    m = math.sqrt(dirx * dirx + diry * diry)
    return dirx / m, diry / m


@njit(cache=True)
def piece_on_line(t0, t1, kind, params, sx, sy, dirx, diry, lx, ly):
    """True when the ground acceleration on [t0, t1] [s] — inside one linear piece of a record, as every
    step of the integrator is — lies on the unit line (l_x, l_y): both samples that bound the piece do (a
    record is linear between them); a pulse acts along its direction throughout; no excitation is on every
    line."""
    if kind == EXC_SAMPLES:
        n = sx.shape[0]
        if n == 0:
            return True
        i = min(max(int(math.floor(0.5 * (t0 + t1) / params[1])), 0), n - 1)
        j = min(i + 1, n - 1)
        return not (off_line(sx[i], sy[i], lx, ly) or off_line(sx[j], sy[j], lx, ly))
    if kind == EXC_NONE:
        return True
    return not off_line(dirx, diry, lx, ly)


def one_directional(kind: int, params: np.ndarray, sx: np.ndarray, sy: np.ndarray, dirx: float, diry: float) -> bool:
    """True when the whole excitation acts along one line (every sample on the line of the largest one,
    to :data:`LINE_TOLERANCE`): a planar motion, whichever way it was given (Eq 5.26)."""
    if kind != EXC_SAMPLES:
        return True
    m = np.hypot(sx, sy)
    if sx.size == 0 or m.max() == 0.0:
        return True
    k = int(np.argmax(m))
    lx, ly = sx[k] / m[k], sy[k] / m[k]
    return bool(np.all(np.abs(sx * ly - sy * lx) <= LINE_TOLERANCE * m))
