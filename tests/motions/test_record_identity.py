"""One recording, one entry (SPEC §14; rockdesign.motions.identity via resolve_motions).

A suite that lists the same recording twice — the same id, one file under two paths, a built-in record
beside its PEER file or its rsn: id, or the same samples under another name — is refused with a
ProjectError naming both entries and the file; the two components of one station are two recordings.
"""
from __future__ import annotations

import numpy as np
import pytest

from rockdesign.errors import ProjectError
from rockdesign.motions.config import parse_excitation, resolve_motions
from rockdesign.motions.identity import Entry, repeated_recording
from rockdesign.motions.library import load_record

G = 9.81


def resolve(raw, file):
    return resolve_motions(parse_excitation(raw, file=str(file), gravity=G), gravity=G)


def refused(raw, file):
    with pytest.raises(ProjectError) as info:
        resolve(raw, file)
    return info.value


def write_at2(path, samples_g, dt=0.01, station_line="Test Event, 1/1/2000, Test Station, 090"):
    rows = "\n".join("  ".join(f"{v: .7E}" for v in samples_g[i:i + 5]) for i in range(0, samples_g.size, 5))
    path.write_text(f"PEER NGA STRONG MOTION DATABASE RECORD\n{station_line}\n"
                    f"ACCELERATION TIME SERIES IN UNITS OF G\nNPTS= {samples_g.size}, DT= {dt:.4f} SEC\n{rows}\n")
    return path


@pytest.fixture
def record_file(tmp_path):
    rng = np.random.default_rng(7)
    (tmp_path / "rec").mkdir()
    return write_at2(tmp_path / "rec" / "r01.AT2", 0.1 * rng.standard_normal(400))


def test_same_id_twice(tmp_path):
    err = refused({"records": ["p695-ff/3a", "p695-ff/3a"]}, tmp_path / "p.toml")
    assert err.file == str(tmp_path / "p.toml") and err.key == "excitation"
    assert "'p695-ff/3a' (excitation.records[0])" in err.found and "(excitation.records[1])" in err.found
    assert "the same record id" in err.found


def test_one_file_under_two_paths(tmp_path, record_file):
    project = tmp_path / "p.toml"
    err = refused({"records": ["rec/r01.AT2", "rec/./r01.AT2"]}, project)   # one path once spelled out
    assert "excitation.records[0]" in err.found and "excitation.records[1]" in err.found
    err = refused({"records": ["rec/r01.AT2", "rec/../rec/r01.AT2"]}, project)
    assert "the same file" in err.found and str(record_file) in err.found
    assert "excitation.records[0]" in err.found and "excitation.records[1]" in err.found
    (tmp_path / "link.AT2").symlink_to(record_file)
    err = refused({"records": ["file:rec/r01.AT2", "./link.AT2"]}, project)
    assert "the same file" in err.found


def test_same_samples_under_another_name_scale_and_polarity(tmp_path, record_file):
    # a one-column copy of the same accelerogram, ×(−2) and in m/s²: no metadata, the same recording
    samples_g = np.loadtxt(record_file, skiprows=4).ravel()
    copy = tmp_path / "copy.txt"
    copy.write_text("# dt=0.01\n# units: m/s^2\n" + "\n".join(f"{v:.9e}" for v in -2 * G * samples_g) + "\n")
    err = refused({"records": ["rec/r01.AT2", "file:copy.txt"]}, tmp_path / "p.toml")
    assert "the same samples" in err.found


def test_builtin_beside_its_rsn_id_in_a_suite(tmp_path):
    # thesis-table-4.1 lists rsn:900:270, resolved to the built-in p695-ff/11a
    err = refused({"suites": ["thesis-table-4.1"], "records": ["p695-ff/11a"]}, tmp_path / "p.toml")
    assert "'rsn:900:270' (suite thesis-table-4.1, built-in p695-ff/11a)" in err.found
    assert "'p695-ff/11a' (excitation.records[0])" in err.found and "Yermo" in err.found


def test_builtin_beside_its_peer_file(tmp_path, shared_records):
    peer = shared_records / "FEMAP695_FF11a_RSN900_YER270.AT2"
    err = refused({"records": ["p695-ff/11a", str(peer)]}, tmp_path / "p.toml")
    assert "RSN 900" in err.found and peer.name in err.found
    # and the PEER file found by its RSN in a records folder beside the file itself
    err = refused({"records": ["rsn:6:180", str(shared_records / "RSN6_IMPVALL.I_I-ELC180.AT2")],
                   "records_dir": str(shared_records)}, tmp_path / "p.toml")
    assert "the same file" in err.found


def test_two_components_of_one_station_are_two_recordings(tmp_path, shared_records):
    resolved = resolve({"records": ["p695-ff/11a", "p695-ff/11b", "p695-nfp/6@0", "p695-nfp/6@90",
                                    str(shared_records / "RSN6_IMPVALL.I_I-ELC180.AT2"),
                                    str(shared_records / "RSN6_IMPVALL.I_I-ELC270.AT2")]}, tmp_path / "p.toml")
    assert len(resolved.records) == 6


def test_rotated_builtin_is_the_recording_of_its_azimuth(shared_records):
    # the NS component rotated from the FEMA pair, as a built-in and as a derived PEER-style file (RSN 821)
    entries = [Entry("p695-nfp/6@0", "a", load_record("p695-nfp/6@0"), {}),
               Entry("ns", "b", load_record(
                   str(shared_records / "DERIVED_RSN821_ERZIKAN_ERZ-NS_from_FEMAP695_rotation.AT2")), {})]
    a, b, why = repeated_recording(entries)
    assert (a.record_id, b.record_id) == ("p695-nfp/6@0", "ns") and "RSN 821" in why


def test_all_builtin_records_are_distinct():
    from rockdesign.motions.library import builtin_ids
    entries = [Entry(rid, "built-in", load_record(rid), {}) for rid in builtin_ids()]
    assert len(entries) == 100 and repeated_recording(entries) is None


def test_duplicate_within_one_user_suite_names_the_manifest(tmp_path, record_file):
    manifest = tmp_path / "mine.toml"
    manifest.write_text('name = "mine"\n[[records]]\nfile = "rec/r01.AT2"\n[[records]]\nfile = "./rec/r01.AT2"\n')
    err = refused({"suites": [str(manifest)]}, tmp_path / "p.toml")
    assert err.file == str(manifest) and "suite mine" in err.found


def test_missing_record_listed_twice(tmp_path):
    err = refused({"records": ["rsn:12345:090", "rsn:12345:090"]}, tmp_path / "p.toml")
    assert "the same record id" in err.found
