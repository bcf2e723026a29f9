"""An independent reference for the cylinder: Lagrange's equations written from the kinematics alone,
integrated by scipy's ``solve_ivp`` (DOP853).  Shares no code or algebra with ``rockdesign.cylinder``.

Kinematics (thesis Eq 5.11, inverted pendulum ψ = −φ): the centre of mass sits at horizontal distance
ρ(θ) = B(1 − cosθ) + H sinθ from the footprint's centre, in the direction φ, at height
z(θ) = B sinθ + H cosθ (+ w_T on the spring–dashpot); the body's angular velocity is
ω = φ̇ e_z + θ̇ n − φ̇ e_3 (Eq 5.17), so |ω|² − (ω·e_3)² = θ̇² + φ̇² sin²θ and ω·e_3 = −φ̇(1 − cosθ).
Per unit mass:  T = ½[(ρ'² + z'² + I1) θ̇² + J(θ) φ̇² + 2 z' θ̇ ẇ + ẇ²],
J = ρ² + I1 sin²θ + I2 (1 − cosθ)²,  V = g z + ½ ω_n² w²,  D = ζ ω_n ẇ²,
with I1 = B²/4 + H²/3, I2 = B²/2; the ground acceleration acts as the force −ü_g on the centre of mass:
Q_θ = −ρ' (ü_gx cosφ + ü_gy sinφ),  Q_φ = ρ (ü_gx sinφ − ü_gy cosφ).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq


class LagrangianCylinder:
    """Equations of motion of the cylinder from T, V, D and Q above (SI)."""

    def __init__(self, H: float, B: float, g: float = 9.81, omega_n: float | None = None, zeta: float = 0.0):
        self.H, self.B, self.g = H, B, g
        self.I1, self.I2 = B * B / 4 + H * H / 3, B * B / 2
        self.omega_n, self.zeta = omega_n, zeta

    def rhs(self, t, y, ground):
        H, B, g, I1, I2 = self.H, self.B, self.g, self.I1, self.I2
        th, thd, ph, phd = y[:4]
        ax, ay = ground(t)
        rho = B * (1 - math.cos(th)) + H * math.sin(th)
        drho = B * math.sin(th) + H * math.cos(th)
        dz = B * math.cos(th) - H * math.sin(th)
        ddz = -B * math.sin(th) - H * math.cos(th)
        J = rho ** 2 + I1 * math.sin(th) ** 2 + I2 * (1 - math.cos(th)) ** 2
        dJ = 2 * rho * drho + 2 * I1 * math.sin(th) * math.cos(th) + 2 * I2 * (1 - math.cos(th)) * math.sin(th)
        a = drho ** 2 + dz ** 2 + I1
        q_th = -drho * (ax * math.cos(ph) + ay * math.sin(ph))
        q_ph = rho * (ax * math.sin(ph) - ay * math.cos(ph))
        phdd = (q_ph - dJ * thd * phd) / J
        if self.omega_n is None:
            thdd = (0.5 * dJ * phd ** 2 - g * dz + q_th) / a
            return [thd, thdd, phd, phdd]
        w, wd = y[4], y[5]
        om, ze = self.omega_n, self.zeta
        mass = np.array([[a, dz], [dz, 1.0]])
        force = np.array([0.5 * dJ * phd ** 2 - g * dz + q_th, -ddz * thd ** 2 - 2 * ze * om * wd - om * om * w])
        thdd, wdd = np.linalg.solve(mass, force)
        return [thd, thdd, phd, phdd, wd, wdd]


def record_ground(t_samples, ax, ay):
    """Piecewise-linear (ü_gx, ü_gy) of a record pair, zero after the last sample."""
    def ground(t):
        if t > t_samples[-1]:
            return 0.0, 0.0
        return float(np.interp(t, t_samples, ax)), float(np.interp(t, t_samples, ay))
    return ground


def uplift(t_samples, ax, ay, threshold):
    """First time |ü_g| = threshold (Eq 5.24), by brentq on the first sample interval that crosses it."""
    mag = np.hypot(ax, ay)
    i = int(np.argmax(mag >= threshold))
    f = lambda t: math.hypot(*record_ground(t_samples, ax, ay)(t)) - threshold  # noqa: E731
    return brentq(f, t_samples[i - 1], t_samples[i], xtol=1e-15)


def integrate_record(model: LagrangianCylinder, t_samples, ax, ay, t_stop, theta_seed=1e-7, rtol=1e-11,
                     atol=1e-13):
    """From rest: uplift, then DOP853 sample interval by sample interval (the kinks of the record) to t_stop.
    Returns (t_uplift, t, y) with y[:, k] at the record samples after uplift."""
    alpha = math.atan2(model.B, model.H)
    t_up = uplift(t_samples, ax, ay, model.g * math.tan(alpha))
    ground = record_ground(t_samples, ax, ay)
    gx, gy = ground(t_up)
    n = 4 if model.omega_n is None else 6
    y = np.zeros(n)
    y[0], y[2] = theta_seed, math.atan2(-gy, -gx)
    knots = [t_up] + [t for t in t_samples if t_up < t <= t_stop]
    out_t, out_y = [t_up], [y.copy()]
    for t0, t1 in zip(knots[:-1], knots[1:]):
        sol = solve_ivp(model.rhs, (t0, t1), y, method="DOP853", rtol=rtol, atol=atol, args=(ground,))
        y = sol.y[:, -1]
        out_t.append(t1)
        out_y.append(y.copy())
    return t_up, np.array(out_t), np.array(out_y).T
