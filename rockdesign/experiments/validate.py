"""Probabilistic comparison of tests and model (thesis Ch. 7).

θ_max/α from shake-table tests and from analyses of the same ensemble form mixed distributions,
F = (1 − p_o) F̄ + p_o H(· − θ_ot) (Eq 7.1): the overturned runs are a probability mass, the others
a conditional CDF F̄. This module computes, with scipy.stats:

* the empirical mixed CDFs and the tests' nonparametric (Dvoretzky–Kiefer–Wolfowitz) bands,
  ε = √(ln(2/a)/(2n)) for confidence 1 − a (90 % and 95 %);
* the Table 7.2 layout: 25/50/75 % percentiles of F ("OT" when they fall in the overturning mass),
  conditional mean and SD of F̄, relative errors Δθ/θ_exp;
* the Kolmogorov distance sup |F_tests − F_model|;
* the Sec 7.2 three-stage tests on a seeded random split of the tests into D1, D2 — (1) D1 vs D2,
  (2) D1 vs the model with the theoretical c_r on D2's motions, (3) D1 vs the model with the
  measured c_r: the test of equal proportions of overturning (two-sided pooled z test; computed as
  the equivalent Pearson χ² test of the 2×2 table, scipy ``chi2_contingency`` without continuity
  correction, z² = χ²) and the two-sample Kolmogorov–Smirnov test of F̄ (scipy ``ks_2samp``), with
  Table 7.3's evidence words.
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import stats

from .free_vibration import ExperimentError

PERCENTILES = (25, 50, 75)
CONFIDENCES = (0.90, 0.95)
_TRUE = {"true", "1", "yes", "y", "t", "ot", "overturned"}
_FALSE = {"false", "0", "no", "n", "f", ""}


def evidence(p_value: float | None) -> str:
    """Table 7.3 evidence against H0 for a p-value."""
    if p_value is None or not math.isfinite(p_value):
        return "not testable"
    if p_value < 0.01:
        return "very strong against H0"
    if p_value < 0.05:
        return "strong against H0"
    if p_value <= 0.10:
        return "medium-weak against H0"
    return "small or none against H0"


def dkw_epsilon(n: int, a: float) -> float:
    """Half-width of the DKW band of an empirical CDF of n samples at confidence 1 − a: √(ln(2/a)/(2n))."""
    return math.sqrt(math.log(2.0 / a) / (2.0 * n))


@dataclass
class MixedSample:
    """θ_max/α of a set of runs; overturned runs are ``inf`` (the mass p_o of Eq 7.1)."""

    name: str
    values: np.ndarray
    ids: list[str] = field(default_factory=list)
    file: str = ""
    """The CSV file the runs were read from (error messages name it)."""

    @property
    def n(self) -> int:
        return int(self.values.size)

    @property
    def conditional(self) -> np.ndarray:
        """The non-overturned values (the sample of F̄)."""
        return self.values[np.isfinite(self.values)]

    @property
    def n_overturned(self) -> int:
        return int(np.sum(~np.isfinite(self.values)))

    @property
    def p_overturn(self) -> float:
        """Estimated probability of overturning p_o [-]."""
        return self.n_overturned / self.n

    def cdf(self, x) -> np.ndarray:
        """Empirical mixed CDF F(x) (the overturning mass sits at +∞)."""
        finite = np.sort(self.conditional)
        return np.searchsorted(finite, np.asarray(x, dtype=float), side="right") / self.n

    def percentile(self, q: float) -> float | None:
        """q-th percentile of F (inverse of the empirical CDF); None when it falls in the overturning mass."""
        value = float(np.quantile(self.values, q / 100.0, method="inverted_cdf"))
        return value if math.isfinite(value) else None

    def dkw_epsilon(self, a: float) -> float:
        return dkw_epsilon(self.n, a)

    def step_points(self, x_max: float) -> tuple[np.ndarray, np.ndarray]:
        """(x, F) of the step CDF for plotting, with the overturning mass placed at ``x_max``."""
        finite = np.sort(self.conditional)
        x = np.concatenate([[0.0], finite, [0.97 * x_max, x_max]])
        return x, np.concatenate([[0.0], self.cdf(finite), [1.0 - self.p_overturn, 1.0]])

    def subset(self, index: np.ndarray, name: str) -> "MixedSample":
        return MixedSample(name, self.values[index], [self.ids[i] for i in index] if self.ids else [], self.file)


def read_results_csv(path, name: str) -> MixedSample:
    """θ_max/α per run from a CSV with a ``theta_max_over_alpha`` column (``inf``/``OT`` or an
    ``overturned`` column marks overturning) and an optional ``id`` column (the check's results.csv
    and the ensemble command's analyses.csv qualify)."""
    path = Path(path)
    file = str(path)
    if not path.is_file():
        raise ExperimentError("results file not found", file=file, expected="a CSV file", found="no such file")
    rows, header_line = _rows(path, file)
    if not rows or "theta_max_over_alpha" not in rows[0][1]:
        raise ExperimentError("missing column", file=file, line=header_line, key="theta_max_over_alpha",
                              expected="a column 'theta_max_over_alpha' (and optionally 'overturned', 'id')",
                              found=", ".join(str(c) for c in rows[0][1].keys()) if rows else "no rows")
    values, ids = [], []
    for k, row in rows:
        if None in row or None in row.values():
            raise ExperimentError("the row does not match the header", file=file, line=k,
                                  expected=f"{len(rows[0][1])} comma-separated fields as in the header",
                                  found=f"{len(row) - (None in row) + len(row.get(None) or [])} field(s)")
        text = (row.get("theta_max_over_alpha") or "").strip()
        flag = (row.get("overturned") or "").strip().lower()
        if flag not in _TRUE and flag not in _FALSE:
            raise ExperimentError("invalid overturned flag", file=file, line=k, key="overturned",
                                  expected="true/false (or 1/0)", found=repr(flag))
        marked_ot = text.lower() in ("inf", "+inf", "ot", "overturned")
        if flag in _FALSE and flag and marked_ot:     # an explicit "not overturned" beside θ_max/α = inf
            raise ExperimentError("the row contradicts itself", file=file, line=k, key="overturned",
                                  expected="overturned = true for θ_max/α = inf/OT (or a finite θ_max/α)",
                                  found=f"overturned = {flag!r} and theta_max_over_alpha = {text!r}")
        if flag in _TRUE and not marked_ot and text:
            try:
                finite = float(text.replace(",", ".") if "," in text and "." not in text else text)
            except ValueError:
                finite = math.nan
            if math.isfinite(finite) and finite < 1.0:   # θ_max < α: the body never passed its tipping angle
                raise ExperimentError("the row contradicts itself", file=file, line=k, key="overturned",
                                      expected="overturned = true only with θ_max/α ≥ 1 (a run that overturns "
                                               "passes θ = α) or inf/OT",
                                      found=f"overturned = {flag!r} and theta_max_over_alpha = {text!r}")
        if flag in _TRUE or marked_ot:
            values.append(math.inf)
        else:
            try:   # a decimal comma ("0,5") as Excel writes it beside semicolons
                v = float(text.replace(",", ".") if "," in text and "." not in text else text)
            except ValueError:
                v = math.nan
            if not (math.isfinite(v) and v >= 0.0):
                raise ExperimentError("invalid θ_max/α", file=file, line=k, key="theta_max_over_alpha",
                                      expected="a number ≥ 0, or inf/OT for an overturned run", found=repr(text))
            values.append(v)
        ids.append((row.get("id") or "").strip())
    if len(values) < 2:
        raise ExperimentError("too few runs", file=file, expected="at least 2 rows", found=str(len(values)))
    if "id" in rows[0][1]:   # ids pair tests with model runs: every row has one, each once
        lines = [k for k, _ in rows]
        for k, rid in zip(lines, ids):
            if not rid:
                raise ExperimentError("missing id", file=file, line=k, key="id",
                                      expected="an id on every row (it pairs tests with model runs)", found="''")
        first: dict[str, int] = {}
        for k, rid in zip(lines, ids):
            if rid in first:
                raise ExperimentError("duplicate id", file=file, line=k, key="id",
                                      expected="each id once (it pairs tests with model runs)",
                                      found=f"'{rid}' again (first on line {first[rid]})")
            first[rid] = k
    return MixedSample(name, np.asarray(values, dtype=float), ids if "id" in rows[0][1] else [], file)


def _rows(path: Path, file: str) -> tuple[list[tuple[int, dict]], int]:
    """(line number, row) of a results CSV (UTF-8 with or without the byte-order mark Excel writes;
    comma-, semicolon- or tab-separated as the header shows; ``#`` lines are comments) and the header's
    line number."""
    data = path.read_bytes()
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise ExperimentError("not UTF-8 text", file=file, line=line,
                              expected="a CSV saved as UTF-8 (Excel: 'CSV UTF-8')",
                              found=f"byte 0x{data[exc.start]:02x} (another encoding, e.g. Latin-1)") from None
    numbered = [(k, ln) for k, ln in enumerate(text.splitlines(), start=1)
                if ln.strip() and not ln.lstrip().startswith("#")]
    if not numbered:
        return [], 1
    header = numbered[0][1]
    delimiter = next((d for d in (",", ";", "\t") if d in header), ",")
    reader = csv.DictReader((ln for _, ln in numbered), delimiter=delimiter)
    rows = [(numbered[i + 1][0], row) for i, row in enumerate(reader)]
    if not rows:
        return [], numbered[0][0]
    for _, row in rows:
        for key in [k for k in row if isinstance(k, str) and k != k.strip()]:
            row[key.strip()] = row.pop(key)
    return rows, numbered[0][0]


def kolmogorov_distance(a: MixedSample, b: MixedSample) -> float:
    """sup_x |F_a(x) − F_b(x)| of the two empirical mixed CDFs (Sec 7.1.1)."""
    x = np.concatenate([a.conditional, b.conditional, [np.inf]])
    return float(np.max(np.abs(a.cdf(x) - b.cdf(x)))) if x.size else 0.0


def proportions_test(a: MixedSample, b: MixedSample) -> dict:
    """Two-sided test of equal overturning proportions (pooled z test ≡ Pearson χ², Sec 7.2.1)."""
    table = np.array([[a.n_overturned, a.n - a.n_overturned], [b.n_overturned, b.n - b.n_overturned]])
    diff = a.p_overturn - b.p_overturn
    if table[:, 0].sum() == 0 or table[:, 1].sum() == 0:
        z, p_value = 0.0, 1.0   # no (or only) overturning in both: the proportions are equal
    else:
        chi2, p_value, _, _ = stats.chi2_contingency(table, correction=False)
        z = math.copysign(math.sqrt(chi2), diff)
    return {"statistic": diff, "z": z, "p_value": float(p_value), "evidence": evidence(float(p_value))}


def ks_test(a: MixedSample, b: MixedSample) -> dict:
    """Two-sample Kolmogorov–Smirnov test of the conditional CDFs F̄ (Sec 7.2.2)."""
    ca, cb = a.conditional, b.conditional
    if ca.size == 0 or cb.size == 0:
        return {"statistic": None, "p_value": None, "evidence": "not testable (a sample has no non-overturned run)"}
    res = stats.ks_2samp(ca, cb)
    return {"statistic": float(res.statistic), "p_value": float(res.pvalue), "evidence": evidence(float(res.pvalue))}


def table_7_2(sample: MixedSample) -> dict:
    """Percentiles (25/50/75 %, None = overturned) and conditional mean/SD (ddof = 1) of θ_max/α."""
    cond = sample.conditional
    out = {str(q): sample.percentile(q) for q in PERCENTILES}
    out["conditional_mean"] = float(np.mean(cond)) if cond.size else None
    out["conditional_sd"] = float(np.std(cond, ddof=1)) if cond.size > 1 else None
    return out


def relative_errors(model: dict, tests: dict) -> dict:
    """Δθ/θ_exp = (θ_num − θ_exp)/θ_exp per Table 7.2 row (None where either is OT or θ_exp = 0)."""
    out = {}
    for key in [str(q) for q in PERCENTILES] + ["conditional_mean"]:
        m, t = model.get(key), tests.get(key)
        out[key] = (m - t) / t if (m is not None and t not in (None, 0.0)) else None
    return out


def split_tests(tests: MixedSample, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Seeded random split of the test indices into D1 (⌊n/2⌋) and D2 (the rest) (Sec 7.2)."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ExperimentError("invalid random seed", key="seed", expected="an integer ≥ 0", found=repr(seed))
    order = np.random.default_rng(seed).permutation(tests.n)
    half = tests.n // 2
    return np.sort(order[:half]), np.sort(order[half:])


def _model_on(model: MixedSample, tests: MixedSample, d2: np.ndarray, name: str) -> tuple[MixedSample, str]:
    """The model runs for D2's motions: matched by id when both files have ids (every test's id must
    be among the model's), else by row (same number of runs), else all runs."""
    if tests.ids and model.ids:
        where = {rid: k for k, rid in enumerate(model.ids)}
        missing = [rid for rid in tests.ids if rid not in where]
        if missing:
            shown = ", ".join(repr(m) for m in missing[:4]) + (f" and {len(missing) - 4} more" if len(missing) > 4
                                                               else "")
            raise ExperimentError("tests without a model run of the same id", file=model.file or None, key="id",
                                  expected=f"every test id of '{tests.file or tests.name}' among the ids of "
                                           f"'{model.file or model.name}'",
                                  found=f"{len(missing)} of {tests.n}: {shown}")
        return model.subset(np.array([where[tests.ids[i]] for i in d2]), name), "id"
    if model.n == tests.n:
        return model.subset(d2, name), "row"
    return MixedSample(name, model.values, model.ids), "all"


@dataclass
class Validation:
    """The Ch. 7 comparison; ``as_json()`` has the documented keys."""

    samples: dict
    seed: int
    split: tuple
    pairing: str
    proportions: list
    ks: list
    percentiles: dict
    errors: dict
    distances: dict

    @property
    def overturn_at(self) -> float:
        """Where the figure draws the overturning mass (right of every non-overturned θ_max/α)."""
        return self.plot_limit

    @property
    def plot_limit(self) -> float:
        finite = np.concatenate([s.conditional for s in self.samples.values()])
        return 1.1 * max(1.0, float(finite.max()) if finite.size else 1.0)

    def as_json(self) -> dict:
        tests = self.samples["tests"]
        analyses = self.samples["analyses"]
        out = {"n_tests": tests.n, "n_analyses": analyses.n, "p_overturn_tests": tests.p_overturn,
               "p_overturn_analyses": analyses.p_overturn,
               "kolmogorov_distance": self.distances["analyses"],
               "proportions": self.proportions, "ks": self.ks, "percentiles": self.percentiles,
               "relative_errors": self.errors, "seed": self.seed, "split": {"D1": len(self.split[0]),
                                                                            "D2": len(self.split[1])},
               "model_pairing": self.pairing,
               "dkw_epsilon": {f"{int(c * 100)}%": tests.dkw_epsilon(1.0 - c) for c in CONFIDENCES}}
        if "analyses_measured_cr" in self.samples:
            m = self.samples["analyses_measured_cr"]
            out.update(n_analyses_measured_cr=m.n, p_overturn_analyses_measured_cr=m.p_overturn,
                       kolmogorov_distance_measured_cr=self.distances["analyses_measured_cr"])
        return out


def validate(tests: MixedSample, analyses: MixedSample, measured: MixedSample | None = None, *,
             seed: int = 1) -> Validation:
    """The Ch. 7 comparison of ``tests`` with ``analyses`` (theoretical c_r) and optionally
    ``measured`` (model with the measured c_r); ``seed`` fixes the D1/D2 split."""
    samples = {"tests": tests, "analyses": analyses}
    if measured is not None:
        samples["analyses_measured_cr"] = measured
    d1, d2 = split_tests(tests, seed)
    test_d1, test_d2 = tests.subset(d1, "tests D1"), tests.subset(d2, "tests D2")
    stages = [("1: tests D1 vs tests D2", test_d2)]
    model_d2, pairing = _model_on(analyses, tests, d2, "analyses D2")
    stages.append(("2: tests D1 vs model (theoretical c_r)", model_d2))
    if measured is not None:
        stages.append(("3: tests D1 vs model (measured c_r)", _model_on(measured, tests, d2, "measured D2")[0]))
    proportions = [{"stage": name, **proportions_test(test_d1, other)} for name, other in stages]
    ks = [{"stage": name, **ks_test(test_d1, other)} for name, other in stages]
    percentiles = {name: table_7_2(s) for name, s in samples.items()}
    errors = {name: relative_errors(percentiles[name], percentiles["tests"]) for name in samples if name != "tests"}
    distances = {name: kolmogorov_distance(tests, s) for name, s in samples.items() if name != "tests"}
    return Validation(samples, seed, (d1, d2), pairing, proportions, ks, percentiles, errors, distances)
