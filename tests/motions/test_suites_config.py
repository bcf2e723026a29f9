"""Suites (built-in and user manifests) and the [excitation] table: resolution, missing records
listed with reasons, stable order, scaling, validation messages."""
from __future__ import annotations

import numpy as np
import pytest

from rockdesign.errors import MotionError, ProjectError
from rockdesign.motions.config import default_excitation, parse_excitation, resolve_motions
from rockdesign.motions.library import load_record
from rockdesign.motions.suites import list_records
from rockdesign.motions.motion import record_motion
from rockdesign.motions.spectra import sd_max
from rockdesign.motions.suites import list_suites, load_suite, save_suite

G = 9.81


def test_builtin_suites_listed():
    names = {s["name"]: s["n_records"] for s in list_suites()}
    assert names == {"p695-farfield": 44, "p695-nearfield-pulse": 28, "p695-nearfield-nopulse": 28,
                     "thesis-table-4.1": 13, "thesis-table-4.2": 8}


def test_p695_suite_order_and_default_scale():
    suite = load_suite("p695-nearfield-nopulse")
    assert [rid for rid, _, _ in suite.records][:3] == ["p695-nfnp/15a", "p695-nfnp/15b", "p695-nfnp/16a"]
    assert not suite.missing
    assert suite.default_scale.method == "factor" and suite.default_scale.value == 1.0


def test_thesis_table_41_without_records_dir():
    """A7–A10 resolve from built-in P695 data and reproduce Table 4.1 (SD_max at 1 % damping, SPEC §5)."""
    suite = load_suite("thesis-table-4.1", gravity=9.80665)
    assert [e.meta["label"] for e in suite.entries] == [f"A{i}" for i in range(1, 14)]
    found = {meta["label"]: (rid, motion, meta) for rid, motion, meta in suite.records}
    assert sorted(found) == ["A10", "A7", "A8", "A9"]
    assert found["A9"][2]["resolved_from"] == "built-in p695-ff/11a"
    assert found["A7"][2]["resolved_from"] == "built-in p695-nfp/6@0"
    for rid, motion, meta in found.values():
        assert motion.pga / 9.80665 == pytest.approx(meta["thesis_pga_g"], abs=0.0051), rid
        assert sd_max(motion, 0.01)[0] == pytest.approx(meta["thesis_sd_max_m"], abs=0.0071), rid
    assert len(suite.missing) == 9
    for rid, reason in suite.missing:
        assert rid.startswith("rsn:") and "no records folder given" in reason


def test_thesis_table_42_with_records_dir(shared_records):
    suite = load_suite("thesis-table-4.2", records_dir=shared_records)
    labels = [meta["label"] for _, _, meta in suite.records]
    assert labels == ["B1", "B2", "B3"]
    assert all("records dir" in meta["resolved_from"] for _, _, meta in suite.records)
    missing = dict(suite.missing)
    assert list(missing) == ["rsn:568:090", "rsn:645:280", "rsn:730:090", "rsn:783:270", "rsn:983:292"]
    assert "RSN568_*090.AT2" in missing["rsn:568:090"] and str(shared_records) in missing["rsn:568:090"]
    # nothing silently skipped
    assert len(suite.records) + len(suite.missing) == 8


def test_list_records_of_a_suite_marks_missing():
    rows = list_records("thesis-table-4.2")
    assert len(rows) == 8 and all(r["pga"] is None and r["missing"] for r in rows)


def test_rsn_ids_resolve_from_builtin_and_records_dir(shared_records):
    assert load_record("rsn:900:270").meta["resolved_from"] == "built-in p695-ff/11a"
    motion = load_record("rsn:6:180", records_dir=shared_records)
    assert motion.meta["rsn"] == 6 and motion.samples.size == 5372
    from rockdesign.errors import RecordError
    with pytest.raises(RecordError, match="RSN 6 component 180 not found"):
        load_record("rsn:6:180")


def test_user_manifest_with_file_entries_and_missing(tmp_path, shared_records):
    manifest = tmp_path / "mine.toml"
    manifest.write_text(f'''name = "mine"
description = "two files and a builtin"
[scale]
method = "pga"
target = "0.2 g"
[[records]]
file = "{shared_records / 'elcentro_chopra_NS.csv'}"
label = "chopra"
[[records]]
file = "missing/file.AT2"
[[records]]
id = "p695-ff/2b"
''')
    suite = load_suite(manifest)
    assert [rid for rid, _, _ in suite.records] == [f"file:{shared_records / 'elcentro_chopra_NS.csv'}", "p695-ff/2b"]
    assert suite.missing[0][0] == "file:missing/file.AT2" and "file not found" in suite.missing[0][1]
    assert suite.default_scale.method == "pga"


def test_manifest_errors(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "bad"\n[[records]]\nlabel = "x"\n')
    with pytest.raises(MotionError) as info:
        load_suite(bad)
    assert info.value.file == str(bad) and info.value.key == "records[0]"
    bad.write_text('name = "bad"\n[[records]]\nid = "p695-ff/23a"\n')
    with pytest.raises(MotionError, match="records\\[0\\].id"):
        load_suite(bad)
    with pytest.raises(MotionError, match="did you mean p695-farfield"):
        load_suite("p695-farfeild")


def test_save_and_load_roundtrip(tmp_path):
    rng = np.random.default_rng(1)
    motions = [record_motion(f"m{i}", rng.standard_normal(300), 0.01, scale=2.0, meta={"seed_value": 7, "event": "x"})
               for i in range(3)]
    path = save_suite(tmp_path / "ens", motions, name="ens", description="test ensemble", meta={"generator": "test"})
    assert path.suffix == ".toml" and path.with_suffix(".npz").is_file()
    suite = load_suite(path)
    assert suite.name == "ens" and suite.meta["generator"] == "test"
    assert [rid for rid, _, _ in suite.records] == ["ens/001", "ens/002", "ens/003"]
    for original, (_, loaded, meta) in zip(motions, suite.records):
        np.testing.assert_array_equal(loaded.samples, 2.0 * original.samples)
        assert loaded.dt == 0.01 and meta["seed_value"] == 7 and meta["event"] == "x"


def test_parse_excitation_contract_example(tmp_path):
    project = tmp_path / "p.toml"
    spec = parse_excitation({"design_pga": "0.35 g", "suites": ["p695-farfield"],
                             "scale": {"method": "pga", "target": "0.35 g"}, "records_dir": str(tmp_path)},
                            file=str(project), gravity=G)
    assert spec.design_pga == pytest.approx(0.35 * G)
    assert spec.suites == ("p695-farfield",) and spec.records_dir == tmp_path
    assert spec.scale.method == "pga" and not spec.default_used


def test_default_excitation():
    spec = parse_excitation(None, file="p.toml", gravity=G)
    assert spec.default_used and spec.suites == ("p695-farfield",) and spec.effective_scale() is None
    spec = default_excitation(0.3 * G)
    assert spec.default_used and spec.effective_scale().method == "pga"
    assert spec.effective_scale().value == pytest.approx(0.3 * G)


@pytest.mark.parametrize("raw,key,fragment", [
    ({"desing_pga": "0.3 g"}, "excitation.desing_pga", "did you mean 'design_pga'"),
    ({"design_pga": "0.3 m"}, "excitation.design_pga", "acceleration"),
    ({"suites": ["p695-farfeild"]}, "excitation.suites[0]", "did you mean p695-farfield"),
    ({"suites": "p695-farfield", "records": [3]}, "excitation.records", "list of non-empty strings"),
    ({"records_dir": "/no/such/folder"}, "excitation.records_dir", "not found"),
    ({"scale": {"method": "pga", "target": "x"}}, "excitation.scale.target", "acceleration"),
    ({"time_scale": {"model_size": "0.5 m"}}, "excitation.time_scale.prototype_size", "both sizes"),
    ({"time_scale": -1}, "excitation.time_scale", "positive"),
])
def test_parse_excitation_errors(raw, key, fragment):
    with pytest.raises(ProjectError) as info:
        parse_excitation(raw, file="p.toml", gravity=G)
    assert info.value.file == "p.toml" and info.value.key == key and fragment in str(info.value)


def test_resolve_order_scaling_and_missing():
    # (p695-ff/11a beside the suite's rsn:900:270 is one recording, refused: tests/motions/test_record_identity.py)
    spec = parse_excitation({"suites": ["thesis-table-4.1"], "records": ["p695-ff/1a", "p695-ff/12a", "rsn:1:x"],
                             "scale": {"method": "pga", "target": "0.3 g"}}, file="p.toml", gravity=G)
    resolved = resolve_motions(spec, gravity=G)
    assert [r.id for r in resolved.records] == ["rsn:821:NS", "rsn:821:EW", "rsn:900:270", "rsn:900:360",
                                                "p695-ff/1a", "p695-ff/12a"]
    assert all(r.motion.pga == pytest.approx(0.3 * G, rel=1e-12) for r in resolved.records)
    assert [r.meta["label"] for r in resolved.records[:4]] == ["A7", "A8", "A9", "A10"]
    assert [m[0] for m in resolved.missing][-1] == "rsn:1:x" and len(resolved.missing) == 10
    assert "0.3 g" in resolved.scale_description


def test_resolve_default_design_pga_and_time_scale():
    spec = default_excitation(0.2 * G)
    resolved = resolve_motions(spec, gravity=G)
    assert len(resolved.records) == 44 and resolved.default_used and not resolved.missing
    assert resolved.records[0].scale == pytest.approx(0.2 / 0.415783, rel=1e-5)
    spec = parse_excitation({"records": ["p695-ff/11a"], "time_scale": {"model_size": "1 m", "prototype_size": "4 m"},
                             "scale": {"method": "uplift", "multiple": 2}}, file="p.toml", gravity=G)
    resolved = resolve_motions(spec, gravity=G, uplift_acceleration=1.0)
    record = resolved.records[0]
    assert record.motion.dt == pytest.approx(0.01) and record.motion.pga == pytest.approx(2.0)
    assert "time scaled by 0.5" in resolved.scale_description


def test_resolve_suite_default_rule_without_design_pga(tmp_path):
    manifest = tmp_path / "s.toml"
    manifest.write_text('name = "s"\n[scale]\nmethod = "factor"\nvalue = 2.0\n[[records]]\nid = "p695-ff/3a"\n')
    spec = parse_excitation({"suites": [str(manifest)], "records": ["p695-ff/3b"]}, file="p.toml", gravity=G)
    resolved = resolve_motions(spec, gravity=G)
    assert [r.scale for r in resolved.records] == [2.0, 1.0]
