"""Bidirectional ground motions (ü_gx, ü_gy) for the 3D cylinder (thesis Ch. 5).

Motion strings (``--motion``), one pair each:

    record:p695-ff/11[,scale=1.2|resultant_pga=0.3g][,azimuth=30deg]   components a along x, b along y
    files:X.AT2,Y.AT2[,scale=…|resultant_pga=…][,azimuth=…]             two record files (x, then y)
    record:p695-ff/11a[,…]  file:X.AT2[,…]                              one component along x (planar)
    ricker-anti:ap=0.38g,Tp=0.95s[,azimuth=30deg]                       a pulse along an azimuth
    free:theta0=0.1rad,phidot0=1e-3rad/s[,thetadot0=…,phi0=…]          free vibration

``azimuth=β`` rotates the pair counter-clockwise by β (x toward y): ü_gx' = ü_gx cosβ − ü_gy sinβ,
ü_gy' = ü_gx sinβ + ü_gy cosβ; a pulse acts along (cosβ, sinβ).  ``resultant_pga=`` scales the pair
by one factor so that max √(ü_gx² + ü_gy²) reaches the target (thesis Table 5.4 scaling, Eq 5.24).
Both components of a record pair are piecewise linear on the same time step; a shorter component is
zero after its end (as every record is).  One-directional motions (a pulse, a single component) with
no initial spin are planar: the cylinder rocks as Housner's cylinder (Eq 5.26).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from ..errors import MotionError
from ..units import QuantityParseError, parse_quantity
from ..motions.excitation import EXC_NONE, EXC_SAMPLES, excitation_end, ground_acceleration_array
from ..motions.motion import PULSE_KINDS, GroundMotion, no_motion
from ..motions.parse import finite, record_file_only, scale_factor

_EMPTY = np.zeros(0)
_PAIR_ID = re.compile(r"^(p695-(?:ff|nfp|nfnp))/(\d+)$", re.I)
PAIR_SUITES = {
    "p695-farfield-pairs": ("p695-ff", range(1, 23)),
    "p695-nearfield-pulse-pairs": ("p695-nfp", range(1, 15)),
    "p695-nearfield-nopulse-pairs": ("p695-nfnp", range(15, 29)),
}
"""Suites of record pairs: the FEMA P695 sets with both horizontal components of each record."""


@dataclass(frozen=True, eq=False)
class MotionPair:
    """Two horizontal ground accelerations as the cylinder kernel consumes them (SI).

    Records: ``kind`` = samples, ``params`` = [scale, dt], ``x``/``y`` the component samples [m/s²],
    ``direction`` = (1, 1).  Pulses: the pulse's ``kind``/``params``, empty samples and the unit
    ``direction`` (cosβ, sinβ) of the pulse.  ``planar``: one-directional (no ü_gy after rotation to
    the pulse line, or a single component).
    """

    name: str
    kind: int
    params: np.ndarray
    x: np.ndarray = field(default_factory=lambda: _EMPTY)
    y: np.ndarray = field(default_factory=lambda: _EMPTY)
    direction: tuple[float, float] = (1.0, 1.0)
    planar: bool = False
    meta: dict = field(default_factory=dict)

    @property
    def duration(self) -> float:
        """Time [s] after which both components are zero."""
        return float(excitation_end(self.kind, self.params, self.x))

    @property
    def is_record(self) -> bool:
        return self.kind == EXC_SAMPLES

    @property
    def dt(self) -> float:
        return float(self.params[1]) if self.is_record else 0.0

    @property
    def scale(self) -> float:
        return float(self.params[0]) if self.is_record else 1.0

    def acceleration(self, t) -> tuple[np.ndarray, np.ndarray]:
        """(ü_gx, ü_gy) [m/s²] at times t [s], exactly as the kernel sees them."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        dx, dy = self.direction
        return (dx * ground_acceleration_array(t, self.kind, self.params, self.x),
                dy * ground_acceleration_array(t, self.kind, self.params, self.y if self.is_record else self.x))

    def sampled(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(t, ü_gx, ü_gy) on the record's samples or on T_p/200 for pulses."""
        if self.kind == EXC_NONE:
            t = np.zeros(1)
        elif self.is_record:
            t = np.arange(self.x.size) * self.dt
        else:
            t = np.arange(0.0, self.duration + 1e-12, self.params[1] / 200.0)
        ax, ay = self.acceleration(t)
        return t, ax, ay

    @property
    def resultant_pga(self) -> float:
        """max √(ü_gx² + ü_gy²) [m/s²] (Eq 5.24's measure; exact for piecewise-linear records)."""
        if self.kind == EXC_NONE:
            return 0.0
        if self.is_record:
            return float(abs(self.params[0]) * np.max(np.hypot(self.x, self.y))) if self.x.size else 0.0
        return abs(float(self.params[0]))

    def scaled(self, factor: float) -> "MotionPair":
        """Both components multiplied by ``factor``."""
        params = self.params.copy()
        params[0] *= factor
        return MotionPair(self.name, self.kind, params, self.x, self.y, self.direction, self.planar,
                          dict(self.meta, scale=self.meta.get("scale", 1.0) * factor))

    def rotated(self, azimuth: float) -> "MotionPair":
        """The pair turned counter-clockwise by ``azimuth`` [rad] (x toward y)."""
        c, s = math.cos(azimuth), math.sin(azimuth)
        meta = dict(self.meta, azimuth=self.meta.get("azimuth", 0.0) + azimuth)
        if self.is_record:
            return MotionPair(self.name, self.kind, self.params, c * self.x - s * self.y, s * self.x + c * self.y,
                              (1.0, 1.0), self.planar, meta)
        dx, dy = self.direction
        return MotionPair(self.name, self.kind, self.params, self.x, self.y, (c * dx - s * dy, s * dx + c * dy),
                          self.planar, meta)


def pair_of_records(name: str, x: GroundMotion, y: GroundMotion | None, meta: dict | None = None) -> MotionPair:
    """A pair from two record motions on the same time step (y = None: one component along x, planar)."""
    if not x.is_record or (y is not None and not y.is_record):
        raise MotionError("a record pair needs two records", key="motion", expected="two sampled records",
                          found=name)
    sx = x.scale * x.samples
    if y is None:
        sy = np.zeros_like(sx)
    else:
        if abs(x.dt - y.dt) > 1e-9 * x.dt:
            raise MotionError("the two components have different time steps", key="motion",
                              expected="records sampled at the same dt",
                              found=f"dt = {x.dt:g} s in '{_source(x)}' and {y.dt:g} s in '{_source(y)}'")
        sy = y.scale * y.samples
        n = max(sx.size, sy.size)
        sx = np.concatenate([sx, np.zeros(n - sx.size)])
        sy = np.concatenate([sy, np.zeros(n - sy.size)])
    info = dict(meta or {}, dt=x.dt, npts=int(sx.size), scale=1.0, components=[x.name] + ([y.name] if y else []))
    return MotionPair(name, EXC_SAMPLES, np.array([1.0, x.dt]), np.ascontiguousarray(sx, dtype=float),
                      np.ascontiguousarray(sy, dtype=float), (1.0, 1.0), y is None, info)


def _source(motion: GroundMotion) -> str:
    """The file a record came from (its name) or the record's id."""
    return motion.meta.get("file_name") or motion.name


def load_pair(pair_id: str, *, gravity: float = 9.81) -> MotionPair:
    """The built-in pair ``p695-ff/11`` (component a along x, b along y) in m/s²."""
    from ..motions.library import load_record
    m = _PAIR_ID.match(pair_id.strip())
    if not m:
        raise MotionError("unknown record pair", key="motion", expected="p695-ff/<1..22>, p695-nfp/<1..14>, "
                          "p695-nfnp/<15..28> (both components), or one component such as p695-ff/11a",
                          found=repr(pair_id))
    prefix, number = m.group(1).lower(), int(m.group(2))
    a = load_record(f"{prefix}/{number}a", gravity=gravity)
    b = load_record(f"{prefix}/{number}b", gravity=gravity)
    meta = {k: a.meta.get(k) for k in ("event", "year", "station", "rsn")}
    meta.update(id=f"{prefix}/{number}", component_x=a.meta.get("component_name"),
                component_y=b.meta.get("component_name"))
    return pair_of_records(f"{prefix}/{number}", a, b, meta)


def pulse_pair(motion: GroundMotion, azimuth: float = 0.0) -> MotionPair:
    """An analytic pulse acting along the azimuth [rad] (planar: a one-directional excitation)."""
    return MotionPair(motion.name, motion.kind, motion.params, _EMPTY, _EMPTY,
                      (math.cos(azimuth), math.sin(azimuth)), True, dict(motion.meta, azimuth=azimuth))


def suite_pairs(name: str, *, gravity: float = 9.81) -> list[MotionPair]:
    """All pairs of a suite of pairs (``p695-farfield-pairs`` 22, near-field pulse 14 and no-pulse 14)."""
    if name not in PAIR_SUITES:
        raise MotionError("unknown suite of record pairs", key="suite", expected=", ".join(PAIR_SUITES),
                          found=repr(name))
    prefix, numbers = PAIR_SUITES[name]
    return [load_pair(f"{prefix}/{n}", gravity=gravity) for n in numbers]


@dataclass(frozen=True)
class PairSpec:
    """A parsed bidirectional motion string: the pair and the initial state of free vibration."""

    pair: MotionPair
    theta0: float = 0.0
    thetadot0: float = 0.0
    phi0: float = 0.0
    phidot0: float = 0.0
    text: str = ""


def _angle(text: str, value: str, name: str = "azimuth") -> float:
    """An angle parameter [rad] (``30deg``, ``30°``, ``0.5rad``): finite, or a one-line error naming it."""
    v = value.strip()
    try:
        if v.endswith("deg") or v.endswith("°"):
            angle = math.radians(float(v.rstrip("°").removesuffix("deg").strip()))
        else:
            angle = parse_quantity(v, "angle")
    except (ValueError, QuantityParseError):
        raise MotionError(f"{name} expects an angle", key="motion", expected=f"e.g. {name}=30deg or "
                          f"{name}=0.5rad", found=f"'{value}' in '{text}'") from None
    return finite(text, name, value, angle)


def _split(text: str, body: str, allowed: tuple[str, ...]) -> tuple[list[str], dict[str, str]]:
    """(positional parts, named parameters) of a pair's motion string (the planar parser's rules)."""
    from ..motions.parse import _fields
    positional: list[str] = []
    named = _fields(text, body, allowed, positional)
    return positional, named


def _apply_scaling(pair: MotionPair, named: dict, text: str, gravity: float, uplift: float) -> MotionPair:
    if "scale" in named and "resultant_pga" in named:
        raise MotionError("conflicting scalings", key="motion", expected="scale=… or resultant_pga=…",
                          found=f"both in '{text}'")
    if "azimuth" in named:
        pair = pair.rotated(_angle(text, named["azimuth"]))
    if "scale" in named:
        pair = pair.scaled(scale_factor(text, named["scale"]))
    if "resultant_pga" in named:
        value = named["resultant_pga"].strip()
        m = re.match(r"^([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*up$", value)
        try:
            target = float(m.group(1)) * uplift if m else parse_quantity(value, "acceleration", gravity=gravity)
        except QuantityParseError as exc:
            raise MotionError(f"resultant_pga expects {exc} or a multiple of 'up'", key="motion",
                              found=f"'{text}'") from None
        finite(text, "resultant_pga", value, target)
        if not target > 0 or pair.resultant_pga == 0:
            raise MotionError("resultant_pga must be positive", key="motion", expected="e.g. resultant_pga=0.3g",
                              found=f"'{text}'")
        pair = pair.scaled(target / pair.resultant_pga)
    return pair


def parse_pair(text: str, *, gravity: float = 9.81, alpha: float = 0.0, uplift_acceleration: float = 0.0,
               p: float = 1.0, records_dir: str | None = None) -> PairSpec:
    """Parse a bidirectional motion string (module docstring) for a cylinder.

    ``alpha`` [rad], ``uplift_acceleration`` g tan α [m/s²] and ``p`` [1/s] give the relative units
    ``0.8alpha``, ``2up`` and ``wp=3p``.
    """
    from ..motions.parse import SystemScales, parse_motion
    if ":" not in text:
        raise MotionError("malformed motion", key="motion", expected="KIND:params, KIND one of record, files, "
                          "file, free, " + ", ".join(PULSE_KINDS), found=f"'{text}'")
    kind, body = (s.strip() for s in text.split(":", 1))
    scales = SystemScales(alpha, uplift_acceleration, p, p, gravity)
    if kind == "free":
        _, named = _split(text, body, ("theta0", "thetadot0", "phi0", "phidot0"))
        if "theta0" not in named and "thetadot0" not in named:
            raise MotionError("free vibration needs an initial tilt", key="motion",
                              expected="free:theta0=0.1rad[,phidot0=1e-3rad/s]", found=f"'{text}'")
        base = parse_motion("free:" + ",".join(f"{k}={v}" for k, v in named.items() if k in ("theta0", "thetadot0")),
                            scales)
        phi0 = _angle(text, named["phi0"], "phi0") if "phi0" in named else 0.0
        phidot0 = 0.0
        if "phidot0" in named:
            try:
                phidot0 = parse_quantity(named["phidot0"], "frequency")
            except QuantityParseError as exc:
                raise MotionError(f"phidot0 expects {exc}", key="motion", found=f"'{text}'") from None
            finite(text, "phidot0", named["phidot0"], phidot0)
        if base.theta0 <= 0.0 and base.thetadot0 <= 0.0:
            raise MotionError("the cylinder's tilt is θ ≥ 0", key="motion", expected="theta0 > 0 or thetadot0 > 0",
                              found=f"'{text}'")
        pair = MotionPair("free vibration", EXC_NONE, np.zeros(0), planar=phidot0 == 0.0)
        return PairSpec(pair, base.theta0, base.thetadot0, phi0, phidot0, text)
    if kind in PULSE_KINDS:
        positional, named = _split(text, body, ("ap", "Tp", "wp", "tm", "t0", "n", "azimuth"))
        azimuth = _angle(text, named.pop("azimuth")) if "azimuth" in named else 0.0
        base = parse_motion(f"{kind}:" + ",".join(positional + [f"{k}={v}" for k, v in named.items()]), scales)
        return PairSpec(pulse_pair(base.motion, azimuth), text=text)
    if kind in ("record", "files", "file"):
        positional, named = _split(text, body, ("scale", "resultant_pga", "azimuth", "units", "dt"))
        if kind == "files" and len(positional) != 2:
            raise MotionError("files: needs two record files", key="motion", expected="files:X.AT2,Y.AT2",
                              found=f"'{text}'")
        record_file_only(text, kind, named)
        if kind != "files" and len(positional) != 1:
            raise MotionError("one record id or file", key="motion", expected="record:p695-ff/11 or file:X.AT2",
                              found=f"'{text}'")
        if kind == "record" and _PAIR_ID.match(positional[0]):
            pair = load_pair(positional[0], gravity=gravity)
        else:
            extra = [f"{k}={named[k]}" for k in ("units", "dt") if k in named]
            if kind == "files":
                x = parse_motion(",".join([f"file:{positional[0]}"] + extra), scales, records_dir=records_dir).motion
                y = parse_motion(",".join([f"file:{positional[1]}"] + extra), scales, records_dir=records_dir).motion
                pair = pair_of_records(f"{positional[0]} + {positional[1]}", x, y)
            else:
                x = parse_motion(",".join([f"{kind}:{positional[0]}"] + extra), scales, records_dir=records_dir).motion
                pair = pair_of_records(positional[0], x, None, {"id": positional[0]})
        return PairSpec(_apply_scaling(pair, named, text, gravity, uplift_acceleration), text=text)
    raise MotionError("unknown motion kind for a cylinder", key="motion",
                      expected="record, files, file, free or a pulse (" + ", ".join(PULSE_KINDS) + ")",
                      found=f"'{kind}' in '{text}'")


def no_pair() -> MotionPair:
    """No ground motion."""
    m = no_motion()
    return MotionPair(m.name, m.kind, m.params, planar=True)
