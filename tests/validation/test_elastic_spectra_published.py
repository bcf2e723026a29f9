"""Elastic response spectra against published values (SPEC §5): PEER's NGA-West2 spectrum of RSN 8883 H1
and Boore's SMC2PSA spectrum of Whittier Narrows, Carson - Catskill 090 (both 5 % damping; numbers and
sources in tests/validation/data, from pyrotd's test fixtures).

PEER sub-steps a record where T < 10 Δt (Δt/m ≤ T/10, ü_g linear in between) and takes the peak at the
(sub-)samples; SMC2PSA takes it at the record's samples only, so it is compared where T ≥ 10 Δt.  A
peak taken only at the samples is up to 2 % low at short periods (the check that this test can fail)."""
from __future__ import annotations

import csv
import gzip
import math
from pathlib import Path

import numpy as np
import pytest

from rockdesign.motions.records import read_record_file
from rockdesign.motions.spectra import response_spectrum, sdof_response

DATA = Path(__file__).parent / "data"
G = 9.80665


def _table(name):
    with open(DATA / name, newline="") as fh:
        rows = list(csv.reader(line for line in fh if not line.startswith("#")))
    return np.array([[float(x) for x in row] for row in rows[1:]]).T


@pytest.fixture(scope="module")
def peer(tmp_path_factory):
    path = tmp_path_factory.mktemp("peer") / "RSN8883_14383980_13849360.AT2"
    path.write_bytes(gzip.decompress((DATA / "RSN8883_14383980_13849360.AT2.gz").read_bytes()))
    motion = read_record_file(path, gravity=G)
    periods, psa_g = _table("peer_ngawest2_rsn8883_h1_psa.csv")
    return motion, periods, psa_g


def test_peer_ngawest2_at_every_period(peer):
    """Agreement to 1e-4 from T = 0.01 s = 2 Δt to 20 s (measured: 1.4e-5; the published values have 7 digits)."""
    motion, periods, psa_g = peer
    assert motion.dt == 0.005 and motion.samples.size == 16396
    _, _, psa = response_spectrum(motion.scale * motion.samples, motion.dt, periods, 0.05)
    error = psa / G / psa_g - 1.0
    short = periods < 10 * motion.dt
    assert short.sum() >= 10
    assert np.max(np.abs(error[short])) < 1e-4, error[short]
    assert np.max(np.abs(error[~short])) < 1e-4, error[~short]


def test_a_peak_at_the_samples_only_is_low_at_short_periods(peer):
    """The discriminating case: at T = 0.042 s = 8.4 Δt the samples miss the peak by ≈ 2 %."""
    motion, periods, psa_g = peer
    k = int(np.argmin(np.abs(periods - 0.042)))
    omega = 2 * math.pi / periods[k]
    u, _ = sdof_response(motion.scale * motion.samples, motion.dt, omega, 0.05)
    sampled = np.max(np.abs(u)) * omega ** 2 / G
    assert sampled / psa_g[k] - 1.0 == pytest.approx(-0.0195, abs=0.001)
    _, _, psa = response_spectrum(motion.scale * motion.samples, motion.dt, periods[k:k + 1], 0.05)
    assert psa[0] / G == pytest.approx(psa_g[k], rel=1e-4)


def test_smc2psa_where_the_period_is_at_least_ten_steps():
    with gzip.open(DATA / "whittier_A-CAT090_gal.txt.gz", "rt") as fh:
        accel = np.loadtxt(fh, comments="#") / 100.0            # gal → m/s²
    dt = 0.02
    periods, psa_cm = _table("smc2psa_whittier_A-CAT090_psa.csv")
    long = periods >= 10 * dt
    _, _, psa = response_spectrum(accel, dt, periods[long], 0.05)
    error = psa * 100.0 / psa_cm[long] - 1.0
    # periods are published with 4 decimals (0.1333 for 2/15 s): 5e-4 covers that rounding (measured 2.5e-4)
    assert np.max(np.abs(error)) < 5e-4, error
