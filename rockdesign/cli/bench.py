"""``rockdesign bench [--quick] [-o DIR]``: work-precision charts, stability study, speed summary (CONTRACT §2, §4).

Writes to DIR: ``bench.json`` (CONTRACT §4 plus extra keys), ``wp_*.png|svg`` work-precision charts,
``stability.md`` with ``stability_*.png|svg`` evidence plots.  Prints the highlights, the stability
table and the summary of ``benchmarks/results/*.json``.  ``--docs docs`` also publishes the run into
the documentation (:mod:`rockdesign.bench.publish`).
"""
from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.table import Table

from ..console import make_console


def _console() -> Console:
    console = make_console(highlight=False, soft_wrap=True)
    if not console.is_terminal:
        console.width = 160
    return console


def print_summary(result, console: Console) -> None:
    """Highlights table, stability table and speed-benchmark summary."""
    study = result.study
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
    speed = result.speed_rows()
    if speed:
        b = Table(title="Speed benchmarks (benchmarks/results/*.json)")
        for col in ("benchmark", "date", "headline numbers"):
            b.add_column(col)
        for row in speed:
            b.add_row(*row)
        console.print(b)
    else:
        console.print("no speed benchmark results found (run the scripts in benchmarks/)")


def register(app: typer.Typer, handle_errors) -> None:
    """Add the ``bench`` command to the main CLI (called by :mod:`rockdesign.cli`)."""

    @app.command()
    @handle_errors(out_dir="-o/--out")
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
        import rockdesign as rd
        from .inputs import output_folder
        output_folder(out, "--out")
        if docs is not None:
            output_folder(docs, "--docs")
        err = make_console(stderr=True, highlight=False, soft_wrap=True)
        log = (lambda line: err.print(line, markup=False)) if verbose else None
        with rd.progress_bars(err, disable=as_json and not err.is_terminal) as stages:
            result = rd.benchmark(out, quick=quick, only=only, stability=not no_stability, docs=docs, progress=stages,
                              log=log, say=err.print)
        if docs is not None:
            err.print(f"published {len(result.published)} files into {docs}", markup=False)
        if as_json:
            sys.stdout.write(json.dumps(result.as_json(), indent=1, ensure_ascii=False) + "\n")
            return
        console = _console()
        print_summary(result, console)
        console.print(f"wrote {out / 'bench.json'}, {len(result.study['files']) - 1} other files in {out} "
                      f"({result.study['seconds']:.0f} s)")
