"""Motion strings of the CLI (CONTRACT §2): pulses, free vibration, built-in records, record files.

    ricker-anti:ap=0.38g,Tp=0.95s        ricker-sym:ap=2.5up,Tp=1.2s,tm=2s
    sine:ap=3.7m/s2,Tp=0.59s              cycloidal-b:ap=0.3g,wp=3p
    free:theta0=0.8alpha[,thetadot0=0.01rad/s]
    record:p695-ff/11a[,scale=1.5]        file:path/to/RSN900_LANDERS_YER270.AT2[,scale=2]

Amplitudes take units (``g`` is the project's gravity) or multiples of the system's exact uplift
acceleration g tan α (``2.5up``; tan α' with flat extensions).  ``wp=3p`` sets ω_p = 3p with p of
Eq 3.13 (``wp=3phat`` uses the system's p̂); ``Tp`` is the pulse period 2π/ω_p.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

from ..errors import MotionError, RockdesignError
from ..units import QuantityParseError, parse_quantity
from .motion import PULSE_KINDS, GroundMotion, no_motion, pulse_motion

_MULTIPLE = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z_]+)\s*$")


@dataclass(frozen=True)
class MotionSpec:
    """A parsed motion string: the ground motion and the initial state (free vibration)."""

    motion: GroundMotion
    theta0: float = 0.0
    thetadot0: float = 0.0
    text: str = ""


@dataclass(frozen=True)
class SystemScales:
    """What relative units in motion strings refer to (SI): α [rad], g tan α [m/s²], p and p̂ [1/s], g."""

    alpha: float
    uplift_acceleration: float
    p: float
    p_hat: float
    g: float


def _fields(text: str, body: str, allowed: tuple[str, ...], positional: list | None = None) -> dict[str, str]:
    """``name=value`` parameters of a motion string (each allowed name once).  With a ``positional`` list,
    empty parts are skipped and parts without ``=`` are appended to it (record pairs: ``files:X,Y``)."""
    out = {}
    if not body.strip():
        return out
    parts = body.split(",")
    no_empty_part(text, parts)
    for part in parts:
        if positional is not None:
            part = part.strip()
            if "=" not in part:
                positional.append(part)
                continue
        if "=" not in part:
            raise MotionError("malformed motion parameter", key="motion", expected="name=value pairs "
                              "separated by commas, e.g. ricker-anti:ap=0.38g,Tp=0.95s", found=f"'{part}' in '{text}'")
        k, v = (x.strip() for x in part.split("=", 1))
        if k not in allowed:
            raise MotionError("unknown motion parameter", key="motion", expected="one of " + ", ".join(allowed),
                              found=f"'{k}' in '{text}'")
        if k in out:
            raise MotionError("parameter given twice", key="motion", expected="each parameter once",
                              found=f"'{k}' in '{text}'")
        out[k] = v
    return out


def no_empty_part(text: str, parts: list[str]) -> None:
    """Refuse an empty parameter (``,,`` or a comma at either end): nothing the user typed is skipped."""
    if any(not part.strip() for part in parts):
        raise MotionError("empty motion parameter (two commas in a row, or a comma at either end)",
                          key="motion", expected="name=value pairs separated by single commas",
                          found=f"'{text}'")


def _relative(value: str, units: dict[str, float]):
    m = _MULTIPLE.match(value)
    if m and m.group(2) in units:
        return float(m.group(1)) * units[m.group(2)]
    return None


def _quantity(text: str, name: str, value: str, dimension: str, scales: SystemScales, relative: dict[str, float]):
    rel = _relative(value, relative)
    try:
        result = rel if rel is not None else parse_quantity(value, dimension, gravity=scales.g)
    except QuantityParseError as exc:
        extra = " or " + " / ".join(f"a multiple of '{u}'" for u in relative) if relative else ""
        raise MotionError(f"parameter '{name}' expects {exc}{extra}", key="motion", found=f"'{text}'") from None
    return finite(text, name, value, result)


def finite(text: str, name: str, raw: str, value: float) -> float:
    """``value`` if it is a finite number (NaN or ±inf, e.g. from ``1e999``, never reach a kernel)."""
    if not math.isfinite(value):
        raise MotionError(f"parameter '{name}' must be a finite number", key="motion",
                          expected=f"{name}=… with a finite value", found=f"'{raw}' in '{text}'")
    return value


def scale_factor(text: str, raw: str) -> float:
    """The ``scale=`` of a motion string: a finite number > 0 (``text``, the whole string, for messages)."""
    try:
        scale = float(raw)
    except ValueError:
        raise MotionError("scale must be a number", key="motion", expected="scale=1.5", found=f"'{text}'") from None
    if not (math.isfinite(scale) and scale > 0):
        raise MotionError("scale must be positive", key="motion", expected="a finite scale > 0",
                                  found=f"'{text}'")
    return scale


def record_file_only(text: str, kind: str, named: dict) -> None:
    """Refuse ``units=``/``dt=`` on a built-in record (it carries its own): they apply to ``file:`` motions."""
    ignored = [k for k in ("units", "dt") if k in named]
    if kind == "record" and ignored:
        raise MotionError(f"'{ignored[0]}=' applies to record files (file:…); a built-in record has its own "
                          "units and time step", key="motion", expected="record:ID[,scale=…] or "
                          "file:PATH[,units=…,dt=…]", found=f"'{ignored[0]}={named[ignored[0]]}' in '{text}'")


def parse_motion(text: str, scales: SystemScales, *, records_dir: str | None = None) -> MotionSpec:
    """Parse a motion string of CONTRACT §2 for a system with the given ``scales``."""
    if ":" not in text:
        raise MotionError("malformed motion", key="motion", expected="KIND:params, KIND one of "
                          + ", ".join(list(PULSE_KINDS) + ["free", "record", "file"]), found=f"'{text}'")
    kind, body = text.split(":", 1)
    kind = kind.strip()
    if kind in PULSE_KINDS:
        f = _fields(text, body, ("ap", "Tp", "wp", "tm", "t0", "n"))
        if "ap" not in f:
            raise MotionError("missing pulse amplitude", key="motion", expected="ap=… (e.g. ap=0.38g or ap=2.5up)",
                              found=f"'{text}'")
        if ("Tp" in f) == ("wp" in f):
            raise MotionError("give the pulse period or frequency", key="motion",
                              expected="exactly one of Tp=… (s) or wp=… (e.g. wp=3p)", found=f"'{text}'")
        a_p = _quantity(text, "ap", f["ap"], "acceleration", scales, {"up": scales.uplift_acceleration})
        if a_p <= 0:
            raise MotionError("pulse amplitude must be positive", key="motion", expected="ap > 0", found=f"'{text}'")
        if "Tp" in f:
            T_p = _quantity(text, "Tp", f["Tp"], "time", scales, {})
        else:
            w = _quantity(text, "wp", f["wp"], "frequency", scales, {"p": scales.p, "phat": scales.p_hat})
            if w <= 0:
                raise MotionError("pulse frequency must be positive", key="motion", expected="wp > 0",
                                  found=f"'{text}'")
            T_p = 2 * math.pi / w
        if T_p <= 0:
            raise MotionError("pulse period must be positive", key="motion", expected="Tp > 0", found=f"'{text}'")
        t_m = _quantity(text, "tm", f["tm"], "time", scales, {}) if "tm" in f else None
        t_0 = _quantity(text, "t0", f["t0"], "time", scales, {}) if "t0" in f else 0.0
        for name, value in (("tm", t_m), ("t0", t_0)):
            if value is not None and not (math.isfinite(value) and value >= 0.0):
                raise MotionError(f"'{name}' must be a time ≥ 0 s (the analysis starts at t = 0)", key="motion",
                                  expected=f"{name}=… ≥ 0 s", found=f"'{text}'")
        if "tm" in f and kind not in ("ricker-sym", "ricker-anti"):
            raise MotionError("'tm' (wavelet centre) applies to Ricker wavelets", key="motion",
                              expected="t0=… for sine and cycloidal pulses", found=f"'{text}'")
        n = 1
        if "n" in f:
            if kind != "cycloidal-c" or not f["n"].isdigit() or int(f["n"]) < 1:
                raise MotionError("'n' is the number of cycles of a cycloidal-c pulse", key="motion",
                                  expected="cycloidal-c:…,n=1 (positive integer)", found=f"'{text}'")
            n = int(f["n"])
        return MotionSpec(pulse_motion(kind, a_p, T_p, t_m=t_m, t_0=t_0, n_cycles=n), text=text)
    if kind == "free":
        f = _fields(text, body, ("theta0", "thetadot0"))
        if "theta0" not in f and "thetadot0" not in f:
            raise MotionError("free vibration needs an initial condition", key="motion",
                              expected="free:theta0=0.8alpha (or theta0=0.05rad, thetadot0=0.1rad/s)", found=f"'{text}'")
        th0 = _quantity(text, "theta0", f.get("theta0", "0"), "angle", scales, {"alpha": scales.alpha})
        thd0 = 0.0
        if "thetadot0" in f:
            thd0 = _quantity(text, "thetadot0", f["thetadot0"], "frequency", scales, {})
        if not (math.isfinite(th0) and abs(th0) < math.pi / 2 and math.isfinite(thd0)):
            raise MotionError("initial tilt out of range", key="motion",
                              expected="finite |theta0| < π/2 (the body lies flat at π/2) and finite thetadot0",
                              found=f"'{text}'")
        return MotionSpec(no_motion(), th0, thd0, text)
    if kind in ("record", "file"):
        parts = body.split(",")
        ident = parts[0].strip()
        no_empty_part(text, parts)
        f = _fields(text, ",".join(parts[1:]), ("scale", "units", "dt"))
        record_file_only(text, kind, f)
        scale = scale_factor(text, f["scale"]) if "scale" in f else 1.0
        try:
            if kind == "record":
                from .library import load_record
                motion = load_record(ident, gravity=scales.g, records_dir=records_dir)
            else:
                from .records import read_record_file
                dt = _quantity(text, "dt", f["dt"], "time", scales, {}) if "dt" in f else None
                motion = read_record_file(ident, units=f.get("units"), dt=dt, gravity=scales.g)
        except RockdesignError:
            raise
        except ImportError as exc:  # pragma: no cover - ground-motion package missing
            raise MotionError(f"records are not available: {exc}", key="motion", found=f"'{text}'") from None
        return MotionSpec(motion.scaled(scale) if scale != 1.0 else motion, text=text)
    if kind == "files":   # bidirectional pairs drive the 3D cylinder (rockdesign.cylinder.pairs)
        raise MotionError("a pair of records drives a [cylinder] project", key="motion",
                          expected="one component (record:…a, file:…) for a planar system", found=f"'{text}'")
    raise MotionError("unknown motion kind", key="motion",
                      expected="one of " + ", ".join(list(PULSE_KINDS) + ["free", "record", "file"]),
                      found=f"'{kind}' in '{text}'")
