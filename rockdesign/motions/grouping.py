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
