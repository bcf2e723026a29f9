"""The ``[cylinder]`` section of a project file and ``[analysis] overturn_tilt`` (thesis Ch. 5).

    [cylinder]
    height = "3.0 m"              # 2H               | or half_height = H
    diameter = "0.6 m"            # 2B               | or slenderness = tan(alpha)
    mass = "2.0 t"                # or density (mass = density · π B² · 2H)
    contact = "rigid"             # rigid | spring-dashpot
    contact_frequency = "200 rad/s"   # omega_n (spring-dashpot only; default 200 rad/s, Eq 5.32)
    contact_damping = 0.5             # zeta (spring-dashpot only; default 0.5)
    [analysis]
    overturn_tilt = 1.5           # theta_ot / alpha (default 1.5, Sec 5.5.1)

Everything that does not fit a cylinder raises :class:`~rockdesign.errors.ProjectError` naming the
file, the key, what was expected and what was found: a ``[cylinder]`` together with ``[column]``,
``[podium]`` or ``[superstructure]``, keys of the planar column (``width``, ``extended_width``,
``radius``, ``mass_distribution``...), spring–dashpot keys on a rigid contact, and planar analysis
keys (``model``, ``equations``, ``overturn``...).
"""
from __future__ import annotations

import difflib
import hashlib
import math
from dataclasses import dataclass

from ..errors import ProjectError
from ..project_tables import Project, _parse_analysis, _Table, project_info
from ..units import QuantityParseError, parse_quantity
from .system import (CONTACTS, DEFAULT_CONTACT_DAMPING, DEFAULT_CONTACT_FREQUENCY, DEFAULT_OVERTURN_TILT,
                     Cylinder)

CYLINDER_KEYS = ("height", "half_height", "diameter", "slenderness", "mass", "density", "contact",
                 "contact_frequency", "contact_damping")
PLANAR_ONLY_KEYS = ("width", "extended_width", "radius", "curvature", "depth", "section", "mass_distribution",
                    "end_plate_thickness", "end_plate_density", "restitution", "columns", "cap_beam_mass")
PLANAR_ANALYSIS_KEYS = ("model", "equations", "overturn", "linearization_tolerance", "restitution_variation",
                        "rigid_superstructure_ratio")
PLANAR_SECTIONS = ("column", "podium", "superstructure")
EXCITATION_KEYS = ("design_pga", "suites", "scale", "records_dir")
SCALE_METHODS = ("resultant_pga", "factor")
DEFAULT_SUITE = "p695-farfield-pairs"


def claims(raw: dict) -> bool:
    """True when a TOML document describes a cylinder: a ``[cylinder]`` section, or ``[analysis]
    overturn_tilt`` (which only a cylinder has; the parser then says what is missing)."""
    analysis = raw.get("analysis")
    return "cylinder" in raw or "overturn_tilt" in (analysis if isinstance(analysis, dict) else {})


@dataclass(frozen=True)
class CylinderExcitation:
    """The ``[excitation]`` table of a cylinder project, parsed at load (SI).

    Attributes:
        suites: suites of record pairs (``rockdesign.cylinder.pairs.PAIR_SUITES``), in order.
        method: ``resultant_pga`` (each pair scaled to a peak resultant ground acceleration, Table 5.4)
            or ``factor`` (every pair multiplied by one factor).
        target: the resultant PGA [m/s²] (``resultant_pga``) or the factor [-] (``factor``).
        records_dir: folder of the user's PEER AT2 files for ``simulate`` motions, or None.
        default_used: True when neither ``scale`` nor ``design_pga`` was given (1.5 g tan α, Table 5.4's
            level relative to uplift).
    """

    suites: tuple[str, ...] = (DEFAULT_SUITE,)
    method: str = "resultant_pga"
    target: float = 0.0
    records_dir: str | None = None
    default_used: bool = True

    def factor(self, resultant_pga: float) -> float:
        """The factor on a pair whose peak resultant ground acceleration is ``resultant_pga`` [m/s²]."""
        return self.target / resultant_pga if self.method == "resultant_pga" else self.target

    def as_json(self) -> dict:
        """``summary.scaling`` of results.json."""
        return {"method": self.method, "target" if self.method == "resultant_pga" else "value": self.target}

    def scaling_block(self, records, g: float) -> dict:
        """``excitation.scaling`` of results.json (CONTRACT §7.1) for the check's ``records`` (each with
        ``ground_motion`` and ``scale``): one factor per pair, not ASCE 7-22 §16.2 scaling, no target to judge
        it against (:func:`rockdesign.motions.scaling_report.pair_suite_block`); ``g`` [m/s²] for the words."""
        from ..motions.scaling_report import pair_suite_block
        how = (f"scaled pair by pair to a peak resultant ground acceleration of {self.target / g:.3g} g (thesis "
               "Table 5.4)" if self.method == "resultant_pga" else f"multiplied by {self.target:g}")
        return pair_suite_block(self.method, how, {o.ground_motion: o.scale for o in records})


def parse_cylinder_excitation(raw: dict | None, *, file: str, g: float, tan_alpha: float) -> CylinderExcitation:
    """The typed ``[excitation]`` of a cylinder project (every command validates it at load).

    ``scale = { method = "resultant_pga", target = "0.3 g" }`` or ``{ method = "factor", value = 1.2 }``;
    ``design_pga`` alone means resultant-PGA scaling to it.  Default: resultant PGA 1.5 g tan α (the
    thesis's Table 5.4 level relative to uplift)."""
    raw = raw or {}
    if not isinstance(raw, dict):
        raise ProjectError("must be a table", file=file, key="excitation", expected="an [excitation] table",
                           found=repr(raw))
    for key in raw:
        if key not in EXCITATION_KEYS:
            raise ProjectError("unknown key for a cylinder", file=file, key=f"excitation.{key}",
                               expected="one of " + ", ".join(EXCITATION_KEYS), found=f"'{key}'")
    suites = raw.get("suites", [DEFAULT_SUITE])
    if not isinstance(suites, list) or not all(isinstance(s, str) for s in suites) or not suites:
        raise ProjectError("wrong type", file=file, key="excitation.suites", expected="a list of suite names",
                           found=repr(suites))
    from .pairs import PAIR_SUITES          # (numba under it: loaded once the keys above are valid)
    for s in suites:
        if s not in PAIR_SUITES:
            raise ProjectError("a cylinder needs suites of record pairs", file=file, key="excitation.suites",
                               expected="one of " + ", ".join(PAIR_SUITES), found=repr(s))
    records_dir = raw.get("records_dir")
    if records_dir is not None and not isinstance(records_dir, str):
        raise ProjectError("wrong type", file=file, key="excitation.records_dir", expected="a folder name",
                           found=repr(records_dir))

    def accel(value, key):
        try:
            v = parse_quantity(value, "acceleration", gravity=g)
        except QuantityParseError as exc:
            raise ProjectError(f"expects {exc}", file=file, key=key) from None
        if not v > 0:
            raise ProjectError("must be positive", file=file, key=key, expected="an acceleration > 0", found=repr(value))
        return v

    def typed(method, target, default_used=False):
        return CylinderExcitation(tuple(suites), method, float(target), records_dir, default_used)

    if "scale" in raw:
        rule = raw["scale"]
        if not isinstance(rule, dict) or rule.get("method") not in SCALE_METHODS:
            raise ProjectError("invalid scaling for a cylinder", file=file, key="excitation.scale",
                               expected='{ method = "resultant_pga", target = "0.3 g" } or { method = "factor", '
                                        'value = 1.2 }', found=repr(rule))
        if rule["method"] == "resultant_pga":
            if set(rule) != {"method", "target"}:
                raise ProjectError("resultant_pga scaling takes a target", file=file, key="excitation.scale",
                                   expected='{ method = "resultant_pga", target = "0.3 g" }', found=repr(rule))
            return typed("resultant_pga", accel(rule["target"], "excitation.scale.target"))
        value = rule.get("value")
        if set(rule) != {"method", "value"} or isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not value > 0:
            raise ProjectError("factor scaling takes a positive value", file=file, key="excitation.scale",
                               expected='{ method = "factor", value = 1.2 }', found=repr(rule))
        return typed("factor", value)
    if "design_pga" in raw:
        return typed("resultant_pga", accel(raw["design_pga"], "excitation.design_pga"))
    return typed("resultant_pga", 1.5 * g * tan_alpha, default_used=True)


def parse_cylinder_project(raw: dict, *, file: str = "<project>", text: str = ""):
    """Validate a project with a ``[cylinder]`` section into a :class:`~rockdesign.planar.project.Project`.

    The ``[analysis]`` table is validated by the planar loader, except ``overturn_tilt`` (read here)
    and the planar keys, which are refused.
    """
    sections = ("project", "cylinder", "excitation", "analysis", "design")
    for section in raw:
        if section not in sections and section not in PLANAR_SECTIONS:
            close = difflib.get_close_matches(section, sections, n=1, cutoff=0.5)
            raise ProjectError("unknown section", file=file, key=section,
                               expected="sections " + ", ".join(f"[{s}]" for s in sections),
                               found=f"[{section}]", hint=f"did you mean [{close[0]}]?" if close else None)
    analysis_raw = raw.get("analysis", {})
    if isinstance(analysis_raw, dict):
        analysis = _parse_analysis({k: v for k, v in analysis_raw.items() if k != "overturn_tilt"}, file)
    else:
        analysis = _parse_analysis(analysis_raw, file)   # raises: not a table
    if "cylinder" not in raw:
        raise ProjectError("overturn_tilt applies to a [cylinder] only", file=file, key="analysis.overturn_tilt",
                           expected="a [cylinder] section (planar columns use [analysis] overturn)",
                           found=f"[{'podium' if 'podium' in raw else 'column'}]")
    for section in PLANAR_SECTIONS:
        if section in raw:
            raise ProjectError("conflicting sections", file=file, key=section,
                               expected="a [cylinder] alone (a cylinder is not a planar column, frame or podium)",
                               found=f"[cylinder] and [{section}]")
    for key in PLANAR_ANALYSIS_KEYS:
        if key in analysis_raw:
            raise ProjectError("a planar analysis key does not apply to a cylinder", file=file, key=f"analysis.{key}",
                               expected="for a cylinder: rtol, atol, g, rest_velocity, free_vibration, overturn_tilt",
                               found=f"{key} = {analysis_raw[key]!r}")
    for key in ("fragility_im", "fragility_period"):
        if key in analysis_raw:
            raise ProjectError("the fragility of a cylinder is in the resultant PGA", file=file,
                               key=f"analysis.{key}",
                               expected="no fragility_im or fragility_period for a [cylinder]: a record pair is "
                                        "scaled by its resultant PGA (Table 5.4), the intensity of its fragility",
                               found=f"{key} = {analysis_raw[key]!r}")
    data = raw["cylinder"]
    if isinstance(data, dict):
        for key in data:
            if key in PLANAR_ONLY_KEYS:
                raise ProjectError("a planar-column key does not apply to a cylinder", file=file,
                                   key=f"cylinder.{key}", expected="one of " + ", ".join(CYLINDER_KEYS),
                                   found=f"'{key}'", hint="the cylinder's inertia and contact follow from its "
                                   "height and diameter (Eqs 5.20-5.21)" if key == "mass_distribution" else None)
    t = _Table(data, "cylinder", CYLINDER_KEYS, file, analysis.g)
    info = project_info(raw, file, analysis.g, example="museum column")
    system = _parse_cylinder(t, info["name"], analysis.g, _overturn_tilt(analysis_raw, file))
    excitation = raw.get("excitation")
    # parsed once, here: every command (quantities, simulate, check) rejects the same input
    typed = parse_cylinder_excitation(excitation, file=file, g=analysis.g, tan_alpha=system.tan_alpha)
    return Project(file, info["name"], system, analysis, info, excitation, raw, text,
                   hashlib.sha256(text.encode("utf-8")).hexdigest() if text else "", (), typed)


def _overturn_tilt(analysis_raw: dict, file: str) -> float:
    if "overturn_tilt" not in analysis_raw:
        return DEFAULT_OVERTURN_TILT
    raw = analysis_raw["overturn_tilt"]
    if isinstance(raw, bool) or not isinstance(raw, (int, float)) or not math.isfinite(raw):
        raise ProjectError("wrong type", file=file, key="analysis.overturn_tilt",
                           expected="a plain number θ_ot/α, e.g. 1.5", found=repr(raw))
    if raw < 1.0:
        raise ProjectError("out of range", file=file, key="analysis.overturn_tilt",
                           expected="θ_ot/α ≥ 1 (a cylinder tilted below α always comes back)", found=repr(raw))
    return float(raw)


def _parse_cylinder(t, name: str, g: float, overturn_tilt: float) -> Cylinder:
    H = t.half_height()
    wk = t.one_of("diameter", "slenderness")
    if wk == "diameter":
        B = t.quantity("diameter", "length") / 2.0
    else:
        B = t.number("slenderness", low=0.0) * H
    if B / H >= 1.0:
        raise t.error(wk, "cylinder too squat for rocking", expected="tan α = B/H < 1 (taller than wide)",
                      found=t.data[wk])
    alpha = math.atan2(B, H)
    if overturn_tilt * alpha > math.pi / 2:
        raise ProjectError("out of range", file=t.file, key="analysis.overturn_tilt",
                           expected=f"θ_ot = overturn_tilt·α ≤ π/2, i.e. overturn_tilt ≤ {math.pi / 2 / alpha:.6g} "
                           f"for α = {alpha:.6g} rad", found=repr(overturn_tilt))
    mk = t.one_of("mass", "density")
    if mk == "mass":
        mass = t.quantity("mass", "mass")
    else:
        mass = t.quantity("density", "density") * math.pi * B * B * 2.0 * H
    contact = t.choice("contact", CONTACTS, "rigid")
    if contact == "rigid":
        for key in ("contact_frequency", "contact_damping"):
            if t.has(key):
                raise t.error(key, "only used with a spring-dashpot contact",
                              expected="contact = \"spring-dashpot\" (or no " + key + ")", found=t.data[key])
        return Cylinder(name, H, B, mass, "rigid", DEFAULT_CONTACT_FREQUENCY, DEFAULT_CONTACT_DAMPING, g,
                        overturn_tilt)
    omega = DEFAULT_CONTACT_FREQUENCY
    if t.has("contact_frequency"):
        omega = t.angular_frequency("contact_frequency", plain_is_cyclic=False)   # "30 Hz" is ω_n = 2π·30/s
    zeta = DEFAULT_CONTACT_DAMPING
    if t.has("contact_damping"):
        raw = t.data["contact_damping"]
        zeta = (t.quantity("contact_damping", "dimensionless", positive=False) if isinstance(raw, str)
                else t.number("contact_damping", low=0.0, low_open=False))
        if not 0.0 <= zeta:
            raise t.error("contact_damping", "out of range", expected="ζ ≥ 0", found=raw)
    return Cylinder(name, H, B, mass, "spring-dashpot", omega, zeta, g, overturn_tilt)
