"""Record-file reader: the staged real files against ../shared/ground_motions/MANIFEST.md, other
header layouts and units, and one test per malformed-file error (each names file and line)."""
from __future__ import annotations

import re

import numpy as np
import pytest

from rockdesign.errors import RecordError
from rockdesign.motions.records import read_record_file
from rockdesign.motions.spectra import sd_max

G_REFERENCE = 9.80665  # g of MANIFEST.md


def _manifest_rows(shared):
    text = (shared / "ground_motions" / "MANIFEST.md").read_text()
    rows = []
    for line in text.splitlines():
        if not line.startswith("| `"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        sd2 = re.match(r"([\d.]+)\s*\(([\d.]+)\)", cells[9])
        rows.append({"file": cells[0].strip("`"), "event": cells[1], "year": int(cells[2]), "station": cells[3],
                     "component": cells[4], "rsn": int(cells[5]), "dt": float(cells[6]), "npts": int(cells[7]),
                     "pga_g": float(cells[8]), "sd2": float(sd2.group(1)), "t2": float(sd2.group(2)),
                     "sd1": float(cells[10])})
    return rows


def test_staged_records_match_manifest(shared, shared_records):
    rows = _manifest_rows(shared)
    assert len(rows) == 12
    for row in rows:
        motion = read_record_file(shared_records / row["file"], gravity=G_REFERENCE)
        meta = motion.meta
        assert motion.dt == pytest.approx(row["dt"], rel=1e-12), row["file"]
        assert motion.samples.size == row["npts"], row["file"]
        assert motion.pga / G_REFERENCE == pytest.approx(row["pga_g"], abs=5.1e-5), row["file"]
        sd2, t2 = sd_max(motion, 0.02)
        sd1, _ = sd_max(motion, 0.01)
        assert sd2 == pytest.approx(row["sd2"], abs=5.1e-4), row["file"]
        assert t2 == pytest.approx(row["t2"], abs=5.1e-3), row["file"]
        assert sd1 == pytest.approx(row["sd1"], abs=5.1e-4), row["file"]
        if row["file"].endswith(".AT2"):
            assert meta["format"] == "PEER NGA AT2"
            assert meta["event"] == row["event"]
            assert meta["year"] == row["year"]
            assert meta["station"] == row["station"]
            assert meta["component"] == row["component"]
            assert meta["rsn"] == row["rsn"]
            assert meta["units"].lower() == "g"


def test_one_column_file_with_misleading_prose(shared_records):
    # the comment says "source labels dt=0.02 but dt=0.01 s is inferred"; the declaration line says dt=0.01
    motion = read_record_file(shared_records / "quakeio_elcentro_180_dt0.01.txt")
    assert motion.dt == 0.01 and motion.meta["format"] == "one column" and motion.meta["units"] == "g"


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


AT2_HEAD = ("PEER NGA STRONG MOTION DATABASE RECORD\n"
            "Landers, 6/28/1992, Yermo Fire Station, 270\n"
            "ACCELERATION TIME SERIES IN UNITS OF G\n")


def test_west1_layout_and_units(tmp_path):
    text = ("PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.\n"
            "LANDERS 06/28/92 1158, YERMO FIRE STATION, 270\n"
            "ACCELERATION TIME HISTORY IN UNITS OF G\n"
            "    6    0.0200    NPTS, DT\n"
            " .1000000E+00 -.2000000E+00  .3000000E+00 -.4000000E+00  .5000000E+00\n"
            " .0000000E+00\n")
    motion = read_record_file(_write(tmp_path, "YER270.AT2", text), gravity=10.0)
    assert motion.meta["event"] == "LANDERS" and motion.meta["year"] == 1992
    assert motion.meta["station"] == "YERMO FIRE STATION" and motion.meta["component"] == "270"
    np.testing.assert_allclose(motion.samples, [1.0, -2.0, 3.0, -4.0, 5.0, 0.0])
    assert motion.dt == 0.02


def test_glued_fortran_fields_and_cm_units(tmp_path):
    text = (AT2_HEAD.replace("G\n", "CM/S/S\n") + "NPTS=    4, DT=   .0100 SEC,\n"
            "  -.1000000E+01-.2000000E+01  .3000000E+01  .4000000E+01\n")
    motion = read_record_file(_write(tmp_path, "RSN900_LANDERS_YER270.AT2", text))
    np.testing.assert_allclose(motion.samples, [-0.01, -0.02, 0.03, 0.04])
    assert motion.meta["rsn"] == 900


def test_two_column_and_declared_units(tmp_path):
    path = _write(tmp_path, "a.csv", "time,acc (gal)\n0,0\n0.005,10\n0.01,-20\n0.015,5\n")
    motion = read_record_file(path)
    assert motion.dt == pytest.approx(0.005)
    np.testing.assert_allclose(motion.samples, [0, 0.1, -0.2, 0.05])
    override = read_record_file(path, units="m/s^2")
    np.testing.assert_allclose(override.samples, [0, 10, -20, 5])


def _expect(path, line, fragment):
    with pytest.raises(RecordError) as info:
        read_record_file(path)
    err = info.value
    assert err.file == str(path)
    assert err.line == line
    message = str(err)
    assert f"{path}:{line}" in message
    assert fragment in message
    return err


def test_truncated_data(tmp_path):
    path = _write(tmp_path, "t.AT2", AT2_HEAD + "NPTS=   10, DT=   .0200 SEC\n"
                  "  1.0E-03  2.0E-03  3.0E-03  4.0E-03  5.0E-03\n  6.0E-03  7.0E-03\n")
    err = _expect(path, 6, "truncated")
    assert "NPTS = 10" in str(err) and "7 values" in str(err)


def test_truncated_number_in_last_line(tmp_path):
    path = _write(tmp_path, "t.AT2", AT2_HEAD + "NPTS=   5, DT=   .0200 SEC\n"
                  "  1.0E-03  2.0E-03  3.0E-03  4.0E-03  5.0E-\n")
    _expect(path, 5, "unreadable sample value")


def test_npts_mismatch_more_values(tmp_path):
    path = _write(tmp_path, "m.AT2", AT2_HEAD + "NPTS=    3, DT=   .0200 SEC\n"
                  "  1.0E-03  2.0E-03\n  3.0E-03  4.0E-03\n")
    _expect(path, 6, "more samples than NPTS")


@pytest.mark.parametrize("dt_text", [".0000", "-.0100"])
def test_non_positive_dt(tmp_path, dt_text):
    path = _write(tmp_path, "d.AT2", AT2_HEAD + f"NPTS=    2, DT=   {dt_text} SEC\n  1.0E-03  2.0E-03\n")
    _expect(path, 4, "sample spacing must be positive")


def test_unreadable_npts_dt_line(tmp_path):
    path = _write(tmp_path, "h.AT2", AT2_HEAD + "POINTS 2 STEP 0.01\n  1.0E-03  2.0E-03\n")
    _expect(path, 4, "cannot read NPTS and DT")


def test_nan_value(tmp_path):
    path = _write(tmp_path, "n.AT2", AT2_HEAD + "NPTS=    4, DT=   .0200 SEC\n  1.0E-03  2.0E-03\n  NaN  4.0E-03\n")
    _expect(path, 6, "non-finite")


def test_unknown_units(tmp_path):
    path = _write(tmp_path, "u.AT2", AT2_HEAD.replace("UNITS OF G", "UNITS OF FURLONGS/FORTNIGHT") +
                  "NPTS=    2, DT=   .0200 SEC\n  1.0E-03  2.0E-03\n")
    _expect(path, 3, "unknown acceleration units")


def test_velocity_file_rejected(tmp_path):
    path = _write(tmp_path, "v.VT2", "PEER NGA STRONG MOTION DATABASE RECORD\nx, 1/1/2000, y, 090\n"
                  "VELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS=    2, DT=   .0200 SEC\n  1.0  2.0\n")
    _expect(path, 3, "not an acceleration record")


def test_non_uniform_time_step(tmp_path):
    path = _write(tmp_path, "nu.csv", "# units: g\n0.00, 0.1\n0.01, 0.2\n0.02, 0.1\n0.04, 0.0\n0.05, 0.0\n")
    err = _expect(path, 5, "non-uniform time step")
    assert "t = 0.04" in str(err)


def test_one_column_without_dt(tmp_path):
    path = _write(tmp_path, "c.txt", "# units: m/s^2\n0.1\n0.2\n0.3\n")
    _expect(path, 2, "sample spacing is not given")


def test_two_columns_without_units(tmp_path):
    path = _write(tmp_path, "c.txt", "0.0 0.1\n0.01 0.2\n0.02 0.3\n")
    _expect(path, 1, "units of the accelerations are not declared")


def test_declared_npts_mismatch(tmp_path):
    path = _write(tmp_path, "c.txt", "# npts=5 dt=0.01\n# units: g\n0.1\n0.2\n0.3\n")
    _expect(path, 5, "declared npts")


def test_inconsistent_columns(tmp_path):
    path = _write(tmp_path, "c.txt", "# units: g\n0.0 0.1\n0.01 0.2 0.5\n")
    _expect(path, 3, "inconsistent number of columns")


def test_missing_file(tmp_path):
    with pytest.raises(RecordError) as info:
        read_record_file(tmp_path / "nope.AT2")
    assert "nope.AT2" in str(info.value)
