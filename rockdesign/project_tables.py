"""What every project file shares, planar or cylinder: the [project] and [analysis] tables, the
key-tracking table reader behind the precise error messages, and the loaded :class:`Project`
(docs/project-file.md).  :mod:`rockdesign.planar.project` (columns, frames, podiums) and
:mod:`rockdesign.cylinder.project` (the 3D cylinder) both build on it.
"""
from __future__ import annotations

import difflib
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .errors import ProjectError
from .units import G_DEFAULT, QuantityParseError, parse_angular_frequency, parse_quantity

PROJECT_KEYS = ("name", "engineer", "checker", "job", "client", "notes")


ANALYSIS_KEYS = ("model", "equations", "rtol", "atol", "overturn", "g", "rest_velocity", "sdmax_damping",
                 "sdmax_band", "linearization_tolerance", "restitution_variation", "margin_precision",
                 "margin_max_scale", "free_vibration", "rigid_superstructure_ratio", "scan_rtol",
                 "overturn_probability_limit", "fragility_im", "fragility_period", "quality", "ensemble_size", "seed",
                 "risk_category", "acceptance")


EQUATIONS = ("auto", "exact", "linear")


OVERTURN = ("static", "dynamic")


RESTITUTION_RULES = ("theory", "thesis-eq-3.39")


@dataclass(frozen=True)
class AnalysisSettings:
    """The ``[analysis]`` table in SI (CONTRACT §1, plus documented extensions)."""

    model: str = "auto"
    equations: str = "auto"
    rtol: float = 1e-8      # docs/tolerances.md: the loosest rtol at which the verdict's statistics are converged
    atol: float = 1e-10
    overturn: str = "static"
    g: float = G_DEFAULT
    rest_velocity: float = 5e-4
    sdmax_damping: float = 0.02
    sdmax_band: tuple[float, float] = (0.05, 10.0)
    linearization_tolerance: float = 0.02
    restitution_variation: float = 0.02
    margin_precision: float = 0.01
    margin_max_scale: float = 8.0
    free_vibration: float = 10.0
    rigid_superstructure_ratio: float = 10.0
    """ω_s/p at and above which a podium's superstructure is treated as rigid by default (SPEC §6)."""
    scan_rtol: float = 1e-6
    overturn_probability_limit: float = 0.10
    # fragility, collapse margin and perturbation ensembles (SPEC §11; parsed by _parse_fragility)
    fragility_im: str = "pga"
    fragility_period: float | None = None
    quality: tuple[tuple[str, str], ...] = (("design_requirements", "B"), ("test_data", "B"), ("modeling", "B"))
    ensemble_size: int = 8
    seed: int = 20090601
    # acceptance (SPEC §14, CONTRACT §6.1; parsed by _parse_acceptance)
    risk_category: str = "II"
    acceptance: str = "asce7"
    overturn_probability_limit_set: bool = False    # the project gave overturn_probability_limit (binomial limit)


DEFAULTS = AnalysisSettings()
"""The ``[analysis]`` defaults: the parser fills every key the project file leaves out from here."""


@dataclass(frozen=True)
class Project:
    """A loaded project: the system in SI, analysis settings, the raw input for the report's echo."""

    path: str
    name: str
    system: object
    """The structure in SI, of the project's kind (a planar ``RockingSystem``, a ``Cylinder``, …)."""
    analysis: AnalysisSettings
    info: dict = field(default_factory=dict)
    excitation_raw: dict | None = None
    raw: dict = field(default_factory=dict)
    source_text: str = ""
    sha256: str = ""
    warnings: tuple[str, ...] = ()
    excitation: object | None = None
    """The ``[excitation]`` table parsed at load by the project's kind (planar:
    :class:`~rockdesign.motions.config.ExcitationSpec`, None without the table; cylinder:
    :class:`~rockdesign.cylinder.project.CylinderExcitation`).  The check reads this, never the raw table."""
    kind: object | None = field(default=None, compare=False, repr=False)
    """The kind of structure that parsed the project (:mod:`rockdesign.kinds`): the registry is asked once, at
    load, and every later call (``check``, ``write_report`` of its result) takes the kind from here."""
    derived: dict = field(default_factory=dict, init=False, compare=False, repr=False)
    """What the project's kind derived from it once and keeps for the later steps of the same command (the planar
    check's design quantities and records, read by ``prepare_check`` and analysed by ``check``); a variant made
    with :func:`dataclasses.replace` starts empty."""


class _Table:
    """Reads one TOML table, tracking which keys were used, for precise error messages."""

    def __init__(self, data: dict, section: str, allowed: tuple[str, ...], file: str, gravity: float):
        self.data, self.section, self.allowed, self.file, self.gravity = data, section, allowed, file, gravity
        if not isinstance(data, dict):
            raise ProjectError("must be a table", file=file, key=section, expected=f"a [{section}] table",
                               found=repr(data))
        for key in data:
            if key not in allowed:
                close = difflib.get_close_matches(key, allowed, n=1, cutoff=0.5)
                raise ProjectError("unknown key", file=file, key=f"{section}.{key}",
                                   expected="one of " + ", ".join(allowed),
                                   found=f"'{key}'", hint=f"did you mean '{close[0]}'?" if close else None)

    def key(self, name: str) -> str:
        return f"{self.section}.{name}"

    def has(self, name: str) -> bool:
        return name in self.data

    def error(self, name: str, detail: str, expected: str | None = None, found=None) -> ProjectError:
        return ProjectError(detail, file=self.file, key=self.key(name), expected=expected,
                            found=None if found is None else (repr(found) if not isinstance(found, str) else f"'{found}'"))

    def quantity(self, name: str, dimension: str, *, positive: bool = True, default=None, required=False):
        if name not in self.data:
            if required:
                raise self.error(name, "missing required value", expected=f"{'an' if dimension[0] in 'aeiou' else 'a'} {dimension}")
            return default
        raw = self.data[name]
        try:
            value = parse_quantity(raw, dimension, gravity=self.gravity)
        except QuantityParseError as exc:
            raise ProjectError(f"expects {exc}", file=self.file, key=self.key(name)) from None
        if not math.isfinite(value):
            raise self.error(name, "must be finite", expected=f"a finite {dimension}", found=raw)
        if positive and value <= 0.0:
            raise self.error(name, "must be positive", expected=f"{'an' if dimension[0] in 'aeiou' else 'a'} {dimension} > 0",
                             found=raw)
        return value

    def angular_frequency(self, name: str, *, plain_is_cyclic: bool) -> float:
        """A frequency key as ω [rad/s] (:func:`~rockdesign.units.parse_angular_frequency`: "rad/s" and "rpm"
        are angular, "Hz" cyclic), finite and positive."""
        raw = self.data[name]
        try:
            value = parse_angular_frequency(raw, plain_is_cyclic=plain_is_cyclic)
        except QuantityParseError as exc:
            raise ProjectError(f"expects {exc}", file=self.file, key=self.key(name)) from None
        if not math.isfinite(value) or value <= 0.0:
            raise self.error(name, "must be positive and finite", expected="a frequency > 0 (e.g. '2 Hz')", found=raw)
        return value

    def fraction(self, name: str, *, default: float, low: float = 0.0, high: float = 1.0, low_open: bool = True,
                 high_open: bool = True) -> float:
        """A dimensionless key given as a plain number or with a unit ("10 %"), range-checked in either form."""
        if name not in self.data:
            return default
        raw = self.data[name]
        value = (self.quantity(name, "dimensionless", positive=False) if isinstance(raw, str)
                 else self.number(name, default=default))
        lo_bad = value <= low if low_open else value < low
        hi_bad = value >= high if high_open else value > high
        if lo_bad or hi_bad or not math.isfinite(value):
            lo = f"> {low:g}" if low_open else f"≥ {low:g}"
            hi = f"< {high:g}" if high_open else f"≤ {high:g}"
            raise self.error(name, "out of range", expected=f"a number {lo} and {hi} (e.g. 0.1 or \"10 %\")",
                             found=raw)
        return value

    def choice(self, name: str, options: tuple[str, ...], default: str) -> str:
        raw = self.data.get(name, default)
        if not isinstance(raw, str) or raw not in options:
            close = difflib.get_close_matches(str(raw), options, n=1, cutoff=0.5)
            raise ProjectError("invalid value", file=self.file, key=self.key(name),
                               expected="one of " + ", ".join(f"'{o}'" for o in options), found=repr(raw),
                               hint=f"did you mean '{close[0]}'?" if close else None)
        return raw

    def number(self, name: str, *, default=None, low=None, high=None, low_open=True, high_open=False,
               required=False, integer=False):
        if name not in self.data:
            if required:
                raise self.error(name, "missing required value", expected="a number")
            return default
        raw = self.data[name]
        if isinstance(raw, bool) or not isinstance(raw, (int, float)) or (integer and not isinstance(raw, int)):
            raise self.error(name, "wrong type", expected="an integer" if integer else "a plain number",
                             found=raw)
        value = float(raw)
        lo_bad = low is not None and (value <= low if low_open else value < low)
        hi_bad = high is not None and (value >= high if high_open else value > high)
        if lo_bad or hi_bad or not math.isfinite(value):
            lo = "" if low is None else (f"> {low:g}" if low_open else f"≥ {low:g}")
            hi = "" if high is None else (f"< {high:g}" if high_open else f"≤ {high:g}")
            raise self.error(name, "out of range", expected="a number " + " and ".join(x for x in (lo, hi) if x),
                             found=raw)
        return int(raw) if integer else value

    def half_height(self) -> float:
        """H [m] from ``height`` (= 2H) or ``half_height``, whichever the table gives (exactly one)."""
        key = self.one_of("height", "half_height")
        return self.quantity(key, "length") / (2.0 if key == "height" else 1.0)

    def one_of(self, *names: str, required: bool = True) -> str | None:
        present = [n for n in names if n in self.data]
        if len(present) > 1:
            raise ProjectError("conflicting alternatives", file=self.file, key=self.key(present[1]),
                               expected="only one of " + " or ".join(f"'{n}'" for n in names),
                               found="both " + " and ".join(f"'{n}'" for n in present))
        if not present and required:
            raise ProjectError("missing required value", file=self.file, key=self.key(names[0]),
                               expected="one of " + " or ".join(f"'{n}'" for n in names), found="none")
        return present[0] if present else None


def read_document(path) -> tuple[dict, str]:
    """(TOML document, text) of a project file; a :class:`ProjectError` naming the file when it cannot be
    read or is not TOML.  Which kind of structure the document describes is the registry's question
    (:mod:`rockdesign.kinds`)."""
    file = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8-sig")   # a UTF-8 BOM (Windows Notepad) is not content
    except FileNotFoundError:
        raise ProjectError("file not found", file=file, expected="an existing project file (.toml)") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ProjectError(f"cannot read file: {exc}", file=file) from None
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise _toml_error(file, exc) from None
    return raw, text


def _toml_error(path: str, exc: tomllib.TOMLDecodeError) -> ProjectError:
    m = re.search(r"line (\d+)", str(exc))
    return ProjectError(f"malformed TOML: {exc}", file=path, line=int(m.group(1)) if m else None,
                        expected="valid TOML (strings with units in quotes, e.g. height = \"3.0 m\")")


def _parse_analysis(data: dict, file: str, models: tuple[str, ...] | None = None) -> AnalysisSettings:
    """The ``[analysis]`` table in SI.  ``models``: the structural models of the kind's ``model`` key (the planar
    kind's ``auto``, ``block``, …); None reads any string, for the kind to use or refuse."""
    t = _Table(data, "analysis", ANALYSIS_KEYS, file, G_DEFAULT)
    g = DEFAULTS.g
    if t.has("g"):
        raw = t.data["g"]
        if isinstance(raw, str) and re.search(r"(?<![A-Za-z_])g(?![A-Za-z_0-9])", raw):
            raise t.error("g", "g cannot be defined in terms of itself", expected="e.g. g = \"9.81 m/s^2\"", found=raw)
        g = t.quantity("g", "acceleration")
        if not 9.7 <= g <= 9.9:
            raise t.error("g", "out of range", expected="a gravitational acceleration 9.7–9.9 m/s²", found=raw)
    t.gravity = g
    band = DEFAULTS.sdmax_band
    if t.has("sdmax_band"):
        raw = t.data["sdmax_band"]
        if not (isinstance(raw, list) and len(raw) == 2):
            raise t.error("sdmax_band", "wrong type", expected="two periods, e.g. [\"0.05 s\", \"10 s\"]", found=raw)
        try:
            band = tuple(parse_quantity(x, "time") for x in raw)
        except QuantityParseError as exc:
            raise ProjectError(f"expects {exc}", file=file, key="analysis.sdmax_band") from None
        if not 0.0 < band[0] < band[1]:
            raise t.error("sdmax_band", "out of range", expected="0 < T_min < T_max", found=raw)
    damping = t.quantity("sdmax_damping", "dimensionless", default=DEFAULTS.sdmax_damping)
    if not 0.0 < damping < 1.0:
        raise t.error("sdmax_damping", "out of range", expected="0 < ζ < 1 (e.g. \"2 %\")", found=t.data["sdmax_damping"])
    return AnalysisSettings(
        model=t.choice("model", models, DEFAULTS.model) if models is not None else _model_name(t),
        equations=t.choice("equations", EQUATIONS, DEFAULTS.equations),
        rtol=t.number("rtol", default=DEFAULTS.rtol, low=0.0, high=1e-3),
        atol=t.number("atol", default=DEFAULTS.atol, low=0.0, high=1e-3),
        overturn=t.choice("overturn", OVERTURN, DEFAULTS.overturn),
        g=g,
        rest_velocity=t.quantity("rest_velocity", "frequency", default=DEFAULTS.rest_velocity)
        if isinstance(t.data.get("rest_velocity"), str)
        else t.number("rest_velocity", default=DEFAULTS.rest_velocity, low=0.0, high=0.1),
        sdmax_damping=damping,
        sdmax_band=band,
        linearization_tolerance=t.number("linearization_tolerance", default=DEFAULTS.linearization_tolerance,
                                         low=0.0, high=1.0),
        restitution_variation=t.number("restitution_variation", default=DEFAULTS.restitution_variation, low=0.0, high=0.5),
        margin_precision=t.number("margin_precision", default=DEFAULTS.margin_precision, low=0.0, high=0.5),
        margin_max_scale=t.number("margin_max_scale", default=DEFAULTS.margin_max_scale, low=1.0, high=1000.0),
        free_vibration=_free_vibration(t),
        rigid_superstructure_ratio=t.number("rigid_superstructure_ratio", default=DEFAULTS.rigid_superstructure_ratio,
                                            low=0.0),
        scan_rtol=t.number("scan_rtol", default=DEFAULTS.scan_rtol, low=0.0, high=1e-3),
        # a probability limit of 1 (or "150 %") passes every suite: 0 < limit < 1 in every form
        overturn_probability_limit=t.fraction("overturn_probability_limit",
                                              default=DEFAULTS.overturn_probability_limit),
        **_parse_fragility(t),
        **_parse_acceptance(t),
    )


def _model_name(t: _Table) -> str:
    """``model`` of ``[analysis]`` as written (a string), for a kind that names no structural models."""
    raw = t.data.get("model", DEFAULTS.model)
    if not isinstance(raw, str):
        raise t.error("model", "wrong type", expected="a string", found=raw)
    return raw


RISK_CATEGORIES = ("I", "II", "III", "IV")
ACCEPTANCE_METHODS = ("asce7", "binomial")


def _parse_acceptance(t: _Table) -> dict:
    """``risk_category`` and ``acceptance`` of ``[analysis]`` (CONTRACT §6.1, docs/model.md "Verdict")."""
    return {"risk_category": t.choice("risk_category", RISK_CATEGORIES, DEFAULTS.risk_category),
            "acceptance": t.choice("acceptance", ACCEPTANCE_METHODS, DEFAULTS.acceptance),
            "overturn_probability_limit_set": t.has("overturn_probability_limit")}


def _free_vibration(t: _Table) -> float:
    value = t.quantity("free_vibration", "time", default=DEFAULTS.free_vibration, positive=False)
    if value < 0.0:
        raise t.error("free_vibration", "out of range", expected="a time ≥ 0 s analysed after the motion ends "
                      "(e.g. \"10 s\")", found=t.data["free_vibration"])
    return value


QUALITY_RATINGS = ("A", "B", "C", "D")


def _parse_fragility(t: _Table) -> dict:
    """The fragility, collapse-margin and ensemble keys of ``[analysis]`` (SPEC §11, docs/project-file.md)."""
    im = t.choice("fragility_im", ("pga", "sa", "sdmax"), DEFAULTS.fragility_im)
    period = t.quantity("fragility_period", "time")
    if (im == "sa") != (period is not None):
        raise t.error("fragility_period", "needed with fragility_im = \"sa\" and only then",
                      expected="fragility_period = \"1.0 s\" together with fragility_im = \"sa\"",
                      found=f"fragility_im = \"{im}\" and " + ("no fragility_period" if period is None else
                                                            f"fragility_period = {t.data['fragility_period']!r}"))
    raw = t.data.get("quality", {})
    q = _Table(raw, "analysis.quality", ("design_requirements", "test_data", "modeling"), t.file, t.gravity)
    quality = tuple((k, q.choice(k, QUALITY_RATINGS, dict(DEFAULTS.quality)[k])) for k in q.allowed)
    return {"fragility_im": im, "fragility_period": period, "quality": quality,
            "ensemble_size": t.number("ensemble_size", default=DEFAULTS.ensemble_size, low=0, low_open=False, high=1000,
                                      integer=True),
            "seed": t.number("seed", default=DEFAULTS.seed, low=0, low_open=False, integer=True)}


_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")
"""Control characters (NUL, escape, …; not tab or line breaks): TOML can write them ("\\u0000"), no
report, JSON consumer or terminal shows them as text."""


def refuse_control_characters(raw, file: str, path: str = "") -> None:
    """Refuse text with a control character anywhere in the document (``name = "a\\u0000b"`` was written raw
    into report.html and results.json): a :class:`ProjectError` naming the key."""
    items = raw.items() if isinstance(raw, dict) else enumerate(raw)
    for k, v in items:
        key = f"{path}.{k}" if path and isinstance(raw, dict) else (f"{path}[{k}]" if path else str(k))
        if isinstance(v, str):
            m = _CONTROL.search(v)
            if m:
                raise ProjectError("control character in text", file=file, key=key,
                                   expected="printable text (no NUL, escape or other control characters)",
                                   found=f"{ascii(m.group())} at position {m.start()} of {ascii(v)}")
        elif isinstance(v, (dict, list)):
            refuse_control_characters(v, file, key)


DESIGN_SECTION = "design"
"""The table of ``rockdesign design``'s settings every kind's project file may hold (``[design.tolerance]``)."""


def parse_design_table(raw: dict, file: str) -> None:
    """Validate the shape of ``[design]``: only a ``tolerance`` table, whose entries are ``"table.key" = VALUE``
    (or ``table.key = VALUE`` as a nested table), VALUE a string or a number; what VALUE means is read by the design
    command against the keys it varies (:mod:`rockdesign.design_space.tolerance`)."""
    section = raw.get(DESIGN_SECTION)
    if section is None:
        return
    example = '[design.tolerance] with e.g. "podium.width" = "1%" or "podium.width" = "4 mm"'
    if not isinstance(section, dict):
        raise ProjectError("wrong type", file=file, key=DESIGN_SECTION, expected=f"a table: {example}", found=section)
    for k, v in section.items():
        if k != "tolerance":
            raise ProjectError("unknown key", file=file, key=f"design.{k}", expected="design.tolerance",
                               found=k)
        if not isinstance(v, dict):
            raise ProjectError("wrong type", file=file, key="design.tolerance", expected=f"a table: {example}",
                               found=v)
        for table, entry in v.items():
            items = entry.items() if isinstance(entry, dict) else [(None, entry)]
            for name, value in items:
                key = f"design.tolerance.{table}" + (f".{name}" if name is not None else "")
                if "." not in (table if name is None else f"{table}.{name}"):
                    raise ProjectError("not a key of the project file", file=file, key=key,
                                       expected="TABLE.KEY of a key the design chart varies, e.g. \"podium.width\"",
                                       found=table)
                if isinstance(value, bool) or not isinstance(value, (str, int, float)):
                    raise ProjectError("wrong type", file=file, key=key,
                                       expected="a tolerance such as \"1%\" or \"4 mm\"", found=value)


def project_info(raw: dict, file: str, g: float, example: str = "5-storey block") -> dict:
    """The ``[project]`` table (name required, engineer/notes optional; all strings) of any project file; no
    text of the document may hold a control character (:func:`refuse_control_characters`); the shape of the
    ``[design]`` table (:func:`parse_design_table`)."""
    refuse_control_characters(raw, file)
    parse_design_table(raw, file)
    section = raw.get("project", {})
    if not isinstance(section, dict):
        raise ProjectError("wrong type", file=file, key="project", expected="a [project] table with name = \"...\"",
                           found=section)
    info_t = _Table(section, "project", PROJECT_KEYS, file, g)
    if "name" not in section:
        raise ProjectError("missing required value", file=file, key="project.name",
                           expected=f"a project name, e.g. name = \"{example}\"", found="none")
    info = {}
    for k in PROJECT_KEYS:
        if k in info_t.data:
            if not isinstance(info_t.data[k], str):
                raise info_t.error(k, "wrong type", expected="a string", found=info_t.data[k])
            info[k] = info_t.data[k]
    return info


parse_analysis = _parse_analysis
"""The ``[analysis]`` table every kind's project file shares (the name a kind's parser uses)."""
TableReader = _Table
"""The key-tracking reader of one TOML table (the name a kind's parser uses)."""
