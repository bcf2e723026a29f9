"""``scale = { method = "asce7-22", ... }`` through the [excitation] table and resolve_motions (CONTRACT §7.1).

One factor per ground motion, shared by its two components, equal to the factors of
rockdesign.motions.asce7_22 (tested against its definition in tests/motions/test_asce7_22.py); a suite of
single components, or one without a period range, is refused naming the file and key.
"""
from __future__ import annotations

import pytest

from rockdesign.errors import ProjectError
from rockdesign.motions.asce7_22 import rocking_structure_periods
from rockdesign.motions.config import parse_excitation, resolve_motions
from rockdesign.motions.grouping import ground_motion_id

G = 9.81
PODIUM = rocking_structure_periods(fixed_base=0.30, uplifted=0.30 / 2.147, rocking=1.364)
RULE = {"method": "asce7-22", "SMS": "0.60 g", "SM1": "0.30 g", "TL": "8 s"}


def test_farfield_suite_one_factor_per_ground_motion(tmp_path):
    spec = parse_excitation({"suites": ["p695-farfield"], "scale": RULE}, file=str(tmp_path / "p.toml"), gravity=G)
    resolved = resolve_motions(spec, gravity=G, characteristic_periods=PODIUM)
    result = resolved.asce7_22
    assert len(resolved.records) == 44 and result.conformant and result.min_ratio == pytest.approx(0.9)
    assert resolved.rules == [(None, spec.scale)]
    by_gm = {}
    for record in resolved.records:
        gm = ground_motion_id(record.id, record.meta)
        by_gm.setdefault(gm, set()).add(record.scale)
        assert record.scale == result.factors[gm]
        assert record.motion.scale == pytest.approx(result.factors[gm], rel=1e-15)
    assert len(by_gm) == 22 and all(len(f) == 1 for f in by_gm.values())
    assert result.period_range.lo == pytest.approx(0.2 * 0.30 / 2.147) and not result.period_range.given
    assert "ASCE 7-22 §16.2.3" in resolved.scale_description


def test_period_range_given_in_the_project(tmp_path):
    spec = parse_excitation({"records": ["p695-ff/11a", "p695-ff/11b", "p695-ff/12a", "p695-ff/12b"],
                             "scale": dict(RULE, periods=["0.1 s", "2 s"])}, file=str(tmp_path / "p.toml"), gravity=G)
    resolved = resolve_motions(spec, gravity=G)                 # no structure needed
    assert resolved.asce7_22.period_range.as_list() == [0.1, 2.0] and resolved.asce7_22.period_range.given
    assert set(resolved.asce7_22.factors) == {"p695-ff/11", "p695-ff/12"}
    # with the structure's periods too, the basis names both
    resolved = resolve_motions(spec, gravity=G, characteristic_periods=PODIUM)
    assert "would be 0.0279–2.73 s" in resolved.asce7_22.period_range.basis


def test_no_period_range(tmp_path):
    spec = parse_excitation({"records": ["p695-ff/11a", "p695-ff/11b"], "scale": RULE},
                            file=str(tmp_path / "p.toml"), gravity=G)
    with pytest.raises(ProjectError) as info:
        resolve_motions(spec, gravity=G)
    assert info.value.file == str(tmp_path / "p.toml") and info.value.key == "excitation.scale.periods"


def test_single_components_cannot_conform(tmp_path):
    # thesis Table 4.1: A7/A8 are one pair (Erzincan NS/EW), A9/A10 another (Yermo); then a lone component
    spec = parse_excitation({"suites": ["thesis-table-4.1"], "records": ["p695-ff/1a"], "scale": RULE},
                            file=str(tmp_path / "p.toml"), gravity=G)
    with pytest.raises(ProjectError) as info:
        resolve_motions(spec, gravity=G, characteristic_periods=PODIUM)
    err = info.value
    assert err.file == str(tmp_path / "p.toml") and err.key == "excitation.scale"
    assert "cannot conform" in str(err) and "p695-ff/1 (p695-ff/1a): one component only" in err.found
    assert "p695-nfp/6" not in err.found and "p695-ff/11" not in err.found


def test_target_table_too_short_for_the_range(tmp_path):
    (tmp_path / "mce_r.csv").write_text("period [s], Sa [g]\n0.1, 0.6\n0.5, 0.6\n2.0, 0.15\n")
    spec = parse_excitation({"records": ["p695-ff/11a", "p695-ff/11b"],
                             "scale": {"method": "asce7-22", "target": "mce_r.csv"}},
                            file=str(tmp_path / "p.toml"), gravity=G)
    with pytest.raises(ProjectError) as info:
        resolve_motions(spec, gravity=G, characteristic_periods=PODIUM)
    assert info.value.key == "excitation.scale.target" and "does not cover" in str(info.value)
    resolved = resolve_motions(spec, gravity=G, characteristic_periods={"T": 0.6})       # 0.12–1.2 s: covered
    assert resolved.asce7_22.conformant


def test_design_pga_beside_asce7_22_is_refused(tmp_path):
    with pytest.raises(ProjectError) as info:
        parse_excitation({"design_pga": "0.3 g", "scale": RULE}, file=str(tmp_path / "p.toml"), gravity=G)
    assert info.value.key == "excitation.design_pga" and "asce7-22" in str(info.value)


def test_suite_manifest_rule(tmp_path):
    manifest = tmp_path / "pairs.toml"
    manifest.write_text('name = "pairs"\n[scale]\nmethod = "asce7-22"\nSMS = "0.6 g"\nSM1 = "0.3 g"\nTL = "8 s"\n'
                        'periods = ["0.1 s", "2 s"]\n'
                        + "".join(f'[[records]]\nid = "p695-ff/{n}"\n' for n in ("11a", "11b", "12a", "12b")))
    spec = parse_excitation({"suites": [str(manifest)]}, file=str(tmp_path / "p.toml"), gravity=G)
    resolved = resolve_motions(spec, gravity=G)
    assert resolved.asce7_22.conformant and resolved.rules[0][0] == "pairs"
    spec = parse_excitation({"suites": [str(manifest)], "records": ["p695-ff/1a"]}, file=str(tmp_path / "p.toml"),
                            gravity=G)
    with pytest.raises(ProjectError, match="cannot scale it beside other records"):
        resolve_motions(spec, gravity=G)
