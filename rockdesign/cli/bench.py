"""``rockdesign bench [--quick] [-o DIR]``: work-precision charts, stability study, speed summary (CONTRACT §2, §4).

Writes to DIR: ``bench.json`` (CONTRACT §4 plus extra keys), ``wp_*.png|svg`` work-precision charts,
``stability.md`` with ``stability_*.png|svg`` evidence plots.  Prints the highlights, the stability
table and the summary of ``benchmarks/results/*.json``.  ``--docs docs`` also publishes the run into
the documentation (:mod:`rockdesign.bench.publish`).
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.table import Table

from ..console import make_console
from ..errors import RockdesignError


class BenchError(RockdesignError):
    """Invalid ``bench`` options."""


def _console() -> Console:
    console = make_console(highlight=False, soft_wrap=True)
    if not console.is_terminal:
        console.width = 160
    return console


def run_bench(out_dir: Path, quick: bool = False, only: Optional[str] = None, stability: bool = True,
              progress=None, stages=None) -> dict:
    """Run the study, write every output file into ``out_dir`` and return the bench.json object.

    Args:
        out_dir: output folder (created).
        quick: CI-scale run (3 tolerances, fewer repeats, 12-s record, reduced stability cases).
        only: comma-separated filters on problem keys ``name/system`` (substring match), e.g.
            ``"free-vibration/housner-block"``; None = all problems.
        stability: also run the stability study and write stability.md.
        progress: callback for progress lines.
        stages: ``stages(stage, done, total)`` as problems and stability cases finish (progress bars).
    """
    from .. import write_study_figures
    from .. import problem_set
    from .. import highlights, run_study
    from .. import json_ready
    from .. import speed_summary
    t0 = time.perf_counter()
    problems = problem_set(quick=quick)
    if only:
        keys = [k.strip() for k in only.split(",") if k.strip()]
        problems = [p for p in problems if any(k in p.key for k in keys)]
        if not problems:
            raise BenchError("no problem matches", key="--only",
                             expected="substrings of name/system, e.g. free-vibration/housner-block, ricker-anti, "
                                      "record-30s-linearized", found=repr(only))
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    histories: dict = {}
    bar = stages or (lambda stage, done, total: None)
    bar("work-precision problems", 0, len(problems))
    study = run_study(quick=quick, problems=problems, progress=progress, histories=histories,
                      step=lambda done, total: bar("work-precision problems", done, total))
    figures = write_study_figures(study, out_dir, histories)
    study["highlights"] = highlights(study)
    if stability:
        from .. import run_stability, stability_markdown, write_stability_figures
        cases = run_stability(quick=quick, progress=progress,
                              step=lambda done, total: bar("stability cases", done, total))
        stab_figs = write_stability_figures(cases, out_dir)
        (out_dir / "stability.md").write_text(stability_markdown(cases, stab_figs, machine=study["machine"]))
        study["stability"] = [c.as_json() for c in cases]
        figures += [p for paths in stab_figs.values() for p in paths]
    study["speed_benchmarks"] = speed_summary()
    study["files"] = sorted(p.name for p in figures) + (["stability.md"] if stability else []) + ["bench.json"]
    study["seconds"] = time.perf_counter() - t0
    (out_dir / "bench.json").write_text(json.dumps(json_ready(study), indent=1, ensure_ascii=False) + "\n")
    return study


def print_summary(study: dict, console: Console) -> None:
    """Highlights table, stability table and speed-benchmark summary."""
    m = study["machine"]
    console.print(f"rockdesign bench — {m['date']} — {m['uname']} ({m['cpu']}, {m['nproc']} cores)")
    rtol = min(study["tolerances"], key=lambda x: abs(x - 1e-10) / x)
    t = Table(title=f"Work-precision highlights (rockdesign at rtol {rtol:.0e}; cost of the best scipy method at "
                    "equal accuracy, as a multiple of rockdesign's)")
    for col in ("problem", "system", "rockdesign ms", "max |Δθ| [rad]", "impact Δt [s]", "ref. bound [rad]",
                "scipy ×, 1e-6 rad", "scipy ×, 1e-9 rad", "scipy crashes"):
        t.add_column(col, justify="left" if col in ("problem", "system") else "right")

    def fmt(x, f):
        return "–" if x is None else format(x, f)
    for r in study.get("highlights", []):
        t.add_row(r["problem"], r["system"], fmt(r["ms"], ".2f"), fmt(r["error_theta"], ".1e"),
                  fmt(r["error_impact_times"], ".1e"), fmt(r["reference_bound"], ".0e"),
                  fmt(r.get("scipy_best_ratio_1e-06"), ".0f"), fmt(r.get("scipy_best_ratio_1e-09"), ".0f"),
                  str(r["failures"]))
    console.print(t)
    if study.get("stability"):
        methods = list(dict.fromkeys(o["method"] for c in study["stability"] for o in c["outcomes"]))
        s = Table(title="Stability study (details in stability.md)")
        s.add_column("condition")
        for name in methods:
            s.add_column(name)
        for c in study["stability"]:
            verdicts = {o["method"]: o["verdict"] for o in c["outcomes"]}
            s.add_row(c["condition"], *[verdicts.get(name, "–") for name in methods])
        console.print(s)
    from .. import speed_format_value as format_value
    speed = study.get("speed_benchmarks") or []
    if speed:
        b = Table(title="Speed benchmarks (benchmarks/results/*.json)")
        for col in ("benchmark", "date", "headline numbers"):
            b.add_column(col)
        for item in speed:
            heads = "; ".join(f"{k.removeprefix('summary.')} = {format_value(v)}"
                              for k, v in list(item.get("headline", {}).items())[:12])
            b.add_row(item["name"], str(item.get("date") or "–"), heads or item.get("error", "–"))
        console.print(b)
    else:
        console.print("no speed benchmark results found (run the scripts in benchmarks/)")


def register(app: typer.Typer, handle_errors) -> None:
    """Add the ``bench`` command to the main CLI (called by :mod:`rockdesign.cli`)."""

    @app.command()
    @handle_errors
    def bench(quick: bool = typer.Option(False, "--quick", metavar=" ", help="CI-scale run: 3 tolerances, fewer repeats, "
                                                                   "12-s record, reduced stability cases."),
              out: Path = typer.Option(Path("bench-results"), "-o", "--out",
                                       help="Output folder for bench.json, figures and stability.md."),
              only: Optional[str] = typer.Option(None, "--only", help="Comma-separated problem filters "
                                                 "(substrings of name/system, e.g. 'free-vibration/housner-block')."),
              no_stability: bool = typer.Option(False, "--no-stability", metavar=" ", help="Skip the stability study."),
              as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print bench.json to stdout instead of tables."),
              docs: Optional[Path] = typer.Option(None, "--docs", help="Also publish into this docs folder: "
                                                  "figures/, stability.md and the latest-numbers blocks of "
                                                  "workprecision.md and ../benchmarks/README.md."),
              verbose: bool = typer.Option(False, "--verbose", "-v", metavar=" ", help="Print one line per measured point.")):
        """Work-precision charts (error vs wall time) and the solver stability study."""
        from .inputs import output_folder
        output_folder(out, "--out")
        if docs is not None:
            output_folder(docs, "--docs")
        err = make_console(stderr=True, highlight=False, soft_wrap=True)
        from .inputs import compile_kernels
        compile_kernels("bench")      # (every point's first run is untimed anyway: this is for the screen)
        progress = (lambda line: err.print(line, markup=False)) if verbose else None
        from .. import progress_bars
        with progress_bars(err, disable=as_json and not err.is_terminal) as stages:
            study = run_bench(out, quick=quick, only=only, stability=not no_stability, progress=progress,
                              stages=stages)
        if docs is not None:
            from .. import publish_docs
            written = publish_docs(study, out, docs, readmes=[docs.parent / "benchmarks" / "README.md"])
            err.print(f"published {len(written)} files into {docs}", markup=False)
        if as_json:
            from .. import json_ready
            sys.stdout.write(json.dumps(json_ready(study), indent=1, ensure_ascii=False) + "\n")
            return
        console = _console()
        print_summary(study, console)
        console.print(f"wrote {out / 'bench.json'}, {len(study['files']) - 1} other files in {out} "
                      f"({study['seconds']:.0f} s)")
