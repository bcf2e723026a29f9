"""Shared fixtures of the experiment tests: a slender free-vibration specimen and its synthetic records."""
from __future__ import annotations

import math

import pytest

from rockdesign.planar.system import block

SPECIMEN_TOML = """
[project]
name = "free-vibration specimen 2H = 500 mm, 2B = 50 mm"

[column]
height = "500 mm"
width = "50 mm"
mass = "0.329 kg"
mass_distribution = 0.543

[analysis]
g = "9.807 m/s^2"
"""
C_R_RIGHT = 0.93
C_R_LEFT = 0.93 * 1.05          # left and right impacts differ by 5 %
ALPHA = math.atan(0.1)


@pytest.fixture(scope="session")
def specimen():
    """The specimen of SPECIMEN_TOML as a system (2H = 0.5 m, tan α = 0.1, λ = 0.543)."""
    return block(0.25, 0.025, 0.329, 0.543, g=9.807)


def write_tilt_csv(path, t, theta, *, degrees=False, skip=(), nan_rows=()):
    """Write a measurement CSV (t, theta or theta_deg), leaving out rows ``skip`` and blanking ``nan_rows``."""
    with open(path, "w") as fh:
        fh.write("t,theta_deg\n" if degrees else "t,theta\n")
        for k, (a, b) in enumerate(zip(t, theta)):
            if k in skip:
                continue
            if k in nan_rows:
                fh.write(f"{a:.6f},nan\n")
                continue
            fh.write(f"{a:.6f},{math.degrees(b) if degrees else b:.8f}\n")
    return path
