"""Thesis App. A.1: the Ricker wavelets — symmetric Eq A.1 peaks at a_p and its Fourier spectrum at 1/T_p;
antisymmetric Eq A.2 with β = 1.38012 peaks at a_p.  Expected values: tests/validation/data/cases.json
(eqA.*)."""
from __future__ import annotations

import numpy as np

from casedata import case_tests
from rockdesign.motions.excitation import RICKER_ANTI_BETA
from rockdesign.motions.motion import pulse_motion


def _peak(kind):
    return float(np.max(np.abs(pulse_motion(kind, 1.0, 1.0).acceleration(np.linspace(0, 3, 300001)))))


def _fourier_peak_frequency(T_p=0.8):
    """Frequency [Hz] of the largest Fourier amplitude of Eq A.1 (zero-padded FFT, 0.002 Hz bins)."""
    dt = 0.001
    t = np.arange(0, 10 * T_p, dt)
    a = pulse_motion("ricker-sym", 1.0, T_p).acceleration(t)
    n = 2 ** int(np.ceil(np.log2(1 / (0.002 * dt))))
    spectrum = np.abs(np.fft.rfft(a, n))
    return float(np.fft.rfftfreq(n, dt)[np.argmax(spectrum)])


COMPUTE = {
    "eqA.1_max": lambda: _peak("ricker-sym"),
    "eqA.2_beta": lambda: [RICKER_ANTI_BETA, _peak("ricker-anti")],
    "eqA.1_peak_freq": _fourier_peak_frequency,
}

test_case = case_tests(COMPUTE)
