"""Records by identity: the same recording under two names is one ground motion (SPEC §14).

A suite lists records by names — built-in ids, ``rsn:`` ids, file paths, manifest entries — but a
ground-motion component is a *recording*: one station's record of one earthquake along one axis.  Two
entries of a suite are the same recording when any of these hold (checked in this order):

1. **the same id** (``p695-ff/11a`` twice);
2. **the same source**: the same file after resolving the path (``rec/r01.AT2`` and ``rec/./r01.AT2``,
   a symbolic link and its target), or the same built-in record (``rsn:900:270`` resolves to the
   built-in ``p695-ff/11a``);
3. **the same station recording**: the same PEER record sequence number (RSN: one station's recording
   of one earthquake) and the same component axis — azimuths equal modulo 180° (``YER270`` in the
   built-in set and ``270`` in the header of ``RSN900_LANDERS_YER270.AT2``; NGA-West1 and West2
   processings of one recording alike), or equal labels where no azimuth can be read;
4. **the same samples**: equal time step and length and max |a₁/PGA₁ − s·a₂/PGA₂| ≤ 1e-4 with s = ±1 —
   the same accelerogram up to its units, a scale factor or its polarity.  1e-4 of the PGA is a
   thousand times the rounding of stored records (float32, 7-digit AT2 text: ~1e-7) and a thousand times
   below the difference of two distinct recordings (of the order of their PGA);
5. **the same samples shifted in time**: equal time step and a normalised cross-correlation
   max_k |Σ a₁[n] a₂[n+k]| / (‖a₁‖ ‖a₂‖) ≥ :data:`SHIFT_CORRELATION` (:func:`scipy.signal.correlate`) —
   a copy delayed by 2 s under another name, with or without the first or last seconds cut.  Measured: such
   copies of the built-in records correlate at ≥ 0.998 (2 s cut at either end); the 2,046 pairs of distinct
   built-in records sharing a time step at most 0.52 (the two components of p695-ff/7).

:func:`refuse_repeated_recordings` raises a :class:`~rockdesign.errors.ProjectError` naming both entries
(where each was given) and the file: counting one recording twice would count one trial twice in every
statement over ground motions (SPEC §14, ASCE 7-22 §16.2.2, §16.4.1.1).  The two horizontal components of
one station are *different* recordings of one ground motion (:mod:`rockdesign.motions.grouping`).
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ProjectError

CONTENT_TOLERANCE = 1e-4
"""Two accelerograms are one when they differ by at most this fraction of their PGA at every sample."""
SHIFT_CORRELATION = 0.9
"""Two accelerograms on one time step are one, shifted, when their normalised cross-correlation reaches this
(copies ≥ 0.998, distinct recordings ≤ 0.52: module docstring)."""
ENERGY_GATE = 0.5
"""Cross-correlation is computed only for records whose Σa²/PGA² (a shift leaves it as it is) differ by less
than this fraction: a correlation of 0.9 needs most of each record's energy in the other."""


@dataclass(frozen=True, eq=False)
class Entry:
    """One record of a suite as the user gave it.

    Attributes:
        record_id: its id.
        where: where it was given ("suite p695-farfield", "excitation.records[2]").
        motion: the loaded GroundMotion (None: not found).
        meta: the entry's metadata.
        file: the file that lists it (a suite manifest or the project file), for messages.
    """

    record_id: str
    where: str
    motion: object | None
    meta: dict
    file: str | None = None


def _builtin(entry: Entry) -> str | None:
    meta = entry.motion.meta if entry.motion is not None else {}
    name = entry.meta.get("builtin") or meta.get("builtin")
    if not name and meta.get("set") and meta.get("id"):
        name = meta["id"]
    return str(name).lower() if name else None


def _source(entry: Entry) -> str | None:
    """The resolved file a record was read from, or the built-in record it is."""
    if entry.motion is None:
        return None
    builtin = _builtin(entry)
    if builtin:
        return f"built-in {builtin}"
    meta = entry.motion.meta
    if meta.get("format") and meta.get("source_file"):     # read_record_file (not an npz array)
        try:
            return f"file {Path(meta['source_file']).resolve()}"
        except OSError:
            return f"file {meta['source_file']}"
    return None


def _component_axis(text) -> tuple[str, object] | None:
    """('azimuth', degrees mod 180) or ('label', upper-case text) of a component name, or None."""
    from .library import component_azimuth
    if text is None:
        return None
    name = str(text).strip()
    if not name:
        return None
    if "@" in name:
        try:
            return ("azimuth", round(float(name.rsplit("@", 1)[1]) % 180.0, 3))
        except ValueError:
            pass
    degrees = name.upper().removesuffix("DEG").strip()
    try:
        return ("azimuth", round(float(degrees) % 180.0, 3))
    except ValueError:
        pass
    az = component_azimuth(name)
    trailing = re.search(r"(\d{3})$", name)
    if az is None and trailing:                 # NGA names: station code + 3-digit azimuth (E11230, G03000)
        az = float(trailing.group(1))
    if az is None and name.upper() in ("N", "S", "E", "W", "NS", "SN", "EW", "WE"):
        az = 0.0 if name.upper() in ("N", "S", "NS", "SN") else 90.0
    if az is not None:
        return ("azimuth", round(az % 180.0, 3))
    return ("label", name.upper())


def _recording(entry: Entry) -> tuple[int, tuple[str, object]] | None:
    """(RSN, component axis) of a record, when both are known."""
    if entry.motion is None:
        return None
    meta = dict(entry.motion.meta)
    rsn = entry.meta.get("rsn", meta.get("rsn"))
    if isinstance(rsn, bool) or not isinstance(rsn, (int, np.integer)):
        return None
    builtin = _builtin(entry)
    axis = _component_axis(builtin) if builtin and "@" in builtin else None
    for text in (meta.get("component_name"), meta.get("component"), entry.meta.get("component")):
        if axis is not None:
            break
        axis = _component_axis(text)
    if axis is None:
        return None
    return int(rsn), axis


def _same_recording(a, b) -> bool:
    if a is None or b is None or a[0] != b[0]:
        return False
    (kind_a, value_a), (kind_b, value_b) = a[1], b[1]
    if kind_a == kind_b == "azimuth":
        gap = abs(value_a - value_b) % 180.0
        return min(gap, 180.0 - gap) < 0.5
    if kind_a == kind_b == "label":
        from .library import component_matches
        return component_matches(value_a, value_b) or component_matches(value_b, value_a)
    return False


def _normalised(entry: Entry) -> tuple[tuple[float, int, int], np.ndarray] | None:
    """((dt, length without trailing zeros, index of the peak), samples/PGA) of a record, or None."""
    motion = entry.motion
    if motion is None or not motion.is_record or motion.samples.size < 2:
        return None
    a = np.asarray(motion.samples, dtype=float)
    nonzero = np.flatnonzero(a)
    if nonzero.size == 0:
        return None
    a = a[: nonzero[-1] + 1]
    peak = int(np.argmax(np.abs(a)))
    return (float(f"{motion.dt:.9g}"), a.size, peak), a / abs(a[peak])


def _describe(entry: Entry) -> str:
    where = entry.where
    source = _source(entry)
    if source and entry.record_id.lower().removeprefix("file:") not in source.lower():
        where += f", {source}"
    return f"'{entry.record_id}' ({where})"


def _label(entry: Entry) -> str:
    meta = dict(entry.motion.meta) if entry.motion is not None else {}
    meta.update({k: v for k, v in entry.meta.items() if v is not None})
    parts = [str(meta[k]) for k in ("event", "year", "station") if meta.get(k)]
    component = meta.get("component_name") or meta.get("component")
    if component:
        parts.append(f"component {component}")
    return ", ".join(parts)


def repeated_recording(entries: list[Entry]) -> tuple[Entry, Entry, str] | None:
    """The first two entries that are one recording (module docstring), with the reason; else None."""
    first: dict[tuple, Entry] = {}
    for entry in entries:
        keys = [("id", entry.record_id.strip().lower(), "the same record id")]
        source = _source(entry)
        if source:
            keys.append(("source", source, f"the same {source.split(' ', 1)[0]} ({source.split(' ', 1)[1]})"))
        for kind, value, why in keys:
            seen = first.get((kind, value))
            if seen is not None:
                return seen, entry, why
            first[(kind, value)] = entry
    recordings = [(e, _recording(e)) for e in entries]
    for i, (a, ra) in enumerate(recordings):
        for b, rb in recordings[i + 1:]:
            if _same_recording(ra, rb):
                return a, b, f"the same station recording: RSN {ra[0]}, the same component axis"
    buckets: dict[tuple, list[tuple[Entry, np.ndarray]]] = {}
    for entry in entries:
        found = _normalised(entry)
        if found is None:
            continue
        key, shape = found
        for other, other_shape in buckets.get(key, []):
            diff = min(float(np.max(np.abs(shape - other_shape))), float(np.max(np.abs(shape + other_shape))))
            if diff <= CONTENT_TOLERANCE:
                return other, entry, (f"the same samples (time step, length and accelerations within "
                                      f"{CONTENT_TOLERANCE:g} of the PGA, up to a factor)")
        buckets.setdefault(key, []).append((entry, shape))
    return shifted_copy(entries)


def _trimmed(entry: Entry) -> tuple[float, np.ndarray] | None:
    """(time step [s], samples without leading and trailing zeros, scaled to unit norm) of a record, or None."""
    motion = entry.motion
    if motion is None or not motion.is_record or motion.samples.size < 2:
        return None
    a = np.asarray(motion.samples, dtype=float)
    nonzero = np.flatnonzero(a)
    if nonzero.size < 2:
        return None
    a = a[nonzero[0]: nonzero[-1] + 1]
    return float(f"{motion.dt:.9g}"), a / np.linalg.norm(a)


def shifted_copy(entries: list[Entry]) -> tuple[Entry, Entry, str] | None:
    """The first two entries that are one accelerogram shifted in time (rule 5 of the module docstring), with
    the reason; else None."""
    from scipy import signal
    by_step: dict[float, list[tuple[Entry, np.ndarray, float]]] = {}
    for entry in entries:
        found = _trimmed(entry)
        if found is None:
            continue
        dt, unit = found
        effective = 1.0 / float(np.max(unit ** 2))          # Σa²/PGA²: samples carrying the energy
        for other, other_unit, other_effective in by_step.get(dt, []):
            if abs(effective - other_effective) > ENERGY_GATE * max(effective, other_effective):
                continue
            c = signal.correlate(other_unit, unit, mode="full", method="fft")
            k = int(np.argmax(np.abs(c)))
            rho = float(abs(c[k]))
            if rho >= SHIFT_CORRELATION:
                shift = (unit.size - 1 - k) * dt + _start(entry) - _start(other)
                return other, entry, (f"the same samples shifted by {shift:.4g} s (normalised cross-correlation "
                                      f"{rho:.4f} ≥ {SHIFT_CORRELATION:g}; distinct recordings stay below 0.52)")
        by_step.setdefault(dt, []).append((entry, unit, effective))
    return None


def _start(entry: Entry) -> float:
    """Time [s] of a record's first non-zero sample."""
    nonzero = np.flatnonzero(np.asarray(entry.motion.samples))
    return float(nonzero[0]) * float(entry.motion.dt) if nonzero.size else 0.0


def refuse_repeated_recordings(entries: list[Entry], *, file: str | None = None, key: str = "excitation") -> None:
    """Refuse a suite that lists one recording twice (SPEC §14; module docstring).

    Args:
        entries: every record of the suite as given (found or not), in order.
        file: the project file (named in the message unless both entries come from one manifest).
        key: the project key of the suite.

    Raises:
        ProjectError: naming both entries, where each was given, why they are one recording, and the file.
    """
    found = repeated_recording(entries)
    if found is None:
        return
    a, b, why = found
    where = a.file if a.file and a.file == b.file else file
    label = _label(a) or _label(b)
    raise ProjectError(
        "the same ground motion twice in the suite", file=where, key=key,
        expected="each recording once (a recording is one station's component, whatever names it; "
                 "list it once)",
        found=f"{_describe(a)} and {_describe(b)} are one recording: {why}" + (f" — {label}" if label else ""))

