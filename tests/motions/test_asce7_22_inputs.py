"""ASCE 7-22 §16.2 inputs that passed silently (issue 49): ranges of SMS, SM1, TL and periods, and the identity
of ground motions (a shifted copy, one station split in two, two stations made one).

``SMS = "1e400 g"`` became infinity and the suite was "conformant" with factors 4.55–21.1; ``periods =
["0.001 ms", "2 s"]`` ran for minutes without a word; a copy of p695-ff/2a delayed by 2 s counted as a new
recording; Capitola and Gilroy #3 declared one ground motion were scaled as a pair; 11 stations whose
components each had their own ``ground_motion`` counted as 22 ground motions.  Each is refused, from the
library (a ProjectError naming file, key, expected, found) and from the command line (exit 2, one line).
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.errors import ProjectError
from rockdesign.motions.config import parse_excitation, resolve_motions
from rockdesign.motions.identity import SHIFT_CORRELATION, Entry, repeated_recording
from rockdesign.motions.library import load_record
from rockdesign.motions.motion import record_motion
from rockdesign.motions.scaling import parse_scale_rule
from rockdesign.paths import REPO_ROOT

G = 9.81
ASCE = REPO_ROOT / "examples" / "podium_asce7_22.toml"
ASCE_SCALE = 'scale = { method = "asce7-22", SMS = "0.30 g", SM1 = "0.12 g", TL = "8 s" }'
runner = CliRunner()


def rule(**keys):
    return parse_scale_rule({"method": "asce7-22", **keys}, file="p.toml", gravity=G)


def resolve(raw, file):
    return resolve_motions(parse_excitation(raw, file=str(file), gravity=G), gravity=G)


def check_cli(tmp_path: Path, old: str, new: str):
    text = ASCE.read_text(encoding="utf-8")
    assert old in text
    project = tmp_path / "p.toml"
    project.write_text(text.replace(old, new), encoding="utf-8")
    r = runner.invoke(app, ["check", str(project), "--no-pdf", "-o", str(tmp_path / "out")])
    assert r.exit_code == 2, (r.exit_code, r.output)
    assert "Traceback" not in r.output and not (tmp_path / "out").exists()
    flat = " ".join(r.stderr.split())
    assert flat.count("error:") == 1, flat
    return flat


@pytest.fixture(autouse=True)
def no_compiling(monkeypatch):
    def boom(*args, **kwargs):
        raise AssertionError("compiled kernels for a bad input")
    monkeypatch.setattr("rockdesign.execution.compilation.prepare", boom)


# ------------------------------------------------------------------ finite, physical MCE_R parameters
@pytest.mark.parametrize("name,value,limit", [
    ("SMS", "1e400 g", "SMS > 0 and SMS ≤ 10 g"), ("SMS", "nan g", "an acceleration like"),
    ("SMS", "60 g", "SMS > 0 and SMS ≤ 10 g"), ("SMS", "-0.3 g", "SMS > 0 and SMS ≤ 10 g"),
    ("SM1", "1e400 g", "SM1 > 0 and SM1 ≤ 10 g"), ("SM1", "0 g", "SM1 > 0 and SM1 ≤ 10 g"),
    ("TL", "1e999 s", "TL > 0 and TL ≤ 100 s"), ("TL", "1e6 s", "TL > 0 and TL ≤ 100 s"), ("TL", "inf s", "a time like"),
])
def test_mce_r_parameters_have_finite_physical_ranges(name, value, limit):
    keys = {"SMS": "0.6 g", "SM1": "0.3 g", "TL": "8 s", name: value}
    with pytest.raises(ProjectError) as err:
        rule(**keys)
    assert err.value.file == "p.toml" and err.value.key == f"excitation.scale.{name}"
    assert limit in err.value.expected and repr(value) in err.value.found


def test_the_largest_accepted_values_still_scale():
    r = rule(SMS="10 g", SM1="10 g", TL="100 s")
    assert r.spectrum.SMS == pytest.approx(10 * G) and r.spectrum.TL == 100.0


@pytest.mark.parametrize("periods", [["0.08 s", "1e400 s"], ["nan s", "2 s"]])
def test_a_period_range_is_finite(periods):
    with pytest.raises(ProjectError) as err:
        rule(SMS="0.6 g", SM1="0.3 g", periods=periods)
    assert err.value.key == "excitation.scale.periods"


def test_sms_1e400_g_from_the_command_line(tmp_path):
    flat = check_cli(tmp_path, 'SMS = "0.30 g"', 'SMS = "1e400 g"')
    assert "key 'excitation.scale.SMS'" in flat and "SMS > 0 and SMS ≤ 10 g" in flat and "'1e400 g' (not finite)" in flat


# ------------------------------------------------------------------ periods the records' samples resolve
def test_a_period_below_the_records_time_step_is_refused_at_once(tmp_path):
    """0.001 ms ran > 180 s (sub-stepped to T/10 at every sample); it is refused before any spectrum."""
    t0 = time.perf_counter()
    flat = check_cli(tmp_path, ASCE_SCALE, ASCE_SCALE.replace(' }', ', periods = ["0.001 ms", "2 s"] }'))
    assert time.perf_counter() - t0 < 60
    assert "key 'excitation.scale.periods'" in flat and "resolve" in flat
    assert "a lower bound ≥ 0.02 s, the largest time step of the suite's records" in flat and "1e-06 s" in flat


def test_the_limit_is_the_coarsest_time_step_of_the_suite(tmp_path):
    pair = ["p695-ff/11a", "p695-ff/11b"]                   # Landers, Yermo: Δt = 0.02 s
    assert load_record(pair[0]).dt == pytest.approx(0.02)
    scale = {"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g", "periods": ["0.019 s", "1 s"]}
    with pytest.raises(ProjectError) as err:
        resolve({"records": pair, "scale": scale}, tmp_path / "p.toml")
    assert err.value.key == "excitation.scale.periods" and "≥ 0.02 s" in err.value.expected
    assert "p695-ff/11" in err.value.expected
    resolved = resolve({"records": pair, "scale": dict(scale, periods=["0.02 s", "1 s"])}, tmp_path / "p.toml")
    assert resolved.asce7_22.conformant and resolved.asce7_22.period_range.lo == 0.02


def test_a_range_derived_from_a_stiff_structure_is_keyed_by_the_rule(tmp_path):
    spec = parse_excitation({"records": ["p695-ff/11a", "p695-ff/11b"],
                             "scale": {"method": "asce7-22", "SMS": "0.6 g", "SM1": "0.3 g"}},
                            file=str(tmp_path / "p.toml"), gravity=G)
    with pytest.raises(ProjectError) as err:
        resolve_motions(spec, gravity=G, characteristic_periods={"superstructure fixed-base period T_s": 0.05})
    assert err.value.key == "excitation.scale" and "0.01 s" in err.value.found and "§16.2.1" in err.value.found


# ------------------------------------------------------------------ one recording, shifted
def write_at2(path: Path, samples_g: np.ndarray, dt: float, station: str = "Test Event, 1/1/2000, Test Station, 090"):
    rows = "\n".join("  ".join(f"{v: .7E}" for v in samples_g[i:i + 5]) for i in range(0, samples_g.size, 5))
    path.write_text(f"PEER NGA STRONG MOTION DATABASE RECORD\n{station}\nACCELERATION TIME SERIES IN UNITS OF G\n"
                    f"NPTS= {samples_g.size}, DT= {dt:.4f} SEC\n{rows}\n")
    return path


@pytest.mark.parametrize("how", ["delayed, padded", "delayed, same length", "first 2 s cut", "flipped and halved"])
def test_a_shifted_copy_under_another_name_is_one_recording(tmp_path, how):
    original = load_record("p695-ff/2a")
    g = np.asarray(original.samples) / G
    shift = int(round(2.0 / original.dt))
    copy = {"delayed, padded": np.concatenate([np.zeros(shift), g]),
            "delayed, same length": np.concatenate([np.zeros(shift), g])[:g.size],
            "first 2 s cut": g[shift:],
            "flipped and halved": -0.5 * np.concatenate([np.zeros(shift), g])}[how]
    path = write_at2(tmp_path / "another_name.AT2", copy, original.dt)
    with pytest.raises(ProjectError) as err:
        resolve({"records": ["p695-ff/2a", str(path)]}, tmp_path / "p.toml")
    assert err.value.key == "excitation" and "another_name.AT2" in err.value.found
    assert "shifted by" in err.value.found and "2 s" in err.value.found and "cross-correlation" in err.value.found


def test_distinct_recordings_stay_far_below_the_threshold():
    """Every pair of distinct built-in records on one time step correlates at most 0.52 (docs/records.md)."""
    from scipy import signal

    from rockdesign.motions.library import builtin_ids
    records = [load_record(i) for i in builtin_ids()]
    entries = [Entry(r.meta["id"], "built-in", r, {}) for r in records]
    assert repeated_recording(entries) is None
    a, b = (np.asarray(load_record(i).samples) for i in ("p695-ff/7a", "p695-ff/7b"))
    rho = np.max(np.abs(signal.correlate(a / np.linalg.norm(a), b / np.linalg.norm(b), method="fft")))
    assert 0.5 < rho < 0.52 < SHIFT_CORRELATION


# ------------------------------------------------------------------ one ground motion, one station
def manifest(tmp_path: Path, body: str, name: str = "mine") -> Path:
    path = tmp_path / f"{name}.toml"
    path.write_text(f'name = "{name}"\n' + body, encoding="utf-8")
    return path


def test_a_pair_of_two_stations_is_refused(tmp_path):
    path = manifest(tmp_path, '[[records]]\nid = "p695-ff/13a"\nground_motion = "loma prieta"\n'
                              '[[records]]\nid = "p695-ff/14b"\nground_motion = "loma prieta"\n')
    with pytest.raises(ProjectError) as err:
        resolve({"suites": [str(path)]}, tmp_path / "p.toml")
    e = err.value
    assert e.file == str(path) and e.key == "records[1].ground_motion"
    assert "two stations" in str(e) and "Capitola, RSN 752" in e.found and "Gilroy Array #3, RSN 767" in e.found


def test_components_of_one_station_as_separate_ground_motions_are_refused(tmp_path):
    body = "".join(f'[[records]]\nid = "p695-ff/{n}{c}"\nground_motion = "gm {n}{c}"\n'
                   for n in range(1, 12) for c in "ab")
    path = manifest(tmp_path, body, "split")
    with pytest.raises(ProjectError) as err:
        resolve({"suites": [str(path)]}, tmp_path / "p.toml")
    e = err.value
    assert e.file == str(path) and e.key == "records[1].ground_motion"
    assert "'gm 1a'" in e.found and "'gm 1b'" in e.found and "RSN 953" in e.found
    assert "count ground motions, not components" in e.expected


def test_a_builtin_beside_the_other_component_of_its_station(tmp_path, shared_records):
    with pytest.raises(ProjectError) as err:
        resolve({"records": ["p695-ff/11a", str(shared_records / "FEMAP695_FF11b_RSN900_YER360.AT2")]},
                tmp_path / "p.toml")
    assert err.value.key == "excitation" and "separate ground motions" in str(err.value) and "RSN 900" in err.value.found


def test_declared_pairs_of_one_station_each_are_accepted(tmp_path):
    body = "".join(f'[[records]]\nid = "p695-ff/{n}{c}"\nground_motion = "gm {n}"\n' for n in (13, 14) for c in "ab")
    resolved = resolve({"suites": [str(manifest(tmp_path, body))]}, tmp_path / "p.toml")
    assert len(resolved.records) == 4


@pytest.mark.parametrize("suite", ["p695-farfield", "p695-nearfield-pulse", "p695-nearfield-nopulse",
                                   "thesis-table-4.1"])
def test_the_built_in_suites_are_consistent(tmp_path, suite):
    assert resolve({"suites": [suite]}, tmp_path / "p.toml").records


def test_a_split_suite_from_the_command_line(tmp_path):
    body = "".join(f'[[records]]\nid = "p695-ff/{n}{c}"\nground_motion = "gm {n}{c}"\n'
                   for n in range(1, 12) for c in "ab")
    path = manifest(tmp_path, body, "split")
    flat = check_cli(tmp_path, 'suites = ["p695-farfield"]', f'suites = ["{path}"]')
    assert str(path) in flat and "key 'records[1].ground_motion'" in flat and "separate ground motions" in flat


def test_a_shifted_copy_from_the_command_line(tmp_path):
    original = load_record("p695-ff/2a")
    g = np.asarray(original.samples) / G
    copy = write_at2(tmp_path / "delayed.AT2", np.concatenate([np.zeros(int(round(2.0 / original.dt))), g]),
                     original.dt)
    flat = check_cli(tmp_path, 'suites = ["p695-farfield"]',
                     f'suites = ["p695-farfield"]\nrecords = ["{copy}"]')
    assert "key 'excitation'" in flat and "delayed.AT2" in flat and "shifted by 2 s" in flat
