"""The ``[excitation]`` table of a project file (CONTRACT §1) and the records it resolves to.

Keys (quantities as strings with units; ``g`` is the project's gravity)::

    [excitation]
    design_pga = "0.35 g"                  # design peak ground acceleration
    suites = ["p695-farfield"]             # built-in suite names or paths to suite manifests
    records = ["p695-ff/11a", "rsn:6:180"] # extension: extra record ids (built-in, rsn:, file:, paths)
    scale = { method = "pga", target = "0.35 g" }   # rockdesign.motions.scaling (factor | pga |
                                           #   sdmax | uplift | spectrum)
    records_dir = "~/peer"                 # folder of the user's PEER *.AT2 files
    time_scale = 0.5                       # extension: Δt × 0.5, or { model_size = "0.25 m",
                                           #   prototype_size = "1 m" } for Δt_m = Δt_p √(R_m/R_p) (Eq 6.5)

Defaults: no suites and no records → suite ``p695-farfield``; no ``scale`` → PGA scaled to
``design_pga`` if given, else each suite's own default rule (the built-in ones: as recorded).
Relative paths are taken from the project file's folder.

``scale = { method = "asce7-22", ... }`` (CONTRACT §7.1) scales ground motions, not records: one factor
per pair of components (:mod:`rockdesign.motions.asce7_22`); the caller passes the structure's
characteristic periods for the §16.2.1 period range unless the rule gives ``periods``.

A suite lists each recording once: the same record under two names (two paths to one file, a built-in
record beside its PEER file, the same id twice) is refused (:mod:`rockdesign.motions.identity`, SPEC §14).
"""
from __future__ import annotations

import difflib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

from ..errors import MotionError, ProjectError, RecordError
from ..paths import user_path
from ..units import QuantityParseError, parse_quantity
from .grouping import ground_motion_id, refuse_inconsistent_ground_motions
from .identity import Entry, refuse_repeated_recordings
from .library import load_record
from .motion import GroundMotion
from .scaling import ScaleRule, parse_scale_rule, scale_factors, similitude_time_factor, time_scaled
from .suites import load_suite, suite_path

EXCITATION_KEYS = ("design_pga", "suites", "records", "scale", "records_dir", "time_scale")
DEFAULT_SUITE = "p695-farfield"


@dataclass(frozen=True)
class ExcitationSpec:
    """The parsed ``[excitation]`` table (SI).

    Attributes:
        design_pga: design PGA [m/s²] or None.
        suites: suite names or manifest paths, in order.
        records: extra record ids, in order.
        scale: the explicit scaling rule, or None (see module docstring for the default).
        records_dir: folder of the user's PEER AT2 files, or None.
        time_scale: time factor Δt_analysis/Δt_record (Eq 6.5), 1 = as recorded.
        default_used: True when the project had no ``[excitation]`` table.
        file: the project file (for messages).
    """

    design_pga: float | None = None
    suites: tuple[str, ...] = (DEFAULT_SUITE,)
    records: tuple[str, ...] = ()
    scale: ScaleRule | None = None
    records_dir: Path | None = None
    time_scale: float = 1.0
    default_used: bool = False
    file: str | None = None

    def effective_scale(self) -> ScaleRule | None:
        """The rule applied to all records: explicit ``scale``, else PGA = design_pga, else None
        (each suite's default rule)."""
        if self.scale is not None:
            return self.scale
        if self.design_pga is not None:
            return ScaleRule("pga", value=self.design_pga)
        return None


@dataclass
class ResolvedRecord:
    """One record ready for analysis: id, scaled motion [m/s²], amplitude factor, metadata."""

    id: str
    motion: GroundMotion
    scale: float
    meta: dict
    suite: str | None = None


@dataclass
class ResolvedSuite:
    """The records of an ExcitationSpec in stable order (suites in order, then extra records).

    Attributes:
        records: the records found, scaled.
        missing: (id, reason, suite) of records not found.
        scale_description: how the records were scaled (for reports).
        default_used: the default excitation was used (no ``[excitation]`` table).
        suites: the suites' names, in order.
        rules: (suite name or None for the extra records, the rule applied to its records), for every
            group with records; one entry (None, rule) when one rule scaled all records.
        asce7_22: the outcome of ASCE 7-22 §16.2.3 scaling (factors per ground motion, period range,
            spectra), when the records were scaled so; else None.
        derived: see below.
    """

    records: list[ResolvedRecord]
    missing: list[tuple[str, str, str | None]]
    scale_description: str
    default_used: bool = False
    suites: list[str] = field(default_factory=list)
    rules: list = field(default_factory=list)
    asce7_22: object | None = None
    derived: dict = field(default_factory=dict, repr=False, compare=False)
    """Numbers that follow from the scaled records alone, computed once for every check that shares them (a
    design grid's variants): e.g. the SD_max of each record by (damping, band)."""


def default_excitation(design_pga: float | None, *, file: str | None = None) -> ExcitationSpec:
    """The excitation of a project without ``[excitation]``: suite p695-farfield scaled to
    ``design_pga`` [m/s²] (CONTRACT §1), flagged ``default_used``."""
    return ExcitationSpec(design_pga=design_pga, suites=(DEFAULT_SUITE,), default_used=True, file=file)


def _unknown_key(name, file):
    close = difflib.get_close_matches(name, EXCITATION_KEYS, n=1, cutoff=0.5)
    return ProjectError("unknown key in [excitation]", file=file, key=f"excitation.{name}",
                        expected=", ".join(EXCITATION_KEYS), found=repr(name),
                        hint=f"did you mean '{close[0]}'?" if close else None)


def _string_list(raw, name, file) -> list[str]:
    if isinstance(raw, str):
        raw = [raw]
    if not isinstance(raw, list) or not all(isinstance(v, str) and v.strip() for v in raw):
        raise ProjectError("invalid list", file=file, key=f"excitation.{name}",
                           expected="a list of non-empty strings", found=repr(raw))
    return [v.strip() for v in raw]


def _base_dir(file: str | None) -> Path:
    return Path(file).expanduser().resolve().parent if file else Path.cwd()


def _relative(text: str, base: Path, *, file: str | None = None, key: str | None = None) -> str:
    """A path of the project file, relative to its folder (``~`` expanded; a ``~user`` that names nobody, a name
    too long or an unreadable folder is refused naming ``key``)."""
    return str(user_path(text, key, file=file, base=base))


def _looks_like_path(text: str) -> bool:
    return text.endswith(".toml") or "/" in text or "\\" in text


def parse_excitation(raw: dict | None, *, file: str, gravity: float = 9.81) -> ExcitationSpec:
    """Validate the ``[excitation]`` table of ``file`` into an :class:`ExcitationSpec` (SI).

    ``raw`` None (no table) gives the default excitation without a design PGA; callers that know
    ``design_pga`` use :func:`default_excitation`.

    Raises:
        ProjectError: unknown key (with the nearest valid one), wrong type or dimension, unknown
            suite, missing records folder.
    """
    if raw is None:
        return default_excitation(None, file=file)
    if not isinstance(raw, dict):
        raise ProjectError("[excitation] must be a table", file=file, key="excitation",
                           expected="a TOML table", found=repr(raw))
    for name in raw:
        if name not in EXCITATION_KEYS:
            raise _unknown_key(name, file)
    base = _base_dir(file)
    design_pga = None
    if "design_pga" in raw:
        try:
            design_pga = parse_quantity(raw["design_pga"], "acceleration", gravity=gravity)
        except QuantityParseError as exc:
            raise ProjectError("invalid design PGA", file=file, key="excitation.design_pga",
                               expected="an acceleration like '0.35 g'", found=repr(raw["design_pga"]),
                               hint=str(exc)) from None
        if not design_pga > 0:
            raise ProjectError("invalid design PGA", file=file, key="excitation.design_pga",
                               expected="a positive acceleration", found=repr(raw["design_pga"]))
    for name in ("suites", "records"):
        if name in raw and isinstance(raw[name], list) and not raw[name] and not (
                raw.get("records") if name == "suites" else raw.get("suites")):
            raise ProjectError(f"empty {name} list", file=file, key=f"excitation.{name}",
                               expected=f"at least one {name[:-1]} (e.g. suites = [\"{DEFAULT_SUITE}\"]), or leave the "
                                        "key out for the default suite", found="[]")
    suites = _string_list(raw.get("suites", []), "suites", file)
    for i, name in enumerate(suites):
        if _looks_like_path(name):
            suites[i] = _relative(name, base, file=file, key=f"excitation.suites[{i}]")
        try:
            suite_path(suites[i])
        except MotionError as exc:
            raise ProjectError(exc.detail, file=file, key=f"excitation.suites[{i}]", expected=exc.expected,
                               found=exc.found, hint=exc.hint) from None
    records = _string_list(raw.get("records", []), "records", file)
    for i, rid in enumerate(records):
        if rid.lower().startswith("file:"):
            records[i] = "file:" + _relative(rid[5:].strip(), base, file=file, key=f"excitation.records[{i}]")
        elif not rid.lower().startswith(("rsn:", "p695-")) and _looks_like_path(rid):
            records[i] = _relative(rid, base, file=file, key=f"excitation.records[{i}]")
    if not suites and not records:
        suites = [DEFAULT_SUITE]
    scale = None
    if "scale" in raw:
        scale = parse_scale_rule(raw["scale"], file=file, key="excitation.scale", gravity=gravity)
    if design_pga is not None and scale is not None:
        _check_one_intensity(design_pga, scale, raw, file, gravity)
    records_dir = None
    if "records_dir" in raw:
        if not isinstance(raw["records_dir"], str) or not raw["records_dir"].strip():
            raise ProjectError("invalid records folder", file=file, key="excitation.records_dir",
                               expected="a folder path string", found=repr(raw["records_dir"]))
        records_dir = Path(_relative(raw["records_dir"].strip(), base, file=file, key="excitation.records_dir"))
        if not records_dir.is_dir():
            raise ProjectError("records folder not found", file=file, key="excitation.records_dir",
                               expected="an existing folder of PEER *.AT2 files", found=str(records_dir))
    time_scale = _parse_time_scale(raw.get("time_scale", 1.0), file, gravity)
    return ExcitationSpec(design_pga=design_pga, suites=tuple(suites), records=tuple(records), scale=scale,
                          records_dir=records_dir, time_scale=time_scale, file=file)


def _check_one_intensity(design_pga: float, scale: ScaleRule, raw: dict, file, gravity: float) -> None:
    """``design_pga`` and an explicit ``scale`` must not name two different intensities: the records
    are scaled by ``scale``, so a design PGA that differs from it (or that the scale method does not
    use) would be silently dropped."""
    given = repr(raw["design_pga"])
    if scale.method == "pga":
        if abs(scale.value - design_pga) > 1e-9 * design_pga:
            raise ProjectError("conflicting design intensities", file=file, key="excitation.scale.target",
                               expected=f"the design PGA design_pga = {given} "
                                        f"({design_pga / gravity:.4g} g), or only one of the two",
                               found=f"{raw['scale'].get('target')!r} ({scale.value / gravity:.4g} g)")
        return
    raise ProjectError(f"design_pga is not used by scale method '{scale.method}'", file=file,
                       key="excitation.design_pga",
                       expected=f"either design_pga (records scaled to that PGA) or scale = {{ method = "
                                f"\"{scale.method}\", ... }}, not both", found=given)


def _parse_time_scale(raw, file, gravity) -> float:
    key = "excitation.time_scale"
    if isinstance(raw, dict):
        allowed = ("model_size", "prototype_size")
        for name in raw:
            if name not in allowed:
                close = difflib.get_close_matches(name, allowed, n=1)
                raise ProjectError("unknown key", file=file, key=f"{key}.{name}", expected=", ".join(allowed),
                                   found=repr(name), hint=f"did you mean '{close[0]}'?" if close else None)
        sizes = []
        for name in allowed:
            if name not in raw:
                raise ProjectError("time scaling by similitude needs both sizes", file=file, key=f"{key}.{name}",
                                   expected='model_size = "0.25 m" and prototype_size = "2.5 m"', found="nothing")
            try:
                sizes.append(parse_quantity(raw[name], "length", gravity=gravity))
            except QuantityParseError:
                raise ProjectError("invalid size", file=file, key=f"{key}.{name}", expected="a length like '2.5 m'",
                                   found=repr(raw[name])) from None
        if not all(s > 0 for s in sizes):
            raise ProjectError("invalid size", file=file, key=key, expected="positive lengths", found=repr(raw))
        return similitude_time_factor(sizes[0], sizes[1])
    if isinstance(raw, bool) or not isinstance(raw, (int, float)) or not (math.isfinite(raw) and raw > 0):
        raise ProjectError("invalid time scale", file=file, key=key,
                           expected="a positive number or { model_size, prototype_size }", found=repr(raw))
    return float(raw)


def resolve_motions(spec: ExcitationSpec, *, gravity: float = 9.81, uplift_acceleration: float | None = None,
                    records_dir=None, characteristic_periods: Mapping[str, float] | None = None) -> ResolvedSuite:
    """Load, time-scale and amplitude-scale the records of ``spec`` in a stable order.

    Order: each suite's records in manifest order, then ``records``.  Records that cannot be found are
    returned in ``missing`` with the reason.  A recording listed twice, under any names, is refused
    (:func:`rockdesign.motions.identity.refuse_repeated_recordings`, SPEC §14).

    Args:
        spec: the parsed excitation.
        gravity: g [m/s²].
        uplift_acceleration: the system's g tan α [m/s²] (scale method ``uplift``).
        records_dir: overrides ``spec.records_dir`` (e.g. ``--records-dir``).
        characteristic_periods: label → period [s] of the structure (scale method ``asce7-22``: the
            §16.2.1 period range, :func:`rockdesign.motions.asce7_22.scaling_period_range`), unless the
            rule gives ``periods``.

    Raises:
        ProjectError / MotionError / RecordError: unreadable suites or record files, a recording listed
            twice, impossible scaling (an ``asce7-22`` suite whose ground motions are not pairs).
    """
    folder = records_dir if records_dir is not None else spec.records_dir
    groups: list[tuple[str | None, ScaleRule | None, list[tuple[str, GroundMotion, dict]]]] = []
    missing: list[tuple[str, str, str | None]] = []
    entries: list[Entry] = []
    # (id, the acceptance's meta, the record's meta, where, file): one ground motion, one station
    stations: list[tuple] = []
    for name in spec.suites:
        suite = load_suite(name, gravity=gravity, records_dir=folder)
        found = []
        for index, entry in enumerate(suite.entries):
            manifest = str(suite.path) if suite.path else None
            entries.append(Entry(entry.id, f"suite {suite.name}", entry.motion, entry.meta, manifest))
            if entry.motion is None:
                missing.append((entry.id, entry.reason, suite.name))
            else:
                found.append((entry.id, entry.motion, dict(entry.meta, suite=suite.name)))
                stations.append((entry.id, found[-1][2], {**entry.motion.meta, **entry.meta},
                                 f"suite {suite.name}, records[{index}]", manifest))
        groups.append((suite.name, suite.default_scale, found))
    extra = []
    for i, rid in enumerate(spec.records):
        where = f"excitation.records[{i}]"
        try:
            motion = load_record(rid, gravity=gravity, records_dir=folder)
        except RecordError as exc:
            if rid.lower().startswith("rsn:"):
                missing.append((rid, exc.detail, None))
                entries.append(Entry(rid, where, None, {}, spec.file))
                continue
            raise
        entries.append(Entry(rid, where, motion, {}, spec.file))
        extra.append((rid, motion, dict(motion.meta)))
        stations.append((rid, extra[-1][2], dict(motion.meta), where, spec.file))
    groups.append((None, None, extra))
    refuse_repeated_recordings(entries, file=spec.file, key="excitation")
    refuse_inconsistent_ground_motions(stations, file=spec.file, key="excitation")
    if spec.time_scale != 1.0:
        groups = [(s, r, [(i, time_scaled(m, spec.time_scale), meta) for i, m, meta in items])
                  for s, r, items in groups]
    rule = spec.effective_scale()
    resolved: list[ResolvedRecord] = []
    descriptions = []
    rules = []
    asce = None
    if rule is not None:
        items = [(suite, item) for suite, _, group in groups for item in group]
        if rule.method == "asce7-22":
            factors, asce = _asce7_22_factors(rule, [item for _, item in items], spec, characteristic_periods)
        else:
            factors = scale_factors(rule, [m for _, (_, m, _) in items], uplift_acceleration=uplift_acceleration,
                                    gravity=gravity) if items else []
        for (suite, (rid, motion, meta)), factor in zip(items, factors):
            resolved.append(ResolvedRecord(rid, motion.scaled(factor), factor, meta, suite))
        descriptions.append(rule.describe(gravity))
        rules.append((None, rule))
    else:
        filled = [g for g in groups if g[2]]
        for suite, suite_rule, group in filled:
            group_rule = suite_rule or ScaleRule("factor", value=1.0)
            if group_rule.method == "asce7-22":
                if len(filled) > 1:
                    raise ProjectError(
                        f"suite {suite}'s own asce7-22 rule cannot scale it beside other records", file=spec.file,
                        key="excitation.scale", expected='one rule for the whole suite: [excitation] scale = '
                        '{ method = "asce7-22", ... }', found=", ".join(str(g[0] or "extra records") for g in filled))
                factors, asce = _asce7_22_factors(group_rule, group, spec, characteristic_periods)
            else:
                factors = scale_factors(group_rule, [m for _, m, _ in group], uplift_acceleration=uplift_acceleration,
                                        gravity=gravity)
            for (rid, motion, meta), factor in zip(group, factors):
                resolved.append(ResolvedRecord(rid, motion.scaled(factor), factor, meta, suite))
            descriptions.append(f"{suite or 'extra records'}: {group_rule.describe(gravity)}")
            rules.append((suite, group_rule))
    text = "; ".join(descriptions) or "no records"
    if spec.time_scale != 1.0:
        text += f"; time scaled by {spec.time_scale:.4g} (Δt × {spec.time_scale:.4g}, Eq 6.5)"
    return ResolvedSuite(resolved, missing, text, spec.default_used, [g[0] for g in groups if g[0]], rules, asce)


def _asce7_22_factors(rule: ScaleRule, items: list[tuple[str, GroundMotion, dict]], spec: ExcitationSpec,
                      characteristic_periods):
    """Per-record factors of ASCE 7-22 §16.2.3 scaling (one per ground motion), and the scaling outcome.

    Raises:
        ProjectError: ground motions that are not pairs (one component only, three, different time steps,
            non-orthogonal components), no period range, or a target that does not cover it.
    """
    from .asce7_22 import asce7_22_scaling, pair_components, scaling_period_range
    pairs, problems = pair_components(items)
    if problems:
        listed = "; ".join(f"{gm} ({', '.join(ids)}): {why}" for gm, ids, why in problems[:6])
        if len(problems) > 6:
            listed += f"; and {len(problems) - 6} more"
        raise ProjectError("ASCE 7-22 §16.2.3 scaling needs both horizontal components of every ground motion: "
                           "a suite of single components cannot conform", file=spec.file, key="excitation.scale",
                           expected="two orthogonal components (records) per ground motion, on one time step",
                           found=listed)
    try:
        period_range = scaling_period_range(characteristic_periods, override=rule.periods)
        result = asce7_22_scaling(pairs, rule.spectrum, period_range)
    except MotionError as exc:
        raise ProjectError(exc.detail, file=spec.file, key=exc.key, expected=exc.expected, found=exc.found,
                           hint=exc.hint) from None
    return [result.factors[ground_motion_id(rid, meta)] for rid, _, meta in items], result
