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

from .design.mass import SECTIONS, STEEL_TO_CONCRETE_DENSITY, composite_column, section_area
from ..errors import ProjectError
from .system import Column, RockingSystem, Superstructure
from ..project_tables import (ANALYSIS_KEYS, RESTITUTION_RULES, AnalysisSettings, Project,  # noqa: F401 (re-exported)
                             _parse_analysis, _Table, project_info)
from .validity import validity_warnings

MODELS = ("auto", "rigid-superstructure", "podium-2dof", "block", "frame")
"""The structural models of ``[analysis] model`` (docs/project-file.md; chosen in :mod:`rockdesign.planar.dynamics.model`)."""

SECTIONS_TOP = ("project", "column", "podium", "superstructure", "excitation", "analysis", "design")

COLUMN_KEYS = ("height", "half_height", "width", "slenderness", "extended_width", "radius", "curvature",
               "mass", "density", "depth", "section", "mass_distribution", "end_plate_thickness",
               "end_plate_density", "restitution")
PODIUM_KEYS = ("columns", "cap_beam_mass") + COLUMN_KEYS
SUPERSTRUCTURE_KEYS = ("mass", "period", "frequency", "damping", "damping_correction")


def parse_planar_project(raw: dict, *, file: str = "<project>", text: str = "") -> Project:
    """Validate a TOML document of a planar structure ([column] or [podium]) into a :class:`Project`.

    Which parser reads a document is chosen by the registry of kinds of structure
    (:mod:`rockdesign.kinds`; ``rd.load_project`` / ``rd.parse_project``)."""
    for section in raw:
        if section not in SECTIONS_TOP:
            close = difflib.get_close_matches(section, SECTIONS_TOP, n=1, cutoff=0.5)
            raise ProjectError("unknown section", file=file, key=section,
                               expected="sections " + ", ".join(f"[{s}]" for s in SECTIONS_TOP),
                               found=f"[{section}]", hint=f"did you mean [{close[0]}]?" if close else None)
    analysis = _parse_analysis(raw.get("analysis", {}), file, MODELS)
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
    # parsed once, here, so that every command (quantities, simulate, check) rejects the same input and
    # the check consumes the typed table; last, and its module loaded only now: a mistake in the tables above is
    # reported before the ground-motion modules (and numba under them) load (tests/cli/test_startup.py)
    from ..motions.config import parse_excitation
    excitation = (parse_excitation(raw["excitation"], file=file, gravity=g)
                  if raw.get("excitation") is not None else None)
    return Project(file, info["name"], system, analysis, info, raw.get("excitation"), raw, text,
                   hashlib.sha256(text.encode("utf-8")).hexdigest() if text else "",
                   tuple(validity_warnings(system, analysis)), excitation)


def _parse_column(t: _Table) -> tuple[Column, float | None, str]:
    H = t.half_height()
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
        omega = t.angular_frequency("frequency", plain_is_cyclic=True)    # "2 Hz" cyclic, "12.6 rad/s" angular
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


