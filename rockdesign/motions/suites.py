"""Record suites: named lists of records with metadata and a default scaling rule.

A suite is a TOML manifest (built-in ones in ``ground_motions/*.toml``)::

    name = "thesis-table-4.1"
    description = "..."
    [scale]                      # default scaling rule (see rockdesign.motions.scaling)
    method = "factor"
    value = 1.0
    [[records]]                  # one table per record; the resolution keys are, by priority:
    npz = "ensemble.npz"         #   npz + key (+ dt, units): an array of an npz beside the manifest
    key = "synth_001"
    file = "records/x.AT2"       #   file (+ units, dt): a record file, relative to the manifest
    id = "p695-ff/11a"           #   id: any record id of rockdesign.motions.library
    rsn = 900                    #   rsn + component: the user's records folder first, then the
    component = "270"            #     built-in record (``builtin = "p695-ff/11a"`` or same RSN/component)
    label = "A9"                 # every other key is metadata (event, station, reference values...);
    ground_motion = "Yermo"      #   ground_motion groups the components of one station (motions.grouping)

Records that cannot be found (an ``rsn`` not in the records folder nor built in, a missing
``file``) are listed in :attr:`Suite.missing` with the reason — never skipped silently.
"""
from __future__ import annotations

import difflib
import math
import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import MotionError, RecordError
from ..paths import ground_motions_dir, user_path
from .library import builtin_for_rsn, builtin_ids, builtin_info, find_record_file, load_record, record_summary
from .motion import GroundMotion, record_motion
from .records import acceleration_factor, read_record_file
from .scaling import ScaleRule, parse_scale_rule

RESOLUTION_KEYS = {"id", "npz", "key", "file", "rsn", "component", "builtin", "dt", "units"}


@dataclass
class SuiteEntry:
    """One manifest record: its id, metadata, and the motion (None when missing, with the reason)."""

    id: str
    meta: dict
    motion: GroundMotion | None = None
    reason: str | None = None


@dataclass
class Suite:
    """A loaded suite.

    Attributes:
        name: suite name.
        description: one line.
        records: (id, GroundMotion [m/s²], meta) of every record found, in manifest order.
        missing: (id, reason) of every record not found, in manifest order.
        default_scale: the manifest's scaling rule (None if it has none).
        entries: all entries in manifest order (found and missing).
        path: the manifest file.
        meta: the manifest's other top-level keys (source, notes...).
    """

    name: str
    description: str
    records: list[tuple[str, GroundMotion, dict]]
    missing: list[tuple[str, str]]
    default_scale: ScaleRule | None
    entries: list[SuiteEntry] = field(default_factory=list)
    path: Path | None = None
    meta: dict = field(default_factory=dict)


def suite_path(name_or_path, key: str = "suites") -> Path:
    """The manifest of a built-in suite name, or the given path (``key``: where the user gave it, for
    the error message — the project file's ``suites`` or a command's ``--suite``).

    Raises:
        MotionError: unknown name (with the nearest built-in names).
    """
    text = str(name_or_path)
    path = user_path(text, key, error=MotionError)
    if path.suffix.lower() == ".toml" or path.is_file() or "/" in text:
        if not path.is_file():
            raise MotionError("suite file not found", file=str(path), expected="a suite manifest (*.toml)",
                              found="no such file")
        return path
    builtin = ground_motions_dir() / f"{text}.toml"
    if builtin.is_file():
        return builtin
    names = [s["name"] for s in list_suites()]
    close = difflib.get_close_matches(text, names, n=2)
    raise MotionError("unknown suite", key=key, expected=" | ".join(names) + " or a path to a *.toml",
                      found=repr(text), hint=f"did you mean {' or '.join(close)}?" if close else None)


def _read_manifest(path: Path) -> dict:
    try:
        with open(path, encoding="utf-8-sig") as fh:    # a UTF-8 BOM is not content
            return tomllib.loads(fh.read())
    except tomllib.TOMLDecodeError as exc:
        raise MotionError(f"invalid TOML ({exc})", file=str(path)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise MotionError(f"cannot read the suite manifest ({exc})", file=str(path)) from None


def list_suites() -> list[dict]:
    """Built-in suites: ``[{"name", "description", "n_records", "path"}]`` sorted by name."""
    out = []
    for path in sorted(ground_motions_dir().glob("*.toml")):
        data = _read_manifest(path)
        out.append({"name": data.get("name", path.stem), "description": data.get("description", ""),
                    "n_records": len(data.get("records", [])), "path": str(path)})
    return out


@lru_cache(maxsize=8)
def _npz(path: str, mtime: float) -> dict[str, np.ndarray]:
    with np.load(path) as data:
        return {k: data[k] for k in data.files}


def load_suite(name_or_path, *, gravity: float = 9.81, records_dir=None, key: str = "suites") -> Suite:
    """Load a suite and resolve its records (accelerations in m/s²).

    Args:
        name_or_path: built-in suite name (``p695-farfield``...) or path to a manifest.
        gravity: g [m/s²] converting records stored in g.
        records_dir: the user's folder of PEER AT2 files (for ``rsn`` entries).
        key: where the user named the suite (error messages): ``suites`` or ``--suite``.

    Raises:
        MotionError: unknown suite, invalid manifest; RecordError: unreadable record files.
    """
    path = suite_path(name_or_path, key)
    data = _read_manifest(path)
    file = str(path)
    records = data.get("records")
    if not isinstance(records, list) or not all(isinstance(r, dict) for r in records):
        raise MotionError("a suite needs [[records]] tables", file=file, key="records",
                          expected="one or more [[records]] tables",
                          found="no 'records' key" if records is None else f"records = {records!r}"[:120])
    default_scale = None
    if "scale" in data:
        default_scale = parse_scale_rule(data["scale"], file=file, key="scale", gravity=gravity)
    entries = []
    seen = set()
    for index, raw in enumerate(records):
        entry = _resolve_entry(raw, index, path, gravity, records_dir)
        if entry.id in seen:
            raise MotionError("duplicate record id in suite", file=file, key=f"records[{index}]",
                              expected="unique ids", found=entry.id)
        seen.add(entry.id)
        entries.append(entry)
    name = str(data.get("name", path.stem))
    meta = {k: v for k, v in data.items() if k not in ("name", "description", "records", "scale")}
    return Suite(
        name=name,
        description=str(data.get("description", "")),
        records=[(e.id, e.motion, e.meta) for e in entries if e.motion is not None],
        missing=[(e.id, e.reason) for e in entries if e.motion is None],
        default_scale=default_scale,
        entries=entries,
        path=path,
        meta=meta,
    )


def _resolve_entry(raw: dict, index: int, path: Path, gravity: float, records_dir) -> SuiteEntry:
    file = str(path)
    key = f"records[{index}]"
    meta = {k: v for k, v in raw.items() if k not in RESOLUTION_KEYS or k in ("rsn", "component")}
    if "npz" in raw or "key" in raw:
        for required in ("npz", "key", "dt"):
            if required not in raw:
                raise MotionError(f"npz records need '{required}'", file=file, key=f"{key}.{required}",
                                  expected="npz, key and dt", found="nothing")
        npz_path = (path.parent / raw["npz"]).resolve()
        if not npz_path.is_file():
            return SuiteEntry(str(raw.get("id", raw["key"])), meta, reason=f"npz file not found: {npz_path}")
        arrays = _npz(str(npz_path), npz_path.stat().st_mtime)
        if raw["key"] not in arrays:
            raise MotionError("array not in npz file", file=file, key=f"{key}.key",
                              expected=f"one of {', '.join(sorted(arrays)[:5])}...", found=repr(raw["key"]))
        dt = raw["dt"]
        if isinstance(dt, bool) or not isinstance(dt, (int, float)) or not (dt > 0 and math.isfinite(dt)):
            raise MotionError("invalid dt", file=file, key=f"{key}.dt", expected="a positive number of seconds",
                              found=repr(dt))
        factor = acceleration_factor(str(raw.get("units", "m/s^2")), gravity, file=file, key=f"{key}.units")
        record_id = str(raw.get("id", raw["key"]))
        motion = record_motion(record_id, np.asarray(arrays[raw["key"]], dtype=np.float64) * factor, float(dt),
                               meta=dict(meta, source_file=str(npz_path)))
        return SuiteEntry(record_id, dict(meta, resolved_from=f"{npz_path.name}:{raw['key']}"), motion)
    if "file" in raw:
        record_path = user_path(str(raw["file"]), f"{key}.file", file=file, base=path.parent, error=MotionError)
        record_id = str(raw.get("id", f"file:{raw['file']}"))
        if not record_path.is_file():
            return SuiteEntry(record_id, meta, reason=f"file not found: {record_path}")
        motion = read_record_file(record_path, units=raw.get("units"), dt=raw.get("dt"), gravity=gravity,
                                  name=record_id)
        motion.meta.update(meta)
        return SuiteEntry(record_id, dict(meta, resolved_from=f"file {record_path}"), motion)
    if "id" in raw:
        record_id = str(raw["id"])
        try:
            motion = load_record(record_id, gravity=gravity, records_dir=records_dir)
        except RecordError as exc:
            if record_id.lower().startswith("rsn:"):
                return SuiteEntry(record_id, meta, reason=exc.detail)
            raise MotionError(f"cannot load record ({exc.detail})", file=file, key=f"{key}.id",
                              expected=exc.expected, found=exc.found or repr(record_id), hint=exc.hint) from None
        motion.meta.update(meta)
        return SuiteEntry(record_id, dict(meta, resolved_from=motion.meta.get("resolved_from", "built-in")), motion)
    if "rsn" in raw:
        rsn, component = raw.get("rsn"), raw.get("component")
        if isinstance(rsn, bool) or not isinstance(rsn, int) or not isinstance(component, str) or not component:
            raise MotionError("rsn records need an integer rsn and a component string", file=file, key=key,
                              expected='rsn = 900, component = "270"', found=f"rsn={rsn!r}, component={component!r}")
        record_id = str(raw.get("id", f"rsn:{rsn}:{component}"))
        if records_dir is not None:
            found = find_record_file(records_dir, rsn, component)
            if found is not None:
                motion = read_record_file(found, gravity=gravity, name=record_id)
                motion.meta.update(meta, id=record_id)
                return SuiteEntry(record_id, dict(meta, resolved_from=f"records dir: {found}"), motion)
        builtin = raw.get("builtin") or builtin_for_rsn(rsn, component)
        if builtin:
            try:
                motion = load_record(builtin, gravity=gravity)
            except RecordError as exc:
                raise MotionError(f"invalid built-in record ({exc.detail})", file=file, key=f"{key}.builtin",
                                  expected="a built-in record id", found=repr(builtin)) from None
            motion = GroundMotion(record_id, motion.kind, motion.params, motion.samples,
                                  dict(motion.meta, **meta, id=record_id, builtin=builtin))
            return SuiteEntry(record_id, dict(meta, resolved_from=f"built-in {builtin}"), motion)
        pattern = f"RSN{rsn}_*{component}.AT2"
        if records_dir is None:
            reason = (f"not built in, and no records folder given (set [excitation] records_dir, or pass "
                      f"records_dir, to a folder holding {pattern} from the PEER NGA database)")
        else:
            reason = f"no file {pattern} in {records_dir}, and not built in"
        return SuiteEntry(record_id, meta, reason=reason)
    raise MotionError("record entry has no source", file=file, key=key,
                      expected="one of: id; rsn + component; file; npz + key + dt",
                      found=", ".join(raw) or "an empty table")


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    text = str(value).replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{text}"'


def _plain(value) -> bool:
    if isinstance(value, (str, bool, int, float, np.integer, np.floating)):
        return not (isinstance(value, (float, np.floating)) and not math.isfinite(value))
    return isinstance(value, (list, tuple)) and all(_plain(v) and not isinstance(v, (list, tuple)) for v in value)


def save_suite(path, motions: list[GroundMotion], *, name: str | None = None, description: str = "",
               scale: dict | None = None, meta: dict | None = None) -> Path:
    """Write record motions as a suite: ``<path>.toml`` plus ``<path>.npz`` (float64, m/s²).

    Args:
        path: manifest path (``.toml`` added if missing); the npz gets the same stem.
        motions: record GroundMotions (their scaled samples are stored).
        name: suite name (default: the file stem).
        description: one line.
        scale: default scaling rule table, e.g. ``{"method": "factor", "value": 1.0}``.
        meta: extra top-level keys (strings, numbers).

    Returns:
        The manifest path. Load it back with :func:`load_suite`.
    """
    path = Path(path)
    if path.suffix.lower() != ".toml":
        path = path.with_suffix(".toml")
    path.parent.mkdir(parents=True, exist_ok=True)
    name = name or path.stem
    arrays = {}
    lines = [f"name = {_toml_value(name)}", f"description = {_toml_value(description)}"]
    for k, v in (meta or {}).items():
        if _plain(v):
            lines.append(f"{k} = {_toml_value(v)}")
    lines.append("")
    if scale:
        lines.append("[scale]")
        lines += [f"{k} = {_toml_value(v)}" for k, v in scale.items()]
        lines.append("")
    for i, motion in enumerate(motions, start=1):
        if not motion.is_record:
            raise MotionError("only sampled records can be saved in a suite", key="motions",
                              expected="record motions", found=motion.name)
        key = f"record_{i:03d}"
        arrays[key] = np.asarray(motion.params[0] * motion.samples, dtype=np.float64)
        record_id = motion.meta.get("id") if str(motion.meta.get("id", "")).startswith(f"{name}/") else None
        lines += ["[[records]]", f"id = {_toml_value(record_id or f'{name}/{i:03d}')}",
                  f"npz = {_toml_value(path.with_suffix('.npz').name)}", f"key = {_toml_value(key)}",
                  f"dt = {_toml_value(motion.dt)}", 'units = "m/s^2"']
        for k, v in motion.meta.items():
            if k in ("id", "npz", "key", "file", "builtin", "dt", "units", "npts", "scale", "source_file") \
                    or not _plain(v):
                continue
            lines.append(f"{k} = {_toml_value(v)}")
        lines.append("")
    np.savez_compressed(path.with_suffix(".npz"), **arrays)
    path.write_text("\n".join(lines))
    _npz.cache_clear()
    return path


def list_records(suite: str | None = None, *, gravity: float = 9.81, records_dir=None) -> list[dict]:
    """Records as ``records list --json`` entries: ``id, event, year, station, rsn, component, dt,
    npts, pga`` (pga in m/s² with g = ``gravity``).

    Without ``suite``: all built-in records (from the metadata table, no samples loaded). With a
    suite name or path: its records in manifest order; records that cannot be found carry
    ``dt``/``npts``/``pga`` = None and ``missing`` = the reason.
    """
    if suite is None:
        return [record_summary(rid, row=builtin_info(rid), gravity=gravity) for rid in builtin_ids()]
    loaded = load_suite(suite, gravity=gravity, records_dir=records_dir, key="suite")
    out = []
    for entry in loaded.entries:
        if entry.motion is not None:
            item = record_summary(entry.id, motion=entry.motion)
        else:
            meta = entry.meta
            item = {"id": entry.id, "event": meta.get("event"), "year": meta.get("year"),
                    "station": meta.get("station"), "rsn": meta.get("rsn"),
                    "component": meta.get("component"), "dt": None, "npts": None, "pga": None,
                    "missing": entry.reason}
        if entry.meta.get("label"):
            item["label"] = entry.meta["label"]
        out.append(item)
    return out
