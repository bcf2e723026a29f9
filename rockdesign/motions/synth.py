"""Synthetic ground-motion ensembles from a seed record (thesis Sec 6.4, "Synthetic Ground Motion
Ensembles"), with the site-based stochastic model of the PyPI package ``sgsim`` (optional).

The thesis used the Rezaeian–Der Kiureghian model; ``sgsim`` (Hussaini et al., Earthquake
Spectra 2025) fits a comparable filtered-white-noise model with a time-modulating function and
time-varying filter frequencies/dampings to the seed, then simulates reproducible records
(numpy ``default_rng(seed_value)``). Its fit under-represents long-period content: for El Centro
1940 (RSN 6, 180) the ensemble median SD_max is ≈ 55–60 % of the seed's. :func:`scale_ensemble`
therefore offers one common amplitude factor (keeping record-to-record variability) so that the
ensemble median SD_max equals the seed's (``sdmax``), or the ensemble mean SD spectrum matches
the seed's over the band in the geometric least-squares sense (``spectrum``), and reports the
match before and after.
"""
from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from ..errors import MotionError
from .motion import GroundMotion, record_motion
from .spectra import DEFAULT_BAND, DEFAULT_DAMPING, motion_spectrum, sd_max
from .suites import save_suite
from ..jsonable import json_ready

SCALE_CHOICES = ("sdmax", "spectrum", "none")


def _sgsim():
    try:
        import sgsim  # noqa: PLC0415 - optional dependency, imported on use
    except ImportError:
        raise MotionError("synthetic ensembles need the optional package 'sgsim'", key="synth",
                          expected="sgsim installed (pip install 'rockdesign[synth]')",
                          found="sgsim not importable") from None
    return sgsim


def fit_model(seed: GroundMotion, *, modulating: str = "dual"):
    """Fit sgsim's stochastic model to a seed record (accelerations in m/s²).

    Args:
        seed: a record GroundMotion.
        modulating: "dual" (sgsim BetaDual: two strong phases) or "single" (BetaSingle).

    Returns:
        The fitted ``sgsim.StochasticModel`` (its ``params`` dict describes it).
    """
    sgsim = _sgsim()
    if not seed.is_record:
        raise MotionError("the seed must be a recorded motion", key="seed", expected="a record id or file",
                          found=seed.name)
    functions = sgsim.Functions
    shapes = {"dual": functions.BetaDual, "single": functions.BetaSingle}
    if modulating not in shapes:
        raise MotionError("unknown modulating function", key="modulating", expected="dual | single",
                          found=repr(modulating))
    _, accel = seed.sampled()
    record = sgsim.GroundMotion.load_from(source="Array", dt=seed.dt, ac=np.array(accel, dtype=np.float64))
    inverter = sgsim.ModelInverter(record, shapes[modulating](), functions.Linear(), functions.Constant(),
                                   functions.Linear(), functions.Constant())
    return inverter.fit()


def simulate_ensemble(seed: GroundMotion, n: int, *, seed_value: int = 1, modulating: str = "dual",
                      name: str = "synth", model=None) -> list[GroundMotion]:
    """``n`` synthetic records (m/s², the seed's dt and length) simulated from the fitted model.

    Reproducible: the same seed record, ``n`` and ``seed_value`` give the same records.
    """
    if n < 1:
        raise MotionError("the ensemble needs at least one record", key="n", expected="n >= 1", found=str(n))
    model = model if model is not None else fit_model(seed, modulating=modulating)
    simulated = model.simulate(int(n), seed=int(seed_value))
    accel = np.atleast_2d(np.asarray(simulated.ac, dtype=np.float64))
    seed_id = seed.meta.get("id", seed.name)
    return [record_motion(f"{name}/{i + 1:03d}", accel[i], seed.dt,
                          meta={"id": f"{name}/{i + 1:03d}", "seed_record": seed_id, "seed_value": int(seed_value),
                                "member": i + 1, "generator": "sgsim", "units": "m/s^2"})
            for i in range(accel.shape[0])]


@dataclass
class EnsembleMatch:
    """How an ensemble compares with its seed, before and after scaling (SI).

    Attributes:
        scale_to: sdmax | spectrum | none.
        factor: the common amplitude factor applied.
        damping, band: of the SD spectra compared.
        seed_sd_max, seed_period: SD_max [m] of the seed and its period [s].
        median_sd_max_before, median_sd_max_after: ensemble median SD_max [m].
        spectrum_ratio_before, spectrum_ratio_after: geometric mean over the band of
            (ensemble mean SD)/(seed SD).
        spectrum_ratio_range_after: (min, max) of that ratio over the band after scaling.
    """

    scale_to: str
    factor: float
    damping: float
    band: tuple[float, float]
    seed_sd_max: float
    seed_period: float
    median_sd_max_before: float
    median_sd_max_after: float
    spectrum_ratio_before: float
    spectrum_ratio_after: float
    spectrum_ratio_range_after: tuple[float, float]
    sd_max_members: list[float] = field(default_factory=list)

    def describe(self) -> str:
        """One paragraph: median SD_max before/after scaling relative to the seed, spectrum match."""
        return (f"ensemble median SD_max = {self.median_sd_max_before:.3f} m = "
                f"{100 * self.median_sd_max_before / self.seed_sd_max:.0f} % of the seed's {self.seed_sd_max:.3f} m "
                f"before scaling; common factor {self.factor:.3f} ({self.scale_to}); after: "
                f"{100 * self.median_sd_max_after / self.seed_sd_max:.0f} %; mean SD spectrum / seed over "
                f"{self.band[0]:g}–{self.band[1]:g} s: {self.spectrum_ratio_after:.2f} (geometric mean), "
                f"{self.spectrum_ratio_range_after[0]:.2f}–{self.spectrum_ratio_range_after[1]:.2f} "
                f"({100 * self.damping:g} % damping)")


def scale_ensemble(motions: list[GroundMotion], seed: GroundMotion, *, scale_to: str = "sdmax",
                   damping: float = DEFAULT_DAMPING, band=DEFAULT_BAND,
                   n_periods: int = 100, progress=None) -> tuple[list[GroundMotion], EnsembleMatch]:
    """Scale an ensemble by one common factor towards its seed and report the match.

    ``sdmax``: factor = seed SD_max / ensemble median SD_max. ``spectrum``: factor =
    exp(mean over a log grid of ln(seed SD/ensemble mean SD)). ``none``: factor 1.
    SD_max and spectra use ``damping`` and ``band`` (defaults 2 %, 0.05–10 s, SPEC §5).
    ``progress(stage, done, total)`` is called as the members' spectra are computed.
    """
    if scale_to not in SCALE_CHOICES:
        raise MotionError("unknown ensemble scaling", key="scale_to", expected=" | ".join(SCALE_CHOICES),
                          found=repr(scale_to))
    periods = np.geomspace(band[0], band[1], n_periods)
    seed_sd_max, seed_period = sd_max(seed, damping, band)
    seed_sd = motion_spectrum(seed, periods, damping)[0]
    members, spectra = [], []
    stage = "spectra of the synthetic records (SD_max, SD)"
    for k, m in enumerate(motions):
        members.append(sd_max(m, damping, band)[0])
        spectra.append(motion_spectrum(m, periods, damping)[0])
        if progress is not None:
            progress(stage, k + 1, len(motions))
    mean_sd = np.mean(spectra, axis=0)
    ratio = mean_sd / seed_sd
    if scale_to == "sdmax":
        factor = seed_sd_max / float(np.median(members))
    elif scale_to == "spectrum":
        factor = float(np.exp(-np.mean(np.log(ratio))))
    else:
        factor = 1.0
    scaled = [m.scaled(factor) for m in motions]
    match = EnsembleMatch(
        scale_to=scale_to, factor=factor, damping=damping, band=(float(band[0]), float(band[1])),
        seed_sd_max=seed_sd_max, seed_period=seed_period,
        median_sd_max_before=float(np.median(members)), median_sd_max_after=float(np.median(members)) * factor,
        spectrum_ratio_before=float(np.exp(np.mean(np.log(ratio)))),
        spectrum_ratio_after=float(np.exp(np.mean(np.log(ratio * factor)))),
        spectrum_ratio_range_after=(float(np.min(ratio * factor)), float(np.max(ratio * factor))),
        sd_max_members=[float(v) for v in members],
    )
    return scaled, match


def synthesize(seed: GroundMotion, n: int, out_dir, *, seed_value: int = 1, scale_to: str = "sdmax",
               damping: float = DEFAULT_DAMPING, band=DEFAULT_BAND, modulating: str = "dual",
               name: str | None = None, progress=None) -> tuple[Path, EnsembleMatch]:
    """Fit, simulate ``n`` records, scale and save them as a suite in ``out_dir``.

    Writes ``ensemble.toml`` + ``ensemble.npz`` (load with
    :func:`rockdesign.motions.suites.load_suite`), ``model.json`` (sgsim parameters) and
    ``match.json`` (:class:`EnsembleMatch`). Returns (manifest path, match).
    ``progress(stage, done, total)`` is called at each stage (fit, simulation, spectra, writing).
    """
    if isinstance(seed_value, bool) or not isinstance(seed_value, int) or seed_value < 0:
        raise MotionError("invalid random seed", key="seed_value", expected="an integer ≥ 0",
                          found=repr(seed_value))
    def tick(stage: str, done: int, total: int) -> None:
        if progress is not None:
            progress(stage, done, total)

    out = Path(out_dir).expanduser()
    seed_id = str(seed.meta.get("id", seed.name))
    name = name or f"synth-{seed_id.replace('/', '-').replace(':', '-')}-s{seed_value}"
    tick("fitting the stochastic model to the seed record", 0, 1)
    model = fit_model(seed, modulating=modulating)
    tick(f"simulating {n} records", 0, 1)
    motions = simulate_ensemble(seed, n, seed_value=seed_value, name=name, model=model)
    scaled, match = scale_ensemble(motions, seed, scale_to=scale_to, damping=damping, band=band, progress=progress)
    tick("writing the suite", 0, 1)
    out.mkdir(parents=True, exist_ok=True)   # (after the work: a failed run leaves no empty folder)
    path = save_suite(out / "ensemble.toml", scaled, name=name,
                      description=f"{n} synthetic records (sgsim) from seed {seed_id}, seed value {seed_value}, "
                                  f"scaled by {match.factor:.4g} ({scale_to})",
                      scale={"method": "factor", "value": 1.0},
                      meta={"seed_record": seed_id, "seed_value": int(seed_value), "generator": "sgsim",
                            "ensemble_factor": match.factor, "ensemble_scaling": scale_to})
    (out / "model.json").write_text(json.dumps(json_ready(model.params), indent=2))
    (out / "match.json").write_text(json.dumps(json_ready(asdict(match)), indent=2))
    tick("writing the suite", 1, 1)
    return path, match
