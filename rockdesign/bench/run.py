"""The library function of ``rockdesign bench``: the work-precision study, the solver stability study and the
summary of the speed benchmarks, written to a folder (docs/workprecision.md, docs/stability.md).

    import rockdesign as rd
    b = rd.benchmark("bench-results/", quick=True, only="free-vibration/housner-block", stability=False)
    b.highlights            # per problem: rockdesign's time [ms] and error [rad], scipy's cost at equal accuracy
    b.as_json()             # bench.json (CONTRACT §4 plus extra keys)

Never loaded by a check: the benchmarks measure the engine, they do not produce results.
"""
from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import RockdesignError
from ..execution import compilation
from ..jsonable import json_ready
from ..outdir import refuse_wrong_type
from ..planar.dynamics.warm_up import ENGINE, LINEAR_EXACT
from .figures import write_study_figures
from .problems import problem_set
from .publish import publish_docs
from .runner import highlights, run_study
from .speed import format_value, speed_summary
from .stability import run_stability, stability_markdown, write_stability_figures

__all__ = ["benchmark", "BenchResult", "BenchError"]


class BenchError(RockdesignError):
    """Invalid ``bench`` options."""


@dataclass
class BenchResult:
    """A benchmark run.

    Attributes:
        study: the bench.json object: ``machine``, ``tolerances``, ``problems`` (work-precision points: wall time
            [s] and errors [rad] per method and tolerance), ``highlights``, ``stability`` (one verdict per
            method and condition), ``speed_benchmarks``, ``files``, ``seconds``.
        out_dir: the folder holding bench.json, the figures and stability.md.
        published: the files written into the documentation (``docs``), if any.
    """

    study: dict
    out_dir: Path
    published: list[Path] = field(default_factory=list)

    @property
    def highlights(self) -> list[dict]:
        return self.study.get("highlights", [])

    def as_json(self) -> dict:
        """bench.json (the ``bench --json`` output)."""
        return json_ready(self.study)

    def speed_rows(self) -> list[tuple[str, str, str]]:
        """(benchmark, date, headline numbers) of the speed benchmarks of ``benchmarks/results``."""
        rows = []
        for item in self.study.get("speed_benchmarks") or []:
            heads = "; ".join(f"{k.removeprefix('summary.')} = {format_value(v)}"
                              for k, v in list(item.get("headline", {}).items())[:12])
            rows.append((item["name"], str(item.get("date") or "–"), heads or item.get("error", "–")))
        return rows


def _folder(path, key: str) -> Path:
    path = Path(path).expanduser()
    for p in [path, *path.parents]:
        refuse_wrong_type(p, key, folder=True)
    return path


def benchmark(out_dir: str | Path = "bench-results", *, quick: bool = False, only: str | None = None,
          stability: bool = True, docs: str | Path | None = None,
          progress: Callable[[str, int, int], None] | None = None, log: Callable[[str], object] | None = None,
          say=None) -> BenchResult:
    """Run the work-precision study (error against wall time: rockdesign's engine, its closed form, scipy's
    RK45/DOP853/LSODA/Radau) and the stability study, and write bench.json, the ``wp_*`` and ``stability_*``
    figures (PNG, SVG) and stability.md into ``out_dir``.

    Args:
        out_dir: output folder (created).
        quick: CI-scale run (3 tolerances, fewer repeats, a 12-s record, reduced stability cases).
        only: comma-separated filters on the problem keys ``name/system`` (substrings), e.g.
            ``"free-vibration/housner-block"``; None: every problem.
        stability: also run the stability study and write stability.md.
        docs: also publish the run into this documentation folder (figures/, stability.md and the latest-numbers
            blocks of workprecision.md and ../benchmarks/README.md).
        progress: ``progress(stage, done, total)`` as problems and stability cases finish.
        log: prints one line per measured point.
        say: announces a first-run compilation.
    """
    out = _folder(out_dir, "out_dir")
    docs_dir = None if docs is None else _folder(docs, "docs")
    problems = problem_set(quick=quick)
    if only:
        keys = [k.strip() for k in only.split(",") if k.strip()]
        problems = [p for p in problems if any(k in p.key for k in keys)]
        if not problems:
            raise BenchError("no problem matches", key="only",
                             expected="substrings of name/system, e.g. free-vibration/housner-block, ricker-anti, "
                                      "record-30s-linearized", found=repr(only))
    compilation.prepare("bench", (ENGINE, LINEAR_EXACT), say)      # (every point's first run is untimed anyway: this is for the screen)
    t0 = time.perf_counter()
    out.mkdir(parents=True, exist_ok=True)
    histories: dict = {}
    bar = progress or (lambda stage, done, total: None)
    bar("work-precision problems", 0, len(problems))
    study = run_study(quick=quick, problems=problems, progress=log, histories=histories,
                      step=lambda done, total: bar("work-precision problems", done, total))
    figures = write_study_figures(study, out, histories)
    study["highlights"] = highlights(study)
    if stability:
        cases = run_stability(quick=quick, progress=log, step=lambda done, total: bar("stability cases", done, total))
        stab_figs = write_stability_figures(cases, out)
        (out / "stability.md").write_text(stability_markdown(cases, stab_figs, machine=study["machine"]))
        study["stability"] = [c.as_json() for c in cases]
        figures += [p for paths in stab_figs.values() for p in paths]
    study["speed_benchmarks"] = speed_summary()
    study["files"] = sorted(p.name for p in figures) + (["stability.md"] if stability else []) + ["bench.json"]
    study["seconds"] = time.perf_counter() - t0
    (out / "bench.json").write_text(json.dumps(json_ready(study), indent=1, ensure_ascii=False) + "\n")
    result = BenchResult(study, out)
    if docs_dir is not None:
        result.published = publish_docs(study, out, docs_dir, readmes=[docs_dir.parent / "benchmarks" / "README.md"])
    return result
