"""Read ground-motion record files into GroundMotion objects (accelerations in m/s²).

Formats:

* **PEER NGA AT2** (NGA-West1 and West2): 4 header lines — title; ``event, date, station,
  component``; ``ACCELERATION TIME SERIES IN UNITS OF G``; ``NPTS=  2200, DT=   .0200 SEC`` (or the
  older ``2200  0.0200  NPTS, DT``) — then the samples, several per line.
* **one column**: one acceleration per line; dt from the ``dt`` argument or a header comment
  such as ``# npts=3995 dt=0.01`` / ``# dt: 0.01 s``.
* **two columns** ``t, a`` (comma, semicolon, tab or blank separated): dt from the time column,
  which must be uniform.

Units of the generic files come from the ``units`` argument, a comment (``# units: g``) or the
column header (``time,acc (g)``). ``g`` means the project's gravity (CONTRACT §1). Anything that
cannot be read raises :class:`~rockdesign.errors.RecordError` naming the file and the line.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from ..errors import RecordError
from ..paths import user_path
from ..units import QuantityParseError, parse_quantity
from .motion import GroundMotion, record_motion

_UNIT_FACTORS_OF_G = {"g": 1.0, "gs": 1.0, "g0": 1.0, "g's": 1.0}
_UNIT_FACTORS_SI = {
    "m/s^2": 1.0, "m/s2": 1.0, "m/s/s": 1.0, "m/sec/sec": 1.0, "m/sec^2": 1.0, "m/sec2": 1.0,
    "mps2": 1.0, "m/s**2": 1.0,
    "cm/s^2": 0.01, "cm/s2": 0.01, "cm/s/s": 0.01, "cm/sec/sec": 0.01, "cm/sec^2": 0.01,
    "cm/sec2": 0.01, "cm/s**2": 0.01, "gal": 0.01, "gals": 0.01, "cmps2": 0.01,
    "mm/s^2": 0.001, "mm/s2": 0.001, "mm/s/s": 0.001,
    "in/s^2": 0.0254, "in/s2": 0.0254, "in/s/s": 0.0254, "in/sec/sec": 0.0254,
    "ft/s^2": 0.3048, "ft/s2": 0.3048, "ft/s/s": 0.3048, "ft/sec/sec": 0.3048,
}
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?"
_NUMBER_RE = re.compile(_NUMBER)
_NPTS_DT = [
    re.compile(rf"NPTS\s*[=:]\s*(\d+)\s*[,;]?\s*DT\s*[=:]\s*({_NUMBER})", re.I),
    re.compile(rf"^\s*(\d+)\s+({_NUMBER})\s+NPTS\s*,?\s*DT", re.I),
    re.compile(rf"DT\s*[=:]\s*({_NUMBER})\s*(?:SEC|S)?\s*[,;]?\s*NPTS\s*[=:]\s*(\d+)", re.I),
]
_UNITS_OF = re.compile(r"UNITS?\s+OF\s+([A-Za-z0-9/^*.\-]+(?:\s*/\s*[A-Za-z0-9^*.]+)*)", re.I)
_DECLARATION = re.compile(r"^\s*(dt|npts|units?|unit)\s*[=:]\s*(\S+(?:\s+s(?:ec)?)?)\s*$", re.I)
_KEY_VALUE = re.compile(r"(dt|npts|units?)\s*=\s*(\S+)", re.I)
_HEADER_UNITS = re.compile(r"[\(\[]\s*([^\)\]]+?)\s*[\)\]]")
_DATE = re.compile(r"(\d{1,2})/(\d{1,2})/(\d{2,4})")
_RSN_IN_NAME = re.compile(r"(?:^|[_\-.])RSN(\d+)(?=[_\-.])", re.I)


def acceleration_factor(units: str, gravity: float, *, file: str, line: int | None = None,
                        key: str | None = None) -> float:
    """Factor converting accelerations in ``units`` to m/s² (``g`` = ``gravity`` [m/s²])."""
    text = units.strip().lower().replace(" ", "")
    if text in _UNIT_FACTORS_OF_G:
        return gravity
    if text in _UNIT_FACTORS_SI:
        return _UNIT_FACTORS_SI[text]
    try:
        return parse_quantity(f"1 {units.strip()}", "acceleration", gravity=gravity)
    except QuantityParseError:
        raise RecordError("unknown acceleration units", file=file, line=line, key=key,
                          expected="g, m/s^2, cm/s^2 (gal), mm/s^2, in/s^2 or ft/s^2",
                          found=repr(units)) from None


def read_record_file(path, *, units: str | None = None, dt: float | None = None,
                     gravity: float = 9.81, name: str | None = None) -> GroundMotion:
    """Read a PEER AT2, one-column or two-column record file into a GroundMotion (m/s², s).

    Args:
        path: the record file.
        units: acceleration units of the file's numbers when the file does not say (or to
            override it): ``g``, ``m/s^2``, ``cm/s^2``, ``gal``...
        dt: sample spacing [s] of a one-column file (overrides a header comment).
        gravity: value of g [m/s²] used for files in g (the project's gravity, CONTRACT §1).
        name: name of the motion (default: the file name).

    Returns:
        A record GroundMotion with samples in m/s² and meta: event, year, date, station,
        component, rsn, dt, npts, units, format, source_file.

    Raises:
        RecordError: unreadable or malformed file, naming the file and the line.
    """
    path = user_path(path, None, error=RecordError)
    file = str(path)
    if not path.is_file():
        raise RecordError("record file not found", file=file, expected="an existing file",
                          found="no such file")
    try:
        text = path.read_text(encoding="utf-8-sig", errors="replace")
    except OSError as exc:
        raise RecordError(f"cannot read record file ({exc.strerror})", file=file) from None
    lines = text.splitlines()
    if not any(line.strip() for line in lines):
        raise RecordError("empty record file", file=file, line=1, expected="a header and samples",
                          found="an empty file")
    is_at2 = path.suffix.lower() == ".at2" or lines[0].lstrip().upper().startswith("PEER")
    if is_at2:
        samples, step, meta, factor = _read_at2(lines, file, units, gravity)
    else:
        samples, step, meta, factor = _read_columns(lines, file, units, dt, gravity)
    if dt is not None and is_at2:
        step = _positive_dt(dt, file, None, key="dt")
    rsn = _RSN_IN_NAME.search(path.name)
    if meta.get("rsn") is None and rsn:
        meta["rsn"] = int(rsn.group(1))
    meta.update(source_file=str(path.resolve()), file_name=path.name)
    accel = samples * factor
    return record_motion(name or path.name, accel, step, meta=meta)


def _positive_dt(value, file, line, key=None) -> float:
    step = float(value)
    if not (math.isfinite(step) and step > 0.0):
        raise RecordError("the sample spacing must be positive", file=file, line=line, key=key,
                          expected="DT > 0 s", found=repr(value))
    return step


def _number(token: str) -> float:
    return float(token.replace("D", "E").replace("d", "e"))


def _parse_values(line: str, lineno: int, file: str) -> list[float]:
    """The numbers of one data line; glued Fortran fields (1.0E-03-2.0E-03) are split."""
    values = []
    for token in line.replace(",", " ").split():
        try:
            values.append(_number(token))
            continue
        except ValueError:
            pass
        parts = _NUMBER_RE.findall(token)
        if parts and "".join(parts) == token:
            values.extend(_number(p) for p in parts)
        else:
            raise RecordError("unreadable sample value", file=file, line=lineno,
                              expected="numbers such as -.3355800E-03", found=repr(token))
    for v in values:
        if not math.isfinite(v):
            raise RecordError("non-finite sample value", file=file, line=lineno,
                              expected="finite numbers", found=repr(v))
    return values


def _parse_station_line(text: str) -> dict:
    """``event, date, station, component`` (West2) or ``EVENT MM/DD/YY HHMM, STATION, COMP`` (West1)."""
    parts = _split_outside_parentheses(text)
    meta: dict = {"event": None, "date": None, "year": None, "station": None, "component": None}
    if len(parts) >= 3:
        component = parts[-1]
        note = re.search(r"\s*\((.*)\)\s*$", component)
        if note and note.start() > 0:
            meta["note"] = note.group(1)
            component = component[:note.start()]
        meta["component"] = component.strip() or None
        date_idx = next((i for i, p in enumerate(parts) if _DATE.search(p)), None)
        if date_idx is not None and date_idx < len(parts) - 2:
            match = _DATE.search(parts[date_idx])
            head = parts[date_idx][:match.start()].strip()
            meta["event"] = ", ".join(parts[:date_idx] + ([head] if head else [])) or None
            meta["date"] = match.group(0)
            meta["year"] = _year(match.group(3))
            meta["station"] = ", ".join(parts[date_idx + 1:-1]) or None
        else:
            year_idx = next((i for i, p in enumerate(parts) if re.fullmatch(r"\d{4}", p)), None)
            if year_idx is not None and year_idx < len(parts) - 2:
                meta["event"] = ", ".join(parts[:year_idx]) or None
                meta["year"] = int(parts[year_idx])
                meta["station"] = ", ".join(parts[year_idx + 1:-1]) or None
            else:
                meta["event"] = parts[0] or None
                meta["station"] = ", ".join(parts[1:-1]) or None
    else:
        meta["event"] = text.strip() or None
    return meta


def _split_outside_parentheses(text: str) -> list[str]:
    parts, depth, current = [], 0, []
    for ch in text:
        depth += (ch in "([") - (ch in ")]")
        if ch == "," and depth <= 0:
            parts.append("".join(current).strip())
            current = []
        else:
            current.append(ch)
    parts.append("".join(current).strip())
    return parts


def _year(text: str) -> int:
    year = int(text)
    if year < 100:
        year += 1900 if year > 25 else 2000
    return year


def _read_at2(lines, file, units, gravity):
    if len(lines) < 4:
        raise RecordError("truncated PEER AT2 header", file=file, line=len(lines),
                          expected="4 header lines (title, event, units, NPTS/DT)",
                          found=f"{len(lines)} line(s)")
    meta = _parse_station_line(lines[1])
    meta["format"] = "PEER NGA AT2"
    units_line = lines[2]
    if re.search(r"\b(VELOCITY|DISPLACEMENT)\b", units_line, re.I):
        raise RecordError("not an acceleration record", file=file, line=3,
                          expected="ACCELERATION TIME SERIES", found=units_line.strip())
    found_units = _UNITS_OF.search(units_line)
    if units is None:
        if not found_units:
            raise RecordError("the units of the record are not stated", file=file, line=3,
                              expected="'... IN UNITS OF G' (or pass units=...)",
                              found=units_line.strip() or "an empty line")
        units_text = found_units.group(1).rstrip(".")
        factor = acceleration_factor(units_text, gravity, file=file, line=3)
    else:
        units_text = units
        factor = acceleration_factor(units, gravity, file=file, key="units")
    meta["units"] = units_text
    npts = step = None
    for pattern in _NPTS_DT:
        m = pattern.search(lines[3])
        if m:
            a, b = m.groups()
            npts_text, dt_text = (b, a) if pattern is _NPTS_DT[2] else (a, b)
            npts, step = int(npts_text), _number(dt_text)
            break
    if npts is None:
        raise RecordError("cannot read NPTS and DT", file=file, line=4,
                          expected="'NPTS=  2200, DT=   .0200 SEC' or '2200 0.0200 NPTS, DT'",
                          found=lines[3].strip() or "an empty line")
    step = _positive_dt(step, file, 4)
    if npts < 2:
        raise RecordError("too few samples", file=file, line=4, expected="NPTS >= 2", found=str(npts))
    values: list[float] = []
    last_line = 4
    for lineno, line in enumerate(lines[4:], start=5):
        if not line.strip():
            continue
        row = _parse_values(line, lineno, file)
        if len(values) + len(row) > npts:
            raise RecordError("more samples than NPTS", file=file, line=lineno,
                              expected=f"NPTS = {npts} values (header line 4)",
                              found=f"value {npts + 1} on this line")
        values.extend(row)
        last_line = lineno
    if len(values) < npts:
        raise RecordError("truncated data: fewer samples than NPTS", file=file, line=last_line,
                          expected=f"NPTS = {npts} values (header line 4)",
                          found=f"{len(values)} values, the file ends at line {last_line}")
    meta["npts"] = npts
    return np.asarray(values, dtype=np.float64), step, meta, factor


def _comment_declarations(text: str) -> dict:
    """``dt``/``npts``/``units`` declared in a comment: ``npts=3995 dt=0.01`` or ``units: g``.

    A ';'-separated segment counts only if it is nothing but declarations, so prose such as
    ``source labels dt=0.02 but ...`` is not mistaken for one.
    """
    found: dict = {}
    for segment in text.split(";"):
        segment = segment.strip().rstrip(".")
        if not segment:
            continue
        m = _DECLARATION.match(segment)
        if m:
            found[_declared_key(m.group(1))] = m.group(2)
            continue
        pairs = _KEY_VALUE.findall(segment)
        if pairs and _KEY_VALUE.sub("", segment).strip(" ,\t") == "":
            for k, v in pairs:
                found[_declared_key(k)] = v
    return found


def _declared_key(key: str) -> str:
    key = key.lower()
    return "units" if key.startswith("unit") else key


def _read_columns(lines, file, units, dt, gravity):
    declared: dict = {}
    declared_line: dict = {}
    header_units = header_line = None
    rows: list[tuple[int, list[float]]] = []
    for lineno, line in enumerate(lines, start=1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped[0] in "#%!":
            for k, v in _comment_declarations(stripped.lstrip("#%! ")).items():
                declared[k] = v
                declared_line[k] = lineno
            continue
        if not rows and not _NUMBER_RE.match(stripped.replace(",", " ").split()[0]):
            m = _HEADER_UNITS.findall(stripped)
            header_units, header_line = (m[-1], lineno) if m else (None, lineno)
            continue
        rows.append((lineno, _parse_values(stripped.replace(";", " ").replace("\t", " "), lineno, file)))
    if not rows:
        raise RecordError("no samples found", file=file, line=len(lines),
                          expected="one value per line, or 't, a' pairs", found="no numeric lines")
    ncol = len(rows[0][1])
    for lineno, row in rows:
        if len(row) != ncol or ncol not in (1, 2):
            raise RecordError("inconsistent number of columns", file=file, line=lineno,
                              expected=f"{ncol if ncol in (1, 2) else '1 or 2'} value(s) per line",
                              found=f"{len(row)} value(s)")
    meta = {"event": None, "date": None, "year": None, "station": None, "component": None,
            "rsn": None}
    # units: argument > comment declaration > column header
    if units is not None:
        factor = acceleration_factor(units, gravity, file=file, key="units")
        units_text = units
    elif "units" in declared:
        units_text = declared["units"]
        factor = acceleration_factor(units_text, gravity, file=file, line=declared_line["units"])
    elif header_units:
        units_text = header_units
        factor = acceleration_factor(units_text, gravity, file=file, line=header_line)
    else:
        raise RecordError("the units of the accelerations are not declared", file=file,
                          line=rows[0][0], expected="units=... or a comment '# units: g' or a "
                          "column header like 'acc (g)'", found="no units")
    meta["units"] = units_text
    data = np.asarray([r for _, r in rows], dtype=np.float64)
    if ncol == 1:
        meta["format"] = "one column"
        if dt is not None:
            step = _positive_dt(dt, file, None, key="dt")
        elif "dt" in declared:
            try:
                step_value = parse_quantity(declared["dt"] if re.search(r"[a-z]", declared["dt"], re.I)
                                            else f"{declared['dt']} s", "time")
            except QuantityParseError:
                raise RecordError("cannot read dt", file=file, line=declared_line["dt"],
                                  expected="a time step like 'dt=0.01'", found=declared["dt"]) from None
            step = _positive_dt(step_value, file, declared_line["dt"])
        else:
            raise RecordError("the sample spacing is not given", file=file, line=rows[0][0],
                              expected="dt=... or a header comment '# dt=0.01'", found="no dt")
        samples = data[:, 0]
        if "npts" in declared:
            try:
                npts = int(declared["npts"])
            except ValueError:
                raise RecordError("cannot read npts", file=file, line=declared_line["npts"],
                                  expected="an integer", found=declared["npts"]) from None
            if npts != samples.size:
                where = rows[-1][0] if samples.size < npts else rows[npts][0]
                raise RecordError("number of samples differs from the declared npts", file=file,
                                  line=where, expected=f"npts = {npts} (line {declared_line['npts']})",
                                  found=f"{samples.size} values")
    else:
        meta["format"] = "two columns (t, a)"
        times, samples = data[:, 0], data[:, 1]
        if samples.size < 2:
            raise RecordError("too few samples", file=file, line=rows[0][0], expected=">= 2 rows",
                              found="1 row")
        steps = np.diff(times)
        typical = float(np.median(steps))
        _positive_dt(typical, file, rows[1][0])
        bad = np.nonzero(np.abs(steps - typical) > 0.01 * typical)[0]
        if bad.size:
            i = int(bad[0]) + 1
            raise RecordError("non-uniform time step", file=file, line=rows[i][0],
                              expected=f"t = {times[i - 1] + typical:.6g} s (uniform dt = {typical:.6g} s)",
                              found=f"t = {times[i]:.6g} s")
        step = (times[-1] - times[0]) / (times.size - 1)
        meta["t_start"] = float(times[0])
    if samples.size < 2:
        raise RecordError("too few samples", file=file, line=rows[0][0], expected=">= 2 samples",
                          found=f"{samples.size}")
    meta["npts"] = int(samples.size)
    return samples, float(step), meta, factor
