"""Ground motions, not components: which records of a suite share one recording station and event.

The two horizontal components of one station's recording of one earthquake share source, path and
site; they are not independent trials (FEMA P695 far-field: 44 components, 22 ground motions, 14
earthquakes).  ASCE 7-22 §16.2 and §16.4.1.1 count *ground motions* (pairs), and so does every
acceptance rule of ``rockdesign check`` (SPEC §14).

A record's ground motion is, in this order:

1. the suite manifest's ``ground_motion`` key of the record (any string or integer; records that share
   it are one ground motion) — the way to group a user's own AT2 files;
2. the record number of a built-in FEMA P695 record (``p695-ff/11a`` and ``p695-ff/11b`` are
   ground motion ``p695-ff/11``; the rotated near-field components ``p695-nfp/6@90`` likewise);
3. the PEER record sequence number ``rsn`` (one RSN is one station's recording of one earthquake; its
   components share it);
4. otherwise the record itself (a record without station information is its own ground motion).
"""
from __future__ import annotations

import re

GROUND_MOTION_KEY = "ground_motion"
"""The optional key of a suite manifest's ``[[records]]`` entry that groups records into ground motions."""

_BUILTIN = re.compile(r"^(p695-(?:ff|nfp|nfnp))/(\d+)(?:[ab]|@.*)?$", re.IGNORECASE)


def ground_motion_id(record_id: str, meta: dict | None = None) -> str:
    """The ground motion (station and event) a record belongs to (rules in the module docstring)."""
    meta = meta or {}
    explicit = meta.get(GROUND_MOTION_KEY)
    if explicit is not None and str(explicit).strip():
        return str(explicit).strip()
    for text in (record_id, meta.get("builtin"), meta.get("id")):
        m = _BUILTIN.match(str(text or ""))
        if m:
            return f"{m.group(1).lower()}/{int(m.group(2))}"
    rsn = meta.get("rsn")
    if isinstance(rsn, int) and not isinstance(rsn, bool):
        return f"RSN {rsn}"
    return str(record_id)


def earthquake_id(meta: dict | None) -> str | None:
    """The earthquake of a record ("Northridge 1994") from its ``event`` and ``year``; None when unknown."""
    meta = meta or {}
    event = meta.get("event")
    if not event:
        return None
    year = meta.get("year")
    return f"{event} {year}" if year is not None else str(event)


def count_ground_motions(ground_motions) -> int:
    """The number of distinct ground motions among per-record ground-motion ids."""
    return len(set(ground_motions))


def station_of(meta: dict | None) -> tuple | None:
    """The station recording a record comes from: ``("rsn", n)`` when its PEER RSN is known, else
    ``("name", event, year, station)`` (lower case) when its event and station are; None when neither is."""
    meta = meta or {}
    rsn = meta.get("rsn")
    if isinstance(rsn, int) and not isinstance(rsn, bool):
        return ("rsn", int(rsn))
    event, station = meta.get("event"), meta.get("station")
    if event and station:
        return ("name", str(event).strip().lower(), meta.get("year"), str(station).strip().lower())
    return None


def _same_station(a: tuple | None, b: tuple | None) -> bool:
    return a is not None and b is not None and a[0] == b[0] and a == b


def _station_words(meta: dict) -> str:
    parts = [str(meta[k]) for k in ("event", "year", "station") if meta.get(k)]
    if isinstance(meta.get("rsn"), int):
        parts.append(f"RSN {meta['rsn']}")
    return ", ".join(parts) or "station unknown"


def inconsistent_ground_motions(records) -> tuple[str, tuple, tuple] | None:
    """The first contradiction between the ground motions of a suite's records and their stations, or None.

    Args:
        records: ``(record id, meta, station meta, …)`` per record: ``meta`` as :func:`ground_motion_id` reads it
            for the acceptance rule, ``station meta`` the record's own metadata too (RSN, event, year, station).

    Returns:
        ("stations", a, b): two records of one ground motion that are two stations' recordings (a "pair" of
        Capitola and Gilroy #3); ("split", a, b): two components of one station given as two ground motions
        (counted twice by every statement over ground motions); a and b are items of ``records``.
    """
    known = [(record, ground_motion_id(record[0], record[1]), station_of(record[2])) for record in records]
    for i, (a, gm_a, st_a) in enumerate(known):
        for b, gm_b, st_b in known[i + 1:]:
            if st_a is None or st_b is None or st_a[0] != st_b[0]:
                continue
            if gm_a == gm_b and st_a != st_b:
                return "stations", a, b
            if gm_a != gm_b and st_a == st_b:
                return "split", a, b
    return None


def refuse_inconsistent_ground_motions(records, *, file: str | None, key: str = "excitation") -> None:
    """Refuse a suite whose ground motions contradict its records' stations (SPEC §14, §16: a ground motion is
    the two horizontal components of one station's recording of one earthquake).

    Args:
        records: ``(record id, meta, station meta, where, file)`` per record (:func:`inconsistent_ground_motions`):
            ``where`` says where it was given ("suite mine, records[3]", "excitation.records[1]"), ``file`` the
            file that lists it.
        file: the project file (named unless both records come from one manifest).
        key: the project key of the suite.

    Raises:
        ProjectError: naming both records, where each was given, their ground motions and stations.
    """
    from ..errors import ProjectError
    found = inconsistent_ground_motions(records)
    if found is None:
        return
    what, (id_a, meta_a, station_a, where_a, file_a), (id_b, meta_b, station_b, where_b, file_b) = found
    where = file_a if file_a and file_a == file_b else file
    shown_key = key
    if where != file and where_b.rpartition(", ")[2].startswith("records["):
        shown_key = where_b.rpartition(", ")[2] + f".{GROUND_MOTION_KEY}"     # the manifest's own key
    gm_a, gm_b = ground_motion_id(id_a, meta_a), ground_motion_id(id_b, meta_b)
    if what == "stations":
        raise ProjectError(
            "one ground motion made of two stations' recordings", file=where, key=shown_key,
            expected="the two horizontal components of one station's recording of one earthquake per ground motion "
                     "(ASCE 7-22 §16.2.2; in a suite manifest, one ground_motion for those two only)",
            found=f"ground motion '{gm_a}': '{id_a}' ({where_a}; {_station_words(station_a)}) and '{id_b}' "
                  f"({where_b}; {_station_words(station_b)})")
    raise ProjectError(
        "two components of one station given as separate ground motions", file=where, key=shown_key,
        expected="one ground motion for the components of one station's recording (ASCE 7-22 §16.2.2 and "
                 "§16.4.1.1 count ground motions, not components; in a suite manifest, one ground_motion for both)",
        found=f"'{id_a}' ({where_a}) as ground motion '{gm_a}' and '{id_b}' ({where_b}) as '{gm_b}': both "
              f"{_station_words(station_a)}")
