"""Built-in record sets and record ids (CONTRACT §2).

Record ids understood by :func:`load_record`:

* ``p695-ff/<n><c>`` (far-field, n = 1…22), ``p695-nfp/<n><c>`` (near-field pulse, n = 1…14),
  ``p695-nfnp/<n><c>`` (near-field no-pulse, n = 15…28), c = a | b: the FEMA P695 records
  (FEMA 2009, Appendix A) shipped in ``ground_motions/p695_*.npz`` (as recorded, in g).
* ``p695-…/<n>@<azimuth>``: the horizontal component of FEMA record n rotated to the given
  azimuth [degrees clockwise from north], exact 2-D rotation of the two orthogonal components
  (e.g. ``p695-nfp/6@0`` is Erzincan 1992 NS, recovering the as-recorded NGA-West1 component).
* ``rsn:<RSN>:<component>``: a PEER NGA record found in the user's records folder
  (``records_dir``, files named ``RSN<RSN>_…<component>.AT2`` as PEER delivers them, or with the
  component on line 2 of the AT2 header), else a built-in record with the same RSN and component.
* ``file:<path>`` or a plain path: any file :func:`~rockdesign.motions.records.read_record_file`
  reads.

Loaded arrays are cached: each npz file is read once per process.
"""
from __future__ import annotations

import csv
import difflib
import math
import re
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import RecordError
from ..paths import ground_motions_dir, user_path
from .motion import GroundMotion, record_motion
from .records import read_record_file

BUILTIN_SETS = {
    "p695-ff": ("p695-farfield", range(1, 23)),
    "p695-nfp": ("p695-nearfield-pulse", range(1, 15)),
    "p695-nfnp": ("p695-nearfield-nopulse", range(15, 29)),
}
_BUILTIN_ID = re.compile(r"^(p695-(?:ff|nfp|nfnp))/(\d+)([ab])$", re.I)
_ROTATED_ID = re.compile(r"^(p695-(?:ff|nfp|nfnp))/(\d+)@([-+]?\d+(?:\.\d*)?)$", re.I)
_RSN_ID = re.compile(r"^rsn:(\d+):(.+)$", re.I)
_RECORD_SUFFIXES = {".at2", ".txt", ".csv", ".dat", ".acc", ".tsv"}
ID_FORMS = ("p695-ff/<1..22><a|b>, p695-nfp/<1..14><a|b>, p695-nfnp/<15..28><a|b>, "
            "p695-<set>/<n>@<azimuth deg>, rsn:<RSN>:<component>, file:<path>")


@lru_cache(maxsize=1)
def _catalogue() -> dict[str, dict]:
    """Rows of ``ground_motions/p695_records.csv`` keyed by record id (types converted)."""
    path = ground_motions_dir() / "p695_records.csv"
    if not path.is_file():
        raise RecordError("built-in record table missing", file=str(path),
                          expected="p695_records.csv (run scripts/convert_fema_p695.py)",
                          found="no such file")
    rows = {}
    with open(path, newline="") as fh:
        for row in csv.DictReader(fh):
            for key in ("record", "year", "rsn", "npts"):
                row[key] = int(row[key])
            for key in ("magnitude", "distance_rrup_km", "distance_rjb_km", "vs30_m_s", "dt",
                        "pga_g", "normalization_factor"):
                row[key] = float(row[key])
            rows[row["id"]] = row
    return rows


@lru_cache(maxsize=None)
def _npz_arrays(file_name: str) -> dict[str, np.ndarray]:
    """All arrays of one built-in npz file (read once per process; float32, in g)."""
    path = ground_motions_dir() / file_name
    try:
        with np.load(path) as data:
            return {key: data[key] for key in data.files}
    except OSError as exc:
        raise RecordError(f"cannot read built-in records ({exc})", file=str(path)) from None


def builtin_ids() -> list[str]:
    """All built-in record ids in table order (far-field, near-field pulse, no-pulse)."""
    return list(_catalogue())


def builtin_info(record_id: str) -> dict:
    """Metadata row of a built-in record (event, year, station, rsn, component_name, dt, npts, pga_g…)."""
    row = _catalogue().get(record_id.lower())
    if row is None:
        raise _unknown_id(record_id)
    return dict(row)


def _short_component(component_name: str) -> str:
    return component_name.split("/")[-1]


def _builtin_meta(row: dict, gravity: float) -> dict:
    return {
        "id": row["id"], "set": row["set"], "record": row["record"], "fema_component": row["component"],
        "event": row["event"], "year": row["year"], "station": row["station"], "rsn": row["rsn"],
        "component": _short_component(row["component_name"]), "component_name": row["component_name"],
        "magnitude": row["magnitude"], "distance_rrup_km": row["distance_rrup_km"],
        "distance_rjb_km": row["distance_rjb_km"], "vs30_m_s": row["vs30_m_s"],
        "units": "g", "gravity": gravity, "source": row["source"], "credit": row["credit"],
        "normalization_factor": row["normalization_factor"],
    }


def _load_builtin(record_id: str, gravity: float) -> GroundMotion:
    row = builtin_info(record_id)
    samples_g = _npz_arrays(row["file"])[row["key"]]
    accel = samples_g.astype(np.float64) * gravity
    return record_motion(row["id"], accel, row["dt"], meta=_builtin_meta(row, gravity))


def component_azimuth(component_name: str) -> float | None:
    """Azimuth [deg clockwise from north] of a component name (``ERZ_032`` → 32, ``CHY101-E`` → 90)."""
    short = _short_component(component_name).upper()
    m = re.search(r"(?<![0-9])(\d{3})$", short)
    if m:
        return float(m.group(1)) % 360.0
    m = re.search(r"[-_](N|E|S|W|NS|EW)$", short)
    if m:
        return {"N": 0.0, "NS": 0.0, "E": 90.0, "EW": 90.0, "S": 180.0, "W": 270.0}[m.group(1)]
    return None


def _load_rotated(prefix: str, number: int, azimuth: float, gravity: float) -> GroundMotion:
    """Component at ``azimuth`` from the two orthogonal FEMA components: a = a1 cos(θ−θ1) + a2 cos(θ−θ2)."""
    text_id = f"{prefix}/{number}@{azimuth:g}"
    rows = [builtin_info(f"{prefix}/{number}{c}") for c in "ab"]
    azimuths = [component_azimuth(r["component_name"]) for r in rows]
    if None in azimuths:
        raise RecordError("cannot rotate this record: component azimuths unknown", key="record id",
                          expected="components named by azimuth (e.g. ERZ_032, ERZ_122)",
                          found=f"{rows[0]['component_name']}, {rows[1]['component_name']}")
    gap = (azimuths[1] - azimuths[0]) % 180.0
    if abs(gap - 90.0) > 1e-9:
        raise RecordError("cannot rotate this record: components not orthogonal", key="record id",
                          expected="azimuths 90° apart", found=f"{azimuths[0]:g}°, {azimuths[1]:g}°")
    if rows[0]["dt"] != rows[1]["dt"] or rows[0]["npts"] != rows[1]["npts"]:
        raise RecordError("cannot rotate this record: components of different length", key="record id",
                          expected="equal dt and npts", found=f"{rows[0]['npts']} and {rows[1]['npts']} samples")
    a1 = _npz_arrays(rows[0]["file"])[rows[0]["key"]].astype(np.float64)
    a2 = _npz_arrays(rows[1]["file"])[rows[1]["key"]].astype(np.float64)
    c1 = math.cos(math.radians(azimuth - azimuths[0]))
    c2 = math.cos(math.radians(azimuth - azimuths[1]))
    accel = (c1 * a1 + c2 * a2) * gravity
    meta = _builtin_meta(rows[0], gravity)
    meta.update(id=text_id, fema_component=None, component=f"{azimuth:g} deg",
                component_name=f"rotated to {azimuth:g} deg from {rows[0]['component_name']} "
                               f"({azimuths[0]:g} deg) and {rows[1]['component_name']} ({azimuths[1]:g} deg)",
                source=f"exact rotation of {rows[0]['id']} and {rows[1]['id']}")
    return record_motion(text_id, accel, rows[0]["dt"], meta=meta)


def builtin_for_rsn(rsn: int, component: str) -> str | None:
    """Id of the built-in record with this RSN and component name (``270`` matches ``YER270``), if any."""
    for record_id, row in _catalogue().items():
        if row["rsn"] == int(rsn) and component_matches(_short_component(row["component_name"]), component):
            return record_id
    return None


def component_matches(name: str, component: str) -> bool:
    """Whether a file stem or component label ``name`` ends with the component token ``component``.

    ``YER270`` and ``RSN900_LANDERS_YER270`` match ``270``; ``ELC180`` does not match ``80``;
    ``ERZ-NS`` matches ``NS``.
    """
    name, token = name.strip().upper(), component.strip().upper()
    if not token or not name.endswith(token):
        return False
    if len(name) == len(token):
        return True
    before = name[-len(token) - 1]
    if not before.isalnum():
        return True
    return token[0].isdigit() and before.isalpha()


@lru_cache(maxsize=16)
def _records_dir_index(folder: str, mtime: float) -> tuple[tuple[int, str, str], ...]:
    """(rsn, path, header component) of every AT2 file below ``folder`` whose name carries RSN<n>."""
    from .records import _RSN_IN_NAME, _parse_station_line
    entries = []
    for path in sorted(Path(folder).rglob("*")):
        if not path.is_file() or path.suffix.lower() != ".at2":
            continue
        m = _RSN_IN_NAME.search(path.name)
        if not m:
            continue
        try:
            with open(path, errors="replace") as fh:
                head = [fh.readline() for _ in range(2)]
            component = _parse_station_line(head[1]).get("component") or ""
        except OSError:
            component = ""
        entries.append((int(m.group(1)), str(path), component))
    return tuple(entries)


def find_record_file(records_dir, rsn: int, component: str) -> Path | None:
    """The AT2 file of record RSN/component in ``records_dir`` (searched recursively), or None.

    A file matches if its name carries ``RSN<rsn>`` and its stem ends with the component
    (``RSN900_LANDERS_YER270.AT2``) or line 2 of its header names that component.

    Raises:
        RecordError: if the folder does not exist or several files match.
    """
    folder = user_path(records_dir, "records_dir", error=RecordError)
    if not folder.is_dir():
        raise RecordError("records folder not found", file=str(folder), key="records_dir",
                          expected="an existing folder of PEER *.AT2 files", found="no such folder")
    index = _records_dir_index(str(folder.resolve()), folder.stat().st_mtime)
    by_rsn = [(Path(p), comp) for r, p, comp in index if r == int(rsn)]
    by_name = [p for p, _ in by_rsn if component_matches(p.stem, component)]
    matches = by_name or [p for p, comp in by_rsn if comp and component_matches(comp, component)]
    if len(matches) > 1:
        raise RecordError(f"several files match RSN {rsn} component {component}", file=str(folder),
                          key="records_dir", expected="exactly one file",
                          found=", ".join(p.name for p in matches))
    return matches[0] if matches else None


def _unknown_id(record_id: str) -> RecordError:
    close = difflib.get_close_matches(record_id.lower(), builtin_ids(), n=3, cutoff=0.6)
    return RecordError("unknown record id", key="record id", expected=ID_FORMS, found=repr(record_id),
                       hint=f"did you mean {', '.join(close)}?" if close else None)


def load_record(record_id: str, *, gravity: float = 9.81, records_dir=None) -> GroundMotion:
    """The GroundMotion (m/s², s) of a record id (module docstring lists the forms).

    Args:
        record_id: built-in id, rotated built-in id, ``rsn:<RSN>:<component>``, ``file:<path>``
            or a path.
        gravity: g [m/s²] converting records stored in g (the project's gravity).
        records_dir: folder of the user's PEER AT2 files (for ``rsn:`` ids).

    Raises:
        RecordError: unknown id, record not found, unreadable file.
    """
    text = str(record_id).strip()
    m = _BUILTIN_ID.match(text)
    if m:
        return _load_builtin(text.lower(), gravity)
    m = _ROTATED_ID.match(text)
    if m:
        return _load_rotated(m.group(1).lower(), int(m.group(2)), float(m.group(3)), gravity)
    m = _RSN_ID.match(text)
    if m:
        rsn, component = int(m.group(1)), m.group(2).strip()
        if records_dir is not None:
            path = find_record_file(records_dir, rsn, component)
            if path is not None:
                motion = read_record_file(path, gravity=gravity, name=text)
                motion.meta.update(id=text, resolved_from=f"records dir: {path}")
                return motion
        builtin = builtin_for_rsn(rsn, component)
        if builtin is not None:
            motion = _load_builtin(builtin, gravity)
            motion.meta.update(resolved_from=f"built-in {builtin}")
            return motion
        where = f"in {records_dir}" if records_dir is not None else "(no records dir given)"
        raise RecordError(f"record RSN {rsn} component {component} not found {where} nor among the "
                          "built-in records", key="record id",
                          expected=f"a file RSN{rsn}_*{component}.AT2 in the records dir",
                          found="no matching file", hint="download it from the PEER NGA database")
    if text.lower().startswith("file:"):
        path = user_path(text[5:].strip(), "record id", error=RecordError)
        motion = read_record_file(path, gravity=gravity, name=text)
        motion.meta.setdefault("id", text)
        return motion
    path = user_path(text, "record id", error=RecordError)
    if path.is_file() or path.suffix.lower() in _RECORD_SUFFIXES or "/" in text and not text.lower().startswith("p695"):
        motion = read_record_file(path, gravity=gravity, name=text)
        motion.meta.setdefault("id", text)
        return motion
    raise _unknown_id(text)


def record_summary(record_id: str, motion: GroundMotion | None = None, row: dict | None = None,
                   gravity: float = 9.81) -> dict:
    """One ``records list --json`` entry (CONTRACT §3; pga in m/s²)."""
    if motion is not None:
        meta = motion.meta
        return {"id": record_id, "event": meta.get("event"), "year": meta.get("year"),
                "station": meta.get("station"), "rsn": meta.get("rsn"),
                "component": meta.get("component"), "dt": motion.dt, "npts": int(motion.samples.size),
                "pga": motion.pga}
    assert row is not None
    return {"id": record_id, "event": row["event"], "year": row["year"], "station": row["station"],
            "rsn": row["rsn"], "component": _short_component(row["component_name"]), "dt": row["dt"],
            "npts": row["npts"], "pga": row["pga_g"] * gravity}
