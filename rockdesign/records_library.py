"""The library functions of ``rockdesign records``: ground-motion records listed, measured, their elastic
spectra, synthetic ensembles and records for scale models (thesis Ch. 5–7; docs/records.md, docs/api.md).

    import rockdesign as rd
    rd.records_list("p695-ff").rows                  # one dict per record: dt [s], npts, pga [m/s²]
    m = rd.records_show("p695-ff/11a")              # m.measures["arias"] [m/s], m.sd_max [m], m.motion
    s = rd.records_spectrum("p695-ff/11a", damping=0.05)  # s.periods [s], s.sd [m], s.psa [m/s²]
    e = rd.records_synth("p695-ff/11a", 20, "ensemble/")   # e.suite: ensemble.toml for [excitation] suites
    r = rd.records_scale_model("p695-ff/11a", 0.025, table="d=0.125m,v=0.22m/s")   # r.exceeded, r.write_at2(…)

A record is named by a built-in id (``p695-ff/11a``), ``rsn:<RSN>:<component>`` (with ``records_dir``),
``file:<path>`` or a path; a leading ``record:`` is accepted.  Errors name the parameter (``gravity``,
``damping``, ``band``, ``seed_value``, ``table``…); every result has ``as_json()`` (SI) — for ``list`` and
``spectrum`` the ``--json`` output of the command.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from .errors import MotionError
from .execution import compilation
from .experiments.figures import scale_model_figure
from .experiments.scale_model import ScaledRecord, parse_limits, scale_record, write_at2
from .motions.defaults import DEFAULT_BAND, DEFAULT_DAMPING, DEFAULT_N_PERIODS
from .motions.figures import record_history_figure, record_spectrum_figure
from .motions.library import load_record
from .motions.measures import motion_measures, plausibility_warnings
from .motions.motion import GroundMotion
from .motions.spectra import motion_spectrum, period_grid, sd_max
from .motions.warm_up import ELASTIC_SPECTRUM
from .motions.suites import list_records
from .motions.synth import SCALE_CHOICES, EnsembleMatch, synthesize
from .outdir import OutputError, refuse_wrong_type
from .paths import expand_user, require_path, user_path_errors
from .plots import save
from .units import QuantityParseError, parse_quantity

__all__ = ["records_list", "records_show", "records_spectrum", "records_synth", "records_scale_model", "RecordList",
           "RecordMeasures", "RecordSpectrum", "SyntheticSuite", "ScaleModelRecord"]

G_RANGE = (9.7, 9.9)
"""Accepted gravitational accelerations [m/s²] (the range of ``[analysis] g``)."""
MEASURES = ("pga", "pgv", "pgd", "arias", "cav", "bracketed_duration", "significant_duration", "a_rms",
            "predominant_frequency")
"""The intensity measures of ``records spectrum --json`` (SI: m/s², m/s, m, m/s, m/s, s, s, m/s², Hz)."""


# --- inputs -------------------------------------------------------------------------------------------
def record_id(text: str) -> str:
    """The record id without a leading ``record:``."""
    text = str(text).strip()
    return text[7:] if text.lower().startswith("record:") else text


def check_gravity(value: float, key: str = "gravity") -> float:
    """g [m/s²] within :data:`G_RANGE` (a negative or zero g would print negative or infinite values in g)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and G_RANGE[0] <= value <= G_RANGE[1]):
        raise MotionError("out of range", key=key,
                          expected=f"a gravitational acceleration {G_RANGE[0]:g}–{G_RANGE[1]:g} m/s²",
                          found=repr(value))
    return float(value)


def parse_damping(value: float | str) -> float:
    """A damping ratio in [0, 1): a number or a string such as ``"0.02"`` or ``"2 %"``."""
    text = str(value)
    try:
        ratio = parse_quantity(float(text) if _is_number(text) else text, "dimensionless")
    except QuantityParseError:
        raise MotionError("invalid damping", key="damping", expected="a ratio like 0.02 or '2 %'",
                          found=repr(text)) from None
    if not 0.0 <= ratio < 1.0:
        raise MotionError("invalid damping", key="damping", expected="a damping ratio in [0, 1)", found=repr(text))
    return ratio


def parse_band(value) -> tuple[float, float]:
    """A period band (T_min, T_max) [s]: a pair of numbers or the text ``"Tmin:Tmax"`` (0 < T_min < T_max)."""
    try:
        lo, hi = (float(p) for p in (value.split(":") if isinstance(value, str) else value))
    except (TypeError, ValueError):
        raise MotionError("invalid period band", key="band", expected="Tmin:Tmax in seconds, e.g. 0.05:10",
                          found=repr(value)) from None
    if not (0 < lo < hi and math.isfinite(hi)):
        raise MotionError("invalid period band", key="band", expected="0 < Tmin < Tmax", found=repr(value))
    return lo, hi


def parse_corners(value) -> tuple[float, float] | None:
    """Band-pass corners (low, high) [Hz]: a pair of numbers or the text ``"low:high"`` (checked against the
    record's Nyquist frequency when filtering); None for the default corners."""
    if value is None or value == "":
        return None
    try:
        lo, hi = (float(p) for p in (value.split(":") if isinstance(value, str) else value))
    except (TypeError, ValueError):
        raise MotionError("invalid filter corners", key="band", expected="low:high in Hz, e.g. 0.6:150",
                          found=repr(value)) from None
    return lo, hi


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _load(record: str, gravity: float, records_dir) -> tuple[GroundMotion, list[str]]:
    check_gravity(gravity)
    motion = load_record(record_id(record), gravity=gravity, records_dir=records_dir)
    return motion, plausibility_warnings(motion, gravity)


# --- records list ---------------------------------------------------------------------------------------
@dataclass
class RecordList:
    """Records of a suite (or every built-in record).

    Attributes:
        suite: the suite's name or manifest path (None: the built-in records).
        rows: one dict per record: ``id, event, year, station, rsn, component, dt`` [s], ``npts``, ``pga``
            [m/s²]; a record that cannot be found has ``dt``/``npts``/``pga`` None and ``missing`` (the reason);
            a suite may give ``label``.
        gravity: g [m/s²] of records in units of g.
    """

    suite: str | None
    rows: list[dict]
    gravity: float

    @property
    def missing(self) -> list[dict]:
        """The rows of records that cannot be found."""
        return [row for row in self.rows if row.get("missing")]

    def as_json(self) -> list[dict]:
        """The ``records list --json`` output."""
        return self.rows


def records_list(suite: str | Path | None = None, *, gravity: float = 9.81, records_dir=None) -> RecordList:
    """The records of ``suite`` (a suite name such as ``p695-ff`` or a manifest path; None: every built-in
    record, FEMA P695), read with g = ``gravity`` [m/s²]; PEER AT2 files of ``rsn:`` entries from ``records_dir``."""
    check_gravity(gravity)
    name = None if suite is None else str(suite)
    return RecordList(name, list_records(name, gravity=gravity, records_dir=records_dir), gravity)


# --- records show ---------------------------------------------------------------------------------------
@dataclass
class RecordMeasures:
    """Metadata and intensity measures of one record.

    Attributes:
        id: the record id.
        motion: the :class:`~rockdesign.motions.motion.GroundMotion` (``dt`` [s], ``samples`` [m/s²], ``meta``).
        measures: ``pga`` [m/s²], ``pgv`` [m/s], ``pgd`` [m] (no baseline correction), ``arias`` [m/s] (Eq 5.46),
            ``cav`` [m/s] (Eq 5.44), ``bracketed_duration`` [s] (0.05 g), ``significant_duration`` [s] (D5–95),
            ``a_rms`` [m/s²] (Eq 5.45), ``predominant_frequency`` [Hz] (Konno–Ohmachi b = 40; None without motion).
        sd_max, sd_max_period: Polyakov's SD_max [m] and its period [s] (2 % damping, 0.05–10 s; thesis Sec 4.2.5).
        gravity: g [m/s²].
        warnings: implausible content (all zeros, PGA above ~4 g).
    """

    id: str
    motion: GroundMotion
    measures: dict
    sd_max: float
    sd_max_period: float
    gravity: float
    warnings: list[str] = field(default_factory=list)

    def as_json(self) -> dict:
        m = self.motion
        return {"id": self.id, "meta": dict(m.meta), "dt": m.dt, "npts": int(m.samples.size), "duration": m.duration,
                **self.measures, "sd_max": self.sd_max, "t_sd_max": self.sd_max_period,
                "sd_max_damping": DEFAULT_DAMPING, "sd_max_band": list(DEFAULT_BAND), "warnings": list(self.warnings)}

    def write_figure(self, path) -> Path:
        """Ground acceleration, velocity and displacement against t (.png, .svg or .pdf)."""
        save(record_history_figure(self.motion), path, dpi=130)
        return Path(path)


def records_show(record: str, *, gravity: float = 9.81, records_dir=None, say=None) -> RecordMeasures:
    """The intensity measures and SD_max of one record (``say`` announces a first-run compilation)."""
    motion, warnings = _load(record, gravity, records_dir)
    compilation.prepare("records", (ELASTIC_SPECTRUM,), say)
    period_peak = sd_max(motion, DEFAULT_DAMPING, DEFAULT_BAND)
    return RecordMeasures(record_id(record), motion, motion_measures(motion, gravity), *period_peak, gravity,
                          warnings)


# --- records spectrum -----------------------------------------------------------------------------------
@dataclass
class RecordSpectrum:
    """The elastic response spectrum of one record (exact, the free vibration after the record included).

    Attributes:
        id, motion, gravity, warnings: as :class:`RecordMeasures`.
        damping: damping ratio; ``band`` (T_min, T_max) [s].
        periods: T [s] (log-spaced); ``sd`` SD [m], ``psv`` PSV [m/s], ``psa`` PSA [m/s²] at them.
        sd_max, sd_max_period: SD_max [m] over the band and its period [s].
        measures: the intensity measures (:data:`MEASURES`).
    """

    id: str
    motion: GroundMotion
    gravity: float
    damping: float
    band: tuple[float, float]
    periods: np.ndarray
    sd: np.ndarray
    psv: np.ndarray
    psa: np.ndarray
    sd_max: float
    sd_max_period: float
    measures: dict
    warnings: list[str] = field(default_factory=list)

    def as_json(self) -> dict:
        """The ``records spectrum --json`` object (SI)."""
        return {"id": self.id, "damping": self.damping, "band": list(self.band), "periods": self.periods.tolist(),
                "SD": self.sd.tolist(), "PSV": self.psv.tolist(), "PSA": self.psa.tolist(), "sd_max": self.sd_max,
                "t_sd_max": self.sd_max_period, **{k: self.measures[k] for k in MEASURES}}

    def write_figure(self, path) -> Path:
        """SD and PSA against T (.png, .svg or .pdf)."""
        save(record_spectrum_figure(self.as_json(), self.gravity), path, dpi=130)
        return Path(path)


def records_spectrum(record: str, *, damping: float | str = DEFAULT_DAMPING, band=DEFAULT_BAND,
                     n_periods: int = DEFAULT_N_PERIODS, gravity: float = 9.81, records_dir=None,
                     say=None) -> RecordSpectrum:
    """The elastic spectrum of a record at ``n_periods`` log-spaced periods of ``band`` [s] (``"0.05:10"`` or a
    pair), for a ``damping`` ratio (0.02 or ``"2 %"``), with SD_max and the intensity measures."""
    zeta = parse_damping(damping)
    lo, hi = parse_band(band)
    if isinstance(n_periods, bool) or not isinstance(n_periods, (int, np.integer)) or n_periods < 2:
        raise MotionError("invalid number of periods", key="n_periods", expected="an integer ≥ 2",
                          found=repr(n_periods))
    motion, warnings = _load(record, gravity, records_dir)
    compilation.prepare("records", (ELASTIC_SPECTRUM,), say)
    periods = period_grid((lo, hi), int(n_periods))
    sd, psv, psa = motion_spectrum(motion, periods, zeta)
    peak, period = sd_max(motion, zeta, (lo, hi), int(n_periods))
    return RecordSpectrum(record_id(record), motion, gravity, zeta, (lo, hi), periods, sd, psv, psa, peak, period,
                          motion_measures(motion, gravity), warnings)


# --- records synth --------------------------------------------------------------------------------------
@dataclass
class SyntheticSuite:
    """A synthetic ensemble saved as a suite.

    Attributes:
        suite: the manifest ``ensemble.toml`` (beside it ``ensemble.npz``, ``model.json``, ``match.json``); use
            it as ``[excitation] suites = ["…/ensemble.toml"]``.
        n: the number of records.
        match: how the ensemble matches the seed record (:class:`~rockdesign.motions.synth.EnsembleMatch`: the
            common scale factor, SD_max and spectrum ratios).
        warnings: about the seed record.
    """

    suite: Path
    n: int
    match: EnsembleMatch
    warnings: list[str] = field(default_factory=list)

    def describe(self) -> str:
        return self.match.describe()

    def as_json(self) -> dict:
        return {"suite": str(self.suite), "n": self.n, "match": asdict(self.match), "warnings": list(self.warnings)}


def records_synth(seed: str, n: int, out_dir, *, seed_value: int = 1, scale_to: str = "sdmax", gravity: float = 9.81,
                  records_dir=None, progress: Callable[[str, int, int], None] | None = None,
                  say=None) -> SyntheticSuite:
    """``n`` synthetic records from the sgsim stochastic model fitted to the ``seed`` record (random seed
    ``seed_value``), scaled by one common factor to the seed's SD_max (``scale_to="sdmax"``), its spectrum
    (``"spectrum"``) or not at all (``"none"``), saved as a suite in ``out_dir``."""
    if scale_to not in SCALE_CHOICES:
        raise MotionError("unknown ensemble scaling", key="scale_to", expected=" | ".join(SCALE_CHOICES), found=repr(scale_to))
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise MotionError("invalid number of records", key="n", expected="an integer ≥ 1", found=repr(n))
    if isinstance(seed_value, bool) or not isinstance(seed_value, int) or seed_value < 0:
        raise MotionError("invalid random seed", key="seed_value", expected="an integer ≥ 0", found=repr(seed_value))
    require_path(out_dir, "out_dir", "a folder name")
    out = expand_user(out_dir, "out_dir", error=OutputError)
    with user_path_errors("out_dir", out, error=OutputError):
        for p in [out, *out.parents]:
            refuse_wrong_type(p, "out_dir", folder=True)
    motion, warnings = _load(seed, gravity, records_dir)
    compilation.prepare("records", (ELASTIC_SPECTRUM,), say)           # (SD_max of the seed and of every member)
    path, match = synthesize(motion, int(n), out, seed_value=seed_value, scale_to=scale_to, progress=progress)
    return SyntheticSuite(path, int(n), match, warnings)


# --- records scale-model --------------------------------------------------------------------------------
@dataclass
class ScaleModelRecord:
    """A record time-scaled for a small-scale model (Eq 6.5), corrected and checked against the table's limits.

    Attributes:
        id: the record id; ``length_ratio`` R_m/R_p.
        motion: the prototype record.
        scaled: the :class:`~rockdesign.experiments.scale_model.ScaledRecord` (model time: ``dt`` [s],
            ``acceleration`` [m/s²], ``velocity`` [m/s], ``displacement`` [m], ``time_factor`` √(R_m/R_p),
            band-pass ``corners`` [Hz], ``peaks``).
        limits: the table's limits ``{"d": m, "v": m/s, "a": m/s²}`` (keys given only).
        gravity: g [m/s²]; ``warnings`` about the record.
    """

    id: str
    length_ratio: float
    motion: GroundMotion
    scaled: ScaledRecord
    limits: dict
    gravity: float
    warnings: list[str] = field(default_factory=list)

    @property
    def exceeded(self) -> list[str]:
        """The quantities (``d``, ``v``, ``a``) whose peak exceeds the table's limit."""
        return self.scaled.exceeded

    def as_json(self) -> dict:
        """The ``records scale-model --json`` object (SI)."""
        return self.scaled.as_json()

    def write_at2(self, path) -> Path:
        """The scaled, corrected record as a PEER AT2 file (units of g)."""
        return write_at2(self.scaled, path, self.gravity, self.motion.meta)

    def write_figure(self, path) -> Path:
        """a, v, d of the scaled record with the table's limits (.png, .svg or .pdf)."""
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        title = f"{self.id} for R_m/R_p = {self.length_ratio:g} (Eq 6.5)"
        save(scale_model_figure(self.scaled, self.gravity, self.limits, title), path)
        return Path(path)


def records_scale_model(record: str, length_ratio: float, *, table: str | None = None, band=None,
                        gravity: float = 9.81, records_dir=None) -> ScaleModelRecord:
    """The record prepared for a model of length ratio R_m/R_p (thesis Eq 6.5: Δt_m = Δt_p √(R_m/R_p), accelerations
    unchanged): baseline-corrected, band-pass filtered (corners ``band`` = ``"low:high"`` [Hz, model time]; default
    0.1/25 Hz moved by the time scale) and checked against the table's limits ``table`` (e.g.
    ``"d=0.125m,v=0.22m/s,a=1.5g"``; thesis Fig 6.2b)."""
    check_gravity(gravity)
    limits = parse_limits(table, gravity)
    corners = parse_corners(band)
    motion, warnings = _load(record, gravity, records_dir)
    scaled = scale_record(motion, length_ratio, corners=corners, limits=limits)
    return ScaleModelRecord(record_id(record), length_ratio, motion, scaled, limits, gravity, warnings)
