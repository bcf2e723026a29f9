"""Amplitude scaling rules for ground motions, and time scaling for similitude (SPEC §5, Eq 6.5).

A rule comes from the project file as ``[excitation] scale = { method = ..., ... }``:

=========== ======================================================================================
method      keys (quantities are strings with units; ``g`` is the project's gravity)
=========== ======================================================================================
factor      ``value`` (number): every record × value.
pga         ``target`` (acceleration, "0.35 g"): each record scaled to PGA = target.
sdmax       ``target`` (length, "0.30 m"); ``damping`` (default 0.02, number or "2 %");
            ``band`` (two periods, default ["0.05 s", "10 s"]): each record scaled to SD_max = target.
uplift      ``multiple`` (number): each record scaled to PGA = multiple × the system's uplift
            acceleration g tan α (passed in by the caller; motions stay independent of structures).
spectrum    ``code`` = "ec8" (``ag``, ``ground_type`` A–E, ``spectrum_type`` 1|2 default 1) or
            "asce7" (``SDS``, ``SD1``, ``TL`` default "8 s"); ``band`` (default ["0.05 s", "4 s"]);
            ``damping`` (default 5 %; EC8 applies η, ASCE 7 only 5 %); ``fit`` = "not-below"
            (default: the smallest factor with the suite's mean PSA ≥ ``fraction`` × target over
            the band; ``fraction`` default 0.9 for EC8 §3.2.3.1.2(4), 1.0 for ASCE 7-16 §16.2.3.1)
            or "mean" (geometric least squares: mean of ln(target/mean PSA) over a log grid = 0);
            ``n_periods`` (default 100). One factor for the whole suite, keeping record-to-record
            variability.
asce7-22    ASCE 7-22 §16.2.3 (SPEC §16, :mod:`rockdesign.motions.asce7_22`): the MCE_R target as ``SMS``,
            ``SM1`` (accelerations, "0.60 g") and ``TL`` (time, default "8 s", stated in reports), or
            ``target`` = a two-column file (``period [s], Sa [g]`` header; path relative to the file
            that names it); optional ``periods`` (two periods, the §16.2.1 period range; default
            derived from the structure by the caller).  One factor per ground motion (pair), applied
            to both components: the suite average of the RotD100 5 % spectra is ≥ 90 % of the target
            over the range.  Applied by :func:`rockdesign.motions.config.resolve_motions`.
=========== ======================================================================================
"""
from __future__ import annotations

import difflib
import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..errors import MotionError, ProjectError
from ..paths import user_path
from ..units import QuantityParseError, parse_quantity
from .design_spectra import EC8_GROUND_TYPES, ASCE7Spectrum, EC8Spectrum
from .targets import MCERSpectrum, TabulatedSpectrum, read_target_spectrum
from .excitation import EXC_CYCLOIDAL_A, EXC_CYCLOIDAL_B, EXC_CYCLOIDAL_C, EXC_NONE, EXC_SAMPLES
from .motion import GroundMotion
from .spectra import DEFAULT_BAND, DEFAULT_DAMPING, motion_spectrum, sd_max

METHOD_KEYS = {
    "factor": {"value"},
    "pga": {"target"},
    "sdmax": {"target", "damping", "band", "n_periods"},
    "uplift": {"multiple"},
    "spectrum": {"code", "ag", "ground_type", "spectrum_type", "SDS", "SD1", "TL", "band", "damping",
                 "fit", "fraction", "n_periods"},
    "asce7-22": {"SMS", "SM1", "TL", "target", "periods"},
}
SPECTRUM_DEFAULT_BAND = (0.05, 4.0)
_KEY_HINTS = {
    ("asce7-22", "band"): "the period range of method 'asce7-22' is periods = [\"0.08 s\", \"3.0 s\"]",
    ("asce7-22", "SDS"): "method 'asce7-22' scales to the MCE_R spectrum: SMS = 1.5 SDS (S_DS = 2/3 S_MS)",
    ("asce7-22", "SD1"): "method 'asce7-22' scales to the MCE_R spectrum: SM1 = 1.5 SD1 (S_D1 = 2/3 S_M1)",
    ("asce7-22", "damping"): "ASCE 7-22 §16.2.3 compares 5 %-damped spectra; the damping is not a choice",
}


@dataclass(frozen=True)
class ScaleRule:
    """A parsed scaling rule (SI).

    Attributes:
        method: factor | pga | sdmax | uplift | spectrum | asce7-22.
        value: the factor (factor), target PGA [m/s²] (pga), target SD_max [m] (sdmax) or the
            multiple of the uplift acceleration (uplift); unused for spectrum.
        damping: damping ratio of SD_max (sdmax) or of the record spectra (spectrum).
        band: period band [s] of SD_max or of the spectrum match.
        spectrum: target design spectrum (spectrum), or the MCE_R target (asce7-22).
        fit: "not-below" or "mean" (spectrum).
        fraction: fraction of the target the mean must not fall below (spectrum, not-below).
        n_periods: periods of the grid in the band.
        periods: the period range [s] the project gave (asce7-22), or None (derived from the structure).
    """

    method: str
    value: float = 1.0
    damping: float = DEFAULT_DAMPING
    band: tuple[float, float] = DEFAULT_BAND
    spectrum: EC8Spectrum | ASCE7Spectrum | MCERSpectrum | TabulatedSpectrum | None = None
    fit: str = "not-below"
    fraction: float = 1.0
    n_periods: int = 400
    periods: tuple[float, float] | None = None

    def describe(self, gravity: float = 9.81) -> str:
        """One sentence for reports saying how the records were scaled."""
        band = f"{self.band[0]:g}–{self.band[1]:g} s"
        if self.method == "factor":
            return f"records multiplied by {self.value:g}"
        if self.method == "pga":
            return f"each record scaled to PGA = {self.value / gravity:.4g} g ({self.value:.4g} m/s²)"
        if self.method == "sdmax":
            return (f"each record scaled to SD_max = {self.value:.4g} m "
                    f"({100 * self.damping:g} % damping, periods {band})")
        if self.method == "uplift":
            return f"each record scaled to PGA = {self.value:g} × the uplift acceleration g tan α"
        if self.method == "asce7-22":
            target = self.spectrum.describe(gravity) if self.spectrum else "?"
            span = (f"{self.periods[0]:g}–{self.periods[1]:g} s (given)" if self.periods
                    else "the structure's §16.2.1 range")
            return (f"ASCE 7-22 §16.2.3: one factor per ground motion (both components), suite-average "
                    f"maximum-direction (RotD100) 5 % spectrum ≥ 90 % of the target over {span}; target: {target}")
        target = self.spectrum.describe() if self.spectrum else "?"
        if self.fit == "mean":
            how = "mean PSA matched in the geometric least-squares sense"
        else:
            how = f"mean PSA not below {100 * self.fraction:g} % of the target"
        return (f"one factor for all records: {how} over {band} "
                f"({100 * self.damping:g} % damping); target: {target}")


MCE_R_MAX_G = 10.0
"""Largest S_MS or S_M1 accepted [g]: a bound against typing errors ("1e400 g" became infinity and the suite was
"conformant" with factors up to 21; "60 g" for "0.60 g"), not a statement about seismicity."""
TL_MAX = 100.0
"""Largest T_L accepted [s] (ASCE 7-22 maps T_L from 4 s to 16 s; a study may push it out, not to infinity)."""
_RANGE_WHY = {"SMS": "an MCE_R spectral acceleration, as \"0.60 g\"",
              "SM1": "an MCE_R spectral acceleration at 1 s, as \"0.30 g\"",
              "TL": "the long-period transition period, ASCE 7-22 maps 4–16 s"}


def _error(message, *, file, key, expected=None, found=None, hint=None):
    return ProjectError(message, file=file, key=key, expected=expected, found=found, hint=hint)


def _quantity(raw, name, dimension, *, file, key, gravity):
    try:
        return parse_quantity(raw, dimension, gravity=gravity)
    except QuantityParseError as exc:
        raise _error("invalid value", file=file, key=f"{key}.{name}", expected=str(exc).split(", got")[0],
                     found=repr(raw)) from None


def _number(raw, name, *, file, key, positive=True):
    if isinstance(raw, bool) or not isinstance(raw, (int, float)):
        raise _error("invalid value", file=file, key=f"{key}.{name}", expected="a number", found=repr(raw))
    value = float(raw)
    if not math.isfinite(value) or (positive and value <= 0.0):
        raise _error("invalid value", file=file, key=f"{key}.{name}", expected="a positive number",
                     found=repr(raw))
    return value


def _damping(raw, *, file, key):
    try:
        value = parse_quantity(raw, "dimensionless")
    except QuantityParseError:
        raise _error("invalid damping", file=file, key=f"{key}.damping",
                     expected="a ratio like 0.02 or '2 %'", found=repr(raw)) from None
    if not 0.0 <= value < 1.0:
        raise _error("invalid damping", file=file, key=f"{key}.damping",
                     expected="a damping ratio in [0, 1) (0.02 = 2 %)", found=repr(raw))
    return value


def _band(raw, *, file, key, gravity):
    if not isinstance(raw, (list, tuple)) or len(raw) != 2:
        raise _error("invalid period band", file=file, key=f"{key}.band",
                     expected='two periods like ["0.05 s", "10 s"]', found=repr(raw))
    lo, hi = (_quantity(v, "band", "time", file=file, key=key, gravity=gravity) for v in raw)
    if not 0.0 < lo < hi:
        raise _error("invalid period band", file=file, key=f"{key}.band",
                     expected="0 < Tmin < Tmax", found=repr(raw))
    return (lo, hi)


def _require(raw, name, method, *, file, key):
    if name not in raw:
        raise _error(f"scale method '{method}' needs '{name}'", file=file, key=f"{key}.{name}",
                     expected=f"{name} = ...", found="nothing")
    return raw[name]


def parse_scale_rule(raw: dict, *, file: str, key: str = "excitation.scale",
                     gravity: float = 9.81) -> ScaleRule:
    """Parse a ``scale = {method = ..., ...}`` table into a :class:`ScaleRule` (SI).

    Args:
        raw: the TOML table.
        file: project or suite file (for messages).
        key: dotted key of the table (for messages).
        gravity: g [m/s²] for accelerations written in g.

    Raises:
        ProjectError: unknown method or key (with the nearest valid one), wrong dimension,
            missing key.
    """
    if not isinstance(raw, dict):
        raise _error("scale must be a table", file=file, key=key,
                     expected='{ method = "pga", target = "0.35 g" } (methods: ' + ", ".join(METHOD_KEYS) + ")",
                     found=repr(raw))
    method = raw.get("method")
    if method not in METHOD_KEYS:
        close = difflib.get_close_matches(str(method), list(METHOD_KEYS), n=1)
        raise _error("unknown scale method", file=file, key=f"{key}.method",
                     expected=" | ".join(METHOD_KEYS), found=repr(method),
                     hint=f"did you mean '{close[0]}'?" if close else None)
    allowed = METHOD_KEYS[method] | {"method"}
    for name in raw:
        if name not in allowed:
            close = difflib.get_close_matches(name, sorted(allowed), n=1)
            hint = _KEY_HINTS.get((method, name)) or (f"did you mean '{close[0]}'?" if close else None)
            raise _error(f"unknown key for scale method '{method}'", file=file, key=f"{key}.{name}",
                         expected=", ".join(sorted(allowed)), found=repr(name), hint=hint)
    opts = dict(file=file, key=key)
    if method == "factor":
        return ScaleRule("factor", value=_number(_require(raw, "value", method, **opts), "value", **opts))
    if method == "pga":
        target = _quantity(_require(raw, "target", method, **opts), "target", "acceleration", gravity=gravity, **opts)
        if target <= 0:
            raise _error("invalid value", key=f"{key}.target", file=file, expected="a positive acceleration",
                         found=repr(raw["target"]))
        return ScaleRule("pga", value=target)
    if method == "sdmax":
        target = _quantity(_require(raw, "target", method, **opts), "target", "length", gravity=gravity, **opts)
        if target <= 0:
            raise _error("invalid value", key=f"{key}.target", file=file, expected="a positive length",
                         found=repr(raw["target"]))
        return ScaleRule("sdmax", value=target,
                         damping=_damping(raw.get("damping", DEFAULT_DAMPING), **opts),
                         band=_band(raw.get("band", list(f"{b} s" for b in DEFAULT_BAND)), gravity=gravity, **opts),
                         n_periods=int(_number(raw.get("n_periods", 400), "n_periods", **opts)))
    if method == "uplift":
        return ScaleRule("uplift", value=_number(_require(raw, "multiple", method, **opts), "multiple", **opts))
    if method == "asce7-22":
        return _parse_asce7_22_rule(raw, gravity=gravity, **opts)
    return _parse_spectrum_rule(raw, gravity=gravity, **opts)


def _parse_asce7_22_rule(raw, *, file, key, gravity) -> ScaleRule:
    """``{ method = "asce7-22", SMS, SM1, TL }`` or ``{ method = "asce7-22", target = "mce_r.csv" }``, with an
    optional ``periods`` (CONTRACT §7.1)."""
    opts = dict(file=file, key=key)
    spectral = [name for name in ("SMS", "SM1", "TL") if name in raw]
    if "target" in raw and spectral:
        raise _error("give the MCE_R target one way", file=file, key=f"{key}.{spectral[0]}",
                     expected='either SMS, SM1 and TL, or target = "mce_r.csv"',
                     found=f"target = {raw['target']!r} and {', '.join(spectral)}")
    if "target" in raw:
        text = raw["target"]
        if not isinstance(text, str) or not text.strip():
            raise _error("invalid target spectrum", file=file, key=f"{key}.target",
                         expected='a file name like "mce_r.csv" (columns period [s], Sa [g])', found=repr(text))
        base = Path(file).expanduser().resolve().parent if file else Path.cwd()
        path = user_path(text.strip(), f"{key}.target", file=file, base=base)
        if not path.is_file():
            raise _error("target spectrum file not found", file=file, key=f"{key}.target",
                         expected="a two-column file (period [s], Sa [g]) relative to this file's folder",
                         found=f"{text!r}: no such file {path}")
        spectrum = read_target_spectrum(path, gravity=gravity, key=f"{key}.target")
    else:
        if "SMS" not in raw or "SM1" not in raw:
            missing = "SMS" if "SMS" not in raw else "SM1"
            raise _error("scale method 'asce7-22' needs the MCE_R target", file=file, key=f"{key}.{missing}",
                         expected='SMS = "0.60 g", SM1 = "0.30 g" (TL = "8 s"), or target = "mce_r.csv"',
                         found="nothing")
        sms = _quantity(raw["SMS"], "SMS", "acceleration", gravity=gravity, **opts)
        sm1 = _quantity(raw["SM1"], "SM1", "acceleration", gravity=gravity, **opts)
        tl = _quantity(raw.get("TL", "8 s"), "TL", "time", gravity=gravity, **opts)
        for name, value, limit, unit in (("SMS", sms, MCE_R_MAX_G * gravity, "g"),
                                         ("SM1", sm1, MCE_R_MAX_G * gravity, "g"), ("TL", tl, TL_MAX, "s")):
            if not (math.isfinite(value) and 0.0 < value <= limit):
                shown = f"{limit / gravity:g} g" if unit == "g" else f"{limit:g} s"
                raise _error("MCE_R parameter out of its physical range", file=file, key=f"{key}.{name}",
                             expected=f"{name} > 0 and {name} ≤ {shown} ({_RANGE_WHY[name]})",
                             found=f"{raw.get(name, '8 s')!r}" + ("" if math.isfinite(value) else " (not finite)"))
        if not sm1 / sms < tl:
            raise _error("invalid MCE_R parameters", file=file, key=f"{key}.TL",
                         expected=f"T_L above T_S = SM1/SMS = {sm1 / sms:.3g} s",
                         found=f"TL = {raw.get('TL', '8 s')!r}")
        spectrum = MCERSpectrum(SMS=sms, SM1=sm1, TL=tl, TL_default="TL" not in raw)
    periods = None
    if "periods" in raw:
        periods = _periods(raw["periods"], file=file, key=key, gravity=gravity)
    return ScaleRule("asce7-22", damping=0.05, spectrum=spectrum, periods=periods)


def _periods(raw, *, file, key, gravity) -> tuple[float, float]:
    if not isinstance(raw, (list, tuple)) or len(raw) != 2:
        raise _error("invalid period range", file=file, key=f"{key}.periods",
                     expected='two periods like ["0.08 s", "3.0 s"]', found=repr(raw))
    lo, hi = (_quantity(v, "periods", "time", file=file, key=key, gravity=gravity) for v in raw)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise _error("invalid period range", file=file, key=f"{key}.periods",
                     expected="0 < lower bound < upper bound", found=repr(raw))
    return (lo, hi)


def _parse_spectrum_rule(raw, *, file, key, gravity) -> ScaleRule:
    opts = dict(file=file, key=key)
    code = str(_require(raw, "code", "spectrum", **opts)).lower().replace(" ", "").replace("-", "")
    damping = _damping(raw.get("damping", 0.05), **opts)
    if code in ("ec8", "eurocode8", "en19981"):
        for name in ("SDS", "SD1", "TL"):
            if name in raw:
                raise _error("key belongs to the ASCE 7 spectrum, not EC8", file=file, key=f"{key}.{name}",
                             expected="ag, ground_type, spectrum_type for code = \"ec8\"", found=name)
        ag = _quantity(_require(raw, "ag", "spectrum", **opts), "ag", "acceleration", gravity=gravity, **opts)
        ground = str(raw.get("ground_type", "")).upper()
        if ground not in EC8_GROUND_TYPES[1]:
            raise _error("invalid ground type", file=file, key=f"{key}.ground_type",
                         expected="A, B, C, D or E", found=repr(raw.get("ground_type")))
        stype = raw.get("spectrum_type", 1)
        if stype not in (1, 2):
            raise _error("invalid spectrum type", file=file, key=f"{key}.spectrum_type",
                         expected="1 or 2", found=repr(stype))
        spectrum = EC8Spectrum(ag=ag, ground_type=ground, spectrum_type=int(stype), damping=damping)
        default_fraction = 0.9
    elif code in ("asce7", "asce716", "asce"):
        for name in ("ag", "ground_type", "spectrum_type"):
            if name in raw:
                raise _error("key belongs to the EC8 spectrum, not ASCE 7", file=file, key=f"{key}.{name}",
                             expected="SDS, SD1, TL for code = \"asce7\"", found=name)
        if abs(damping - 0.05) > 1e-12:
            raise _error("the ASCE 7 spectrum is defined for 5 % damping", file=file, key=f"{key}.damping",
                         expected="0.05 (or leave it out)", found=repr(raw.get("damping")))
        sds = _quantity(_require(raw, "SDS", "spectrum", **opts), "SDS", "acceleration", gravity=gravity, **opts)
        sd1 = _quantity(_require(raw, "SD1", "spectrum", **opts), "SD1", "acceleration", gravity=gravity, **opts)
        tl = _quantity(raw.get("TL", "8 s"), "TL", "time", gravity=gravity, **opts)
        if sds <= 0 or sd1 <= 0 or tl <= 0:
            raise _error("invalid ASCE 7 parameters", file=file, key=key, expected="SDS, SD1, TL > 0",
                         found=f"SDS={raw.get('SDS')!r}, SD1={raw.get('SD1')!r}, TL={raw.get('TL')!r}")
        spectrum = ASCE7Spectrum(SDS=sds, SD1=sd1, TL=tl)
        default_fraction = 1.0
    else:
        raise _error("unknown design-spectrum code", file=file, key=f"{key}.code",
                     expected='"ec8" or "asce7"', found=repr(raw.get("code")))
    fit = raw.get("fit", "not-below")
    if fit not in ("not-below", "mean"):
        raise _error("invalid fit", file=file, key=f"{key}.fit", expected='"not-below" or "mean"',
                     found=repr(fit))
    fraction = _number(raw.get("fraction", default_fraction), "fraction", **opts)
    return ScaleRule("spectrum", damping=damping,
                     band=_band(raw.get("band", [f"{b} s" for b in SPECTRUM_DEFAULT_BAND]), gravity=gravity, **opts),
                     spectrum=spectrum, fit=fit, fraction=fraction,
                     n_periods=int(_number(raw.get("n_periods", 100), "n_periods", **opts)))


def scale_factors(rule: ScaleRule, motions: list[GroundMotion], *, uplift_acceleration: float | None = None,
                  gravity: float = 9.81) -> list[float]:
    """Amplitude factors, one per motion, that realise ``rule``.

    Args:
        rule: the parsed rule.
        motions: the (unscaled) motions; PGA and spectra are of the motions as given.
        uplift_acceleration: the system's uplift acceleration g tan α [m/s²] (SPEC §2, Eq 3.34),
            needed by method ``uplift``.
        gravity: g [m/s²] (only for messages).

    Raises:
        MotionError: a record with zero PGA/SD_max, or ``uplift`` without the uplift acceleration.
    """
    if rule.method == "factor":
        return [rule.value] * len(motions)
    if rule.method == "asce7-22":
        raise MotionError("scale method 'asce7-22' scales ground motions (pairs), not single records",
                          key="excitation.scale.method",
                          expected="rockdesign.motions.config.resolve_motions (or motions.asce7_22.asce7_22_scaling)",
                          found="scale_factors on a list of records")
    if rule.method == "spectrum":
        factor = spectrum_factor(rule, motions)
        return [factor] * len(motions)
    if rule.method == "uplift" and (uplift_acceleration is None or not uplift_acceleration > 0):
        raise MotionError("scale method 'uplift' needs the system's uplift acceleration g tan α",
                          key="excitation.scale.method", expected="a positive uplift acceleration",
                          found=repr(uplift_acceleration))
    factors = []
    for motion in motions:
        if rule.method in ("pga", "uplift"):
            target = rule.value if rule.method == "pga" else rule.value * uplift_acceleration
            current = motion.pga
            what = "PGA"
        else:
            target = rule.value
            current = sd_max(motion, rule.damping, rule.band, rule.n_periods)[0]
            what = "SD_max"
        if not current > 0:
            raise MotionError(f"cannot scale a record with zero {what}", key="excitation.scale",
                              expected=f"a record with {what} > 0", found=f"{motion.name}: {what} = 0")
        factors.append(target / current)
    return factors


def mean_spectrum(motions: list[GroundMotion], periods, damping: float = 0.05) -> np.ndarray:
    """Arithmetic mean PSA [m/s²] of the motions at the periods [s] (damping ratio ``damping``)."""
    return np.mean([motion_spectrum(m, periods, damping)[2] for m in motions], axis=0)


def spectrum_factor(rule: ScaleRule, motions: list[GroundMotion]) -> float:
    """The common factor matching the suite's mean PSA to the rule's design spectrum over the band.

    not-below: f = fraction · max_T (S_target(T)/mean PSA(T)); mean: f = exp(mean_T ln(S_target/mean PSA))
    on a logarithmic grid of ``n_periods`` periods.
    """
    if not motions:
        raise MotionError("spectrum scaling needs at least one record", key="excitation.scale",
                          expected="a non-empty suite", found="no records")
    periods = np.geomspace(rule.band[0], rule.band[1], rule.n_periods)
    mean = mean_spectrum(motions, periods, rule.damping)
    if np.any(mean <= 0):
        raise MotionError("cannot scale: the suite's mean spectrum is zero", key="excitation.scale",
                          expected="records with motion in the band", found="zero spectrum")
    ratio = rule.spectrum.psa(periods) / mean
    if rule.fit == "mean":
        return float(np.exp(np.mean(np.log(ratio))))
    return float(rule.fraction * np.max(ratio))


def similitude_time_factor(model_size: float, prototype_size: float) -> float:
    """Δt_m/Δt_p = √(R_m/R_p): time scale of a record from prototype to model (SPEC §2, Eq 6.5).

    Args:
        model_size: size R (or height) of the model [m].
        prototype_size: the same size of the prototype [m].
    """
    if not (model_size > 0 and prototype_size > 0):
        raise ValueError("sizes must be positive")
    return math.sqrt(model_size / prototype_size)


def time_scaled(motion: GroundMotion, time_factor: float) -> GroundMotion:
    """The motion with time stretched by ``time_factor`` (Δt → factor·Δt), accelerations unchanged (Eq 6.5).

    Records: dt × factor. Pulses: T_p, t_m/t_0 (and the cycloidal span) × factor.
    """
    if not time_factor > 0:
        raise ValueError("time factor must be positive")
    params = motion.params.copy()
    if motion.kind == EXC_SAMPLES:
        params[1] *= time_factor
    elif motion.kind != EXC_NONE:
        params[1] *= time_factor
        params[2] *= time_factor
        if motion.kind in (EXC_CYCLOIDAL_A, EXC_CYCLOIDAL_B, EXC_CYCLOIDAL_C):
            params[4] *= time_factor
    meta = dict(motion.meta, time_scale=motion.meta.get("time_scale", 1.0) * time_factor)
    if motion.kind == EXC_SAMPLES:
        meta["dt"] = float(params[1])
    return replace(motion, params=params, meta=meta)
