"""Project files: TOML with pint quantities → a typed :class:`Project` in SI (CONTRACT §1).

Everything the user wrote is validated here, once: unknown keys (with the nearest valid key
suggested), wrong dimensions, missing or conflicting values, out-of-range numbers and impossible
geometry raise :class:`ProjectError` naming the file, the key, what was expected and what was found.
Nothing is silently changed or dropped.
"""
from __future__ import annotations

import difflib
import hashlib
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .design.geometry import critical_curvature
from .design.mass import SECTIONS, STEEL_TO_CONCRETE_DENSITY, composite_column, section_area
from .errors import ProjectError
from .systems import Column, RockingSystem, Superstructure
from .units import G_DEFAULT, QuantityParseError, parse_quantity

COLUMN_KEYS = ("height", "half_height", "width", "slenderness", "extended_width", "radius", "curvature",
               "mass", "density", "depth", "section", "mass_distribution", "end_plate_thickness",
               "end_plate_density", "restitution")
PODIUM_KEYS = ("columns", "cap_beam_mass") + COLUMN_KEYS
SUPERSTRUCTURE_KEYS = ("mass", "period", "frequency", "damping", "damping_correction")
PROJECT_KEYS = ("name", "engineer", "checker", "job", "client", "notes")
ANALYSIS_KEYS = ("model", "equations", "rtol", "atol", "overturn", "g", "rest_velocity", "sdmax_damping",
                 "sdmax_band", "linearization_tolerance", "restitution_variation", "margin_precision",
                 "margin_max_scale", "free_vibration", "rigid_superstructure_ratio", "scan_rtol",
                 "overturn_probability_limit")
SECTIONS_TOP = ("project", "column", "podium", "superstructure", "excitation", "analysis")
MODELS = ("auto", "rigid-superstructure", "podium-2dof", "block", "frame")
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
    scan_rtol: float = 1e-6
    overturn_probability_limit: float = 0.10
    # fragility, collapse margin and perturbation ensembles (SPEC §11; parsed by _parse_fragility)
    fragility_im: str = "pga"
    fragility_period: float | None = None
    quality: tuple[tuple[str, str], ...] = (("design_requirements", "B"), ("test_data", "B"), ("modeling", "B"))
    ensemble_size: int = 8
    seed: int = 20090601


@dataclass(frozen=True)
class Project:
    """A loaded project: the system in SI, analysis settings, the raw input for the report's echo."""

    path: str
    name: str
    system: RockingSystem
    analysis: AnalysisSettings
    info: dict = field(default_factory=dict)
    excitation_raw: dict | None = None
    raw: dict = field(default_factory=dict)
    source_text: str = ""
    sha256: str = ""
    warnings: tuple[str, ...] = ()


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


def _toml_error(path: str, exc: tomllib.TOMLDecodeError) -> ProjectError:
    m = re.search(r"line (\d+)", str(exc))
    return ProjectError(f"malformed TOML: {exc}", file=path, line=int(m.group(1)) if m else None,
                        expected="valid TOML (strings with units in quotes, e.g. height = \"3.0 m\")")


def load_project(path: str | Path) -> Project:
    """Read and validate a project file (CONTRACT §1) into a :class:`Project` in SI units."""
    path = Path(path)
    file = str(path)
    try:
        text = path.read_text(encoding="utf-8-sig")   # a UTF-8 BOM (Windows Notepad) is not content
    except FileNotFoundError:
        raise ProjectError("file not found", file=file, expected="an existing project file (.toml)") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ProjectError(f"cannot read file: {exc}", file=file) from None
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise _toml_error(file, exc) from None
    return parse_project(raw, file=file, text=text)


def parse_project(raw: dict, *, file: str = "<project>", text: str = "") -> Project:
    """Validate an already-parsed TOML document (see :func:`load_project`)."""
    if "cylinder" in raw or "overturn_tilt" in (raw.get("analysis") if isinstance(raw.get("analysis"), dict) else {}):
        from .cylinder.project import parse_cylinder_project   # the 3D cylinder (thesis Ch. 5)
        return parse_cylinder_project(raw, file=file, text=text)
    for section in raw:
        if section not in SECTIONS_TOP:
            close = difflib.get_close_matches(section, SECTIONS_TOP, n=1, cutoff=0.5)
            raise ProjectError("unknown section", file=file, key=section,
                               expected="sections " + ", ".join(f"[{s}]" for s in SECTIONS_TOP),
                               found=f"[{section}]", hint=f"did you mean [{close[0]}]?" if close else None)
    analysis = _parse_analysis(raw.get("analysis", {}), file)
    g = analysis.g
    info = project_info(raw, file, g)
    if "column" in raw and "podium" in raw:
        raise ProjectError("conflicting sections", file=file, key="podium",
                           expected="exactly one of [column] or [podium]", found="both")
    if "column" not in raw and "podium" not in raw:
        raise ProjectError("missing section", file=file, key="column",
                           expected="exactly one of [column] or [podium]", found="neither")
    kind = "podium" if "podium" in raw else "column"
    table = _Table(raw[kind], kind, PODIUM_KEYS if kind == "podium" else COLUMN_KEYS, file, g)
    column, restitution, rule = _parse_column(table)
    n_columns, cap_beam_mass, superstructure = 1, 0.0, None
    if kind == "podium":
        n_columns = table.number("columns", required=True, integer=True, low=1, low_open=False)
        cap_beam_mass = table.quantity("cap_beam_mass", "mass", required=True)
        if "superstructure" in raw:
            superstructure = _parse_superstructure(_Table(raw["superstructure"], "superstructure",
                                                          SUPERSTRUCTURE_KEYS, file, g))
    elif "superstructure" in raw:
        raise ProjectError("a [superstructure] needs a [podium]", file=file, key="superstructure",
                           expected="[podium] with cap_beam_mass and columns", found="[column]")
    system = RockingSystem(info["name"], kind, column, n_columns, cap_beam_mass, superstructure,
                           restitution, rule, g)
    _check_model_choice(analysis, system, file)
    if "excitation" in raw and not isinstance(raw["excitation"], dict):
        raise ProjectError("must be a table", file=file, key="excitation", expected="an [excitation] table",
                           found=repr(raw["excitation"]))
    if raw.get("excitation") is not None:
        # validated here so that every command (quantities, simulate, check) rejects the same input
        from .motions.config import parse_excitation
        parse_excitation(raw["excitation"], file=file, gravity=g)
    from .validity import validity_warnings
    return Project(file, info["name"], system, analysis, info, raw.get("excitation"), raw, text,
                   hashlib.sha256(text.encode("utf-8")).hexdigest() if text else "",
                   tuple(validity_warnings(system, analysis)))


def _parse_column(t: _Table) -> tuple[Column, float | None, str]:
    hk = t.one_of("height", "half_height")
    H = t.quantity(hk, "length") / (2.0 if hk == "height" else 1.0)
    wk = t.one_of("width", "slenderness")
    if wk == "width":
        B = t.quantity("width", "length") / 2.0
    else:
        tan_a = t.number("slenderness", low=0.0)
        B = tan_a * H
    if B / H >= 1.0:
        raise t.error(wk, "column too squat for rocking", expected="tan α = B/H < 1 (a column taller than wide)",
                      found=t.data[wk])
    section = t.choice("section", SECTIONS, "rectangular")
    # extensions
    extension, B_ext, radius = "none", B, 0.0
    rk = t.one_of("radius", "curvature", required=False)
    if t.has("extended_width"):
        B_ext = t.quantity("extended_width", "length") / 2.0
        if B_ext <= B:
            raise t.error("extended_width", "extensions must widen the base",
                          expected=f"extended_width > width = {2 * B:.6g} m", found=t.data["extended_width"])
        if B_ext / H >= 1.0:
            raise t.error("extended_width", "extended base too wide for rocking",
                          expected="tan α' = B'/H < 1", found=t.data["extended_width"])
        if rk is None:
            extension = "flat"
        else:
            extension = "curved"
            radius = t.quantity("radius", "length") if rk == "radius" else t.number("curvature", low=0.0) * 2.0 * H
            rho = radius / (2.0 * H)
            need = (B_ext - B) / H
            if 2.0 * rho < need * (1.0 - 1e-12):
                raise t.error(rk, "geometrically impossible curved extension (Eq 3.44 needs 2ρ ≥ tan α' − tan α)",
                              expected=f"ρ ≥ {need / 2:.6g} (radius ≥ {need * H:.6g} m)", found=t.data[rk])
    elif rk is not None:
        raise t.error(rk, "curved extensions need their total base width",
                      expected="extended_width (2B') together with radius or curvature", found=t.data[rk])
    # mass distribution λ
    lk = t.one_of("mass_distribution", "end_plate_thickness", required=False)
    plate = 0.0
    ratio = STEEL_TO_CONCRETE_DENSITY
    if t.has("end_plate_density"):
        if lk != "end_plate_thickness":
            raise t.error("end_plate_density", "only used with end plates", expected="end_plate_thickness too",
                          found=t.data["end_plate_density"])
        if not t.has("density"):
            raise t.error("end_plate_density", "the plate density needs the column density",
                          expected="density (of the column body) too", found=t.data["end_plate_density"])
        ratio = t.quantity("end_plate_density", "density") / t.quantity("density", "density")
    if lk == "end_plate_thickness":
        plate = t.quantity("end_plate_thickness", "length")
        if plate >= H:
            raise t.error("end_plate_thickness", "end plates thicker than half the column",
                          expected=f"a thickness < H = {H:.6g} m", found=t.data["end_plate_thickness"])
        lam, core_height = composite_column(section, B, H, plate, ratio)
    else:
        lam = t.number("mass_distribution", low=0.0, high=1.0, default=None)
        core_height = 2.0 * H
        if lam is None:
            raise t.error("mass_distribution", "missing required value",
                          expected="mass_distribution = λ (1/3 for a homogeneous rectangle) or end_plate_thickness",
                          found="none")
    # mass
    if t.has("mass"):
        if t.has("density") and not t.has("end_plate_density"):
            raise t.error("density", "conflicting alternatives", expected="only one of 'mass' or 'density'",
                          found="both 'mass' and 'density'")
        if t.has("depth"):
            raise t.error("depth", "only used to compute the mass from density", expected="density and depth "
                          "instead of mass", found=t.data["depth"])
        mass = t.quantity("mass", "mass")
    elif t.has("density"):
        rho_c = t.quantity("density", "density")
        depth = t.quantity("depth", "length", required=(section == "rectangular"))
        if section == "circular" and depth is not None:
            raise t.error("depth", "a circular section has no depth", expected="no depth (diameter = width)",
                          found=t.data["depth"])
        mass = rho_c * section_area(section, B, depth) * core_height
    else:
        raise t.error("mass", "missing required value", expected="mass, or density with depth", found="none")
    # restitution
    rest = t.data.get("restitution", "theory")
    restitution, rule = None, "theory"
    if isinstance(rest, str):
        if rest not in RESTITUTION_RULES:
            raise t.error("restitution", "invalid value",
                          expected="'theory', 'thesis-eq-3.39' or a measured number in (0, 1]", found=rest)
        rule = rest
        if rule == "thesis-eq-3.39" and extension != "flat":
            raise t.error("restitution", "'thesis-eq-3.39' is the printed flat-extension formula",
                          expected="flat extensions (extended_width without radius)", found=rest)
    else:
        restitution = t.number("restitution", low=0.0, high=1.0)
        rule = "measured"
    return Column(H, B, mass, lam, extension, B_ext, radius), restitution, rule


def _parse_superstructure(t: _Table) -> Superstructure:
    mass = t.quantity("mass", "mass", required=True)
    pk = t.one_of("period", "frequency")
    if pk == "period" and t.data["period"] == "rigid":
        for k in ("damping", "damping_correction"):
            if t.has(k):
                raise t.error(k, "not used with a rigid superstructure", expected="no damping for period = \"rigid\"",
                              found=t.data[k])
        return Superstructure(mass, math.inf, 0.0, False)
    if pk == "period":
        omega = 2.0 * math.pi / t.quantity("period", "time")
    else:
        omega = 2.0 * math.pi * t.quantity("frequency", "frequency")
    if not t.has("damping"):
        raise t.error("damping", "missing required value", expected="damping = \"2 %\" (fixed-base ζ_s)",
                      found="none")
    zeta = t.quantity("damping", "dimensionless", positive=False)
    if not 0.0 <= zeta < 1.0:
        raise t.error("damping", "out of range", expected="0 ≤ ζ_s < 1 (e.g. \"2 %\")", found=t.data["damping"])
    corr = t.data.get("damping_correction", True)
    if not isinstance(corr, bool):
        raise t.error("damping_correction", "wrong type", expected="true or false", found=corr)
    return Superstructure(mass, omega, zeta, corr)


def _parse_analysis(data: dict, file: str) -> AnalysisSettings:
    t = _Table(data, "analysis", ANALYSIS_KEYS, file, G_DEFAULT)
    g = G_DEFAULT
    if t.has("g"):
        raw = t.data["g"]
        if isinstance(raw, str) and re.search(r"(?<![A-Za-z_])g(?![A-Za-z_0-9])", raw):
            raise t.error("g", "g cannot be defined in terms of itself", expected="e.g. g = \"9.81 m/s^2\"", found=raw)
        g = t.quantity("g", "acceleration")
        if not 9.7 <= g <= 9.9:
            raise t.error("g", "out of range", expected="a gravitational acceleration 9.7–9.9 m/s²", found=raw)
    t.gravity = g
    band = (0.05, 10.0)
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
    damping = t.quantity("sdmax_damping", "dimensionless", default=0.02)
    if not 0.0 < damping < 1.0:
        raise t.error("sdmax_damping", "out of range", expected="0 < ζ < 1 (e.g. \"2 %\")", found=t.data["sdmax_damping"])
    return AnalysisSettings(
        model=t.choice("model", MODELS, "auto"),
        equations=t.choice("equations", EQUATIONS, "auto"),
        rtol=t.number("rtol", default=1e-8, low=0.0, high=1e-3),
        atol=t.number("atol", default=1e-10, low=0.0, high=1e-3),
        overturn=t.choice("overturn", OVERTURN, "static"),
        g=g,
        rest_velocity=t.quantity("rest_velocity", "frequency", default=5e-4) if isinstance(
            t.data.get("rest_velocity"), str) else t.number("rest_velocity", default=5e-4, low=0.0, high=0.1),
        sdmax_damping=damping,
        sdmax_band=band,
        linearization_tolerance=t.number("linearization_tolerance", default=0.02, low=0.0, high=1.0),
        restitution_variation=t.number("restitution_variation", default=0.02, low=0.0, high=0.5),
        margin_precision=t.number("margin_precision", default=0.01, low=0.0, high=0.5),
        margin_max_scale=t.number("margin_max_scale", default=8.0, low=1.0, high=1000.0),
        free_vibration=_free_vibration(t),
        rigid_superstructure_ratio=t.number("rigid_superstructure_ratio", default=10.0, low=0.0),
        scan_rtol=t.number("scan_rtol", default=1e-6, low=0.0, high=1e-3),
        overturn_probability_limit=t.quantity("overturn_probability_limit", "dimensionless", default=0.10)
        if isinstance(t.data.get("overturn_probability_limit"), str)
        else t.number("overturn_probability_limit", default=0.10, low=0.0, high=1.0),
        **_parse_fragility(t),
    )


def _free_vibration(t: _Table) -> float:
    value = t.quantity("free_vibration", "time", default=10.0, positive=False)
    if value < 0.0:
        raise t.error("free_vibration", "out of range", expected="a time ≥ 0 s analysed after the motion ends "
                      "(e.g. \"10 s\")", found=t.data["free_vibration"])
    return value


ANALYSIS_KEYS += ("fragility_im", "fragility_period", "quality", "ensemble_size", "seed")
QUALITY_RATINGS = ("A", "B", "C", "D")


def _parse_fragility(t: _Table) -> dict:
    """The fragility, collapse-margin and ensemble keys of ``[analysis]`` (SPEC §11, docs/project-file.md)."""
    im = t.choice("fragility_im", ("pga", "sa", "sdmax"), "pga")
    period = t.quantity("fragility_period", "time")
    if (im == "sa") != (period is not None):
        raise t.error("fragility_period", "needed with fragility_im = \"sa\" and only then",
                      expected="fragility_period = \"1.0 s\" together with fragility_im = \"sa\"",
                      found=f"fragility_im = \"{im}\" and " + ("no fragility_period" if period is None else
                                                            f"fragility_period = {t.data['fragility_period']!r}"))
    raw = t.data.get("quality", {})
    q = _Table(raw, "analysis.quality", ("design_requirements", "test_data", "modeling"), t.file, t.gravity)
    quality = tuple((k, q.choice(k, QUALITY_RATINGS, "B")) for k in q.allowed)
    return {"fragility_im": im, "fragility_period": period, "quality": quality,
            "ensemble_size": t.number("ensemble_size", default=8, low=0, low_open=False, high=1000, integer=True),
            "seed": t.number("seed", default=20090601, low=0, low_open=False, integer=True)}


def project_info(raw: dict, file: str, g: float, example: str = "5-storey block") -> dict:
    """The ``[project]`` table (name required, engineer/notes optional; all strings) of any project file."""
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


def _check_model_choice(analysis: AnalysisSettings, system: RockingSystem, file: str) -> None:
    model = analysis.model
    ok = {
        "auto": True,
        "block": system.kind == "column",
        "frame": system.kind == "podium" and system.superstructure is None,
        "rigid-superstructure": system.kind == "podium" and system.superstructure is not None,
        "podium-2dof": system.has_elastic_superstructure,
    }[model]
    if not ok:
        expected = {
            "block": "a [column] project",
            "frame": "a [podium] without [superstructure]",
            "rigid-superstructure": "a [podium] with a [superstructure]",
            "podium-2dof": "a [podium] with an elastic [superstructure] (period or frequency, not \"rigid\")",
        }[model]
        raise ProjectError(f"model '{model}' does not fit this system", file=file, key="analysis.model",
                           expected=expected, found=f"a {system.kind}" + (
                               " with a superstructure" if system.superstructure is not None else ""))


def critical_curvature_of(column: Column) -> float:
    """ρc of a column with extensions (Eq 3.55); convenience for templates and warnings."""
    return critical_curvature(column.tan_alpha, column.tan_alpha_ext)
