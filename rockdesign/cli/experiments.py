"""``rockdesign calibrate | validate | ensemble``: experiments (thesis Ch. 6–7, docs/experiments.md).

The commands parse their options, call ``rd.calibration``, ``rd.validation`` and ``rd.ensemble``
(:mod:`rockdesign.experiments.run`) and print; ``records scale-model`` lives in :mod:`rockdesign.cli.records`.
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
    console = make_console(highlight=False, markup=False, soft_wrap=True)
    if not console.is_terminal:
        console.width = 160
    return console


def _fmt(value, digits: int = 4) -> str:
    return "–" if value is None else f"{value:.{digits}g}"


def calibration_table(cal, console: Console) -> None:
    table = Table(title="free-vibration calibration (thesis Sec 6.3.5, 6.4.3)")
    for col in ("quantity", "measured", "theory", "equation"):
        table.add_column(col)
    table.add_row("p [1/s]", f"{cal.p:.5g} (SD {cal.p_sd:.2g})", f"{cal.p_theory:.5g}", "Eq 2.8 inverted; Eq 3.13/3.76")
    table.add_row("λ [-]", f"{cal.lam:.4g}", "", "from p (Eq 3.13/3.76)")
    table.add_row("c_r, all impacts [-]", f"{cal.c_r:.4f}", f"{cal.c_r_theory:.4f}",
                  f"Eq 6.19 with Eq 2.10; theory {cal.c_r_theory_equation}")
    table.add_row("c_r, left impacts (θ < 0 before) [-]", _fmt(cal.c_r_left), "", "Eq 6.19")
    table.add_row("c_r, right impacts (θ > 0 before) [-]", _fmt(cal.c_r_right), "", "Eq 6.19")
    table.add_row("energy loss per impact 1 − c_r [%]", f"{100 * (1 - cal.c_r):.3g}",
                  f"{100 * (1 - cal.c_r_theory):.3g}", "")
    table.add_row("half-cycles used", str(len(cal.half_cycles)), "", "")
    table.add_row("α [rad]", f"{cal.alpha:.5g}", "", "")
    table.add_row("offset (θ = 0 of the body) [rad]", f"{cal.offset:.3g} ({cal.offset_source})", "", "")
    table.add_row("noise SD [rad]", f"{cal.noise:.2g}", "", "")
    console.print(table)
    for w in cal.warnings:
        console.print(f"warning: {w}")


def validation_tables(data: dict, console: Console) -> None:
    names = list(data["percentiles"])
    table = Table(title="θ_max/α: percentiles and conditional moments (thesis Table 7.2 layout; OT = overturned)")
    table.add_column("")
    for name in names:
        table.add_column(name)
        if name != "tests":
            table.add_column("Δθ/θ_exp")
    for key, label in (("25", "25th percentile"), ("50", "50th percentile"), ("75", "75th percentile"),
                       ("conditional_mean", "conditional mean"), ("conditional_sd", "conditional SD")):
        cells = [label]
        for name in names:
            v = data["percentiles"][name][key]
            cells.append(("OT" if key in ("25", "50", "75") else "–") if v is None else f"{v:.3f}")
            if name != "tests":
                e = data["relative_errors"][name].get(key)
                cells.append("–" if e is None else f"{e:+.3f}")
        table.add_row(*cells)
    console.print(table)
    console.print(f"tests: n = {data['n_tests']}, p_o = {data['p_overturn_tests']:.3f}; model: n = {data['n_analyses']}, "
                  f"p_o = {data['p_overturn_analyses']:.3f}; Kolmogorov distance {data['kolmogorov_distance']:.3f}"
                  + (f" (measured c_r: {data['kolmogorov_distance_measured_cr']:.3f})"
                     if "kolmogorov_distance_measured_cr" in data else ""))
    console.print(f"model runs paired with the tests by {data['model_pairing']}"
                  + {"id": "", "row": " (no ids in both files: row k with row k)",
                     "all": " (no ids in both files and different numbers of runs: the whole model sample)"}
                  [data["model_pairing"]])
    console.print(f"DKW band half-width on the test CDF: {data['dkw_epsilon']['90%']:.3f} (90 %), "
                  f"{data['dkw_epsilon']['95%']:.3f} (95 %)")
    for key, title, stat in (("proportions", "test of equal proportions of overturning (Sec 7.2.1)", "p_D1 − p_other"),
                             ("ks", "two-sample Kolmogorov–Smirnov test of F̄ (Sec 7.2.2)", "D")):
        table = Table(title=f"{title}; split seed {data['seed']}")
        for col in ("stage", stat, "p-value", "evidence (Table 7.3)"):
            table.add_column(col)
        for row in data[key]:
            table.add_row(row["stage"], _fmt(row["statistic"], 3), _fmt(row["p_value"], 3), row["evidence"])
        console.print(table)


def register(app: typer.Typer, handle_errors) -> None:
    @app.command()
    @handle_errors
    def calibrate(project: Path = typer.Argument(..., help="Project file (TOML) of the specimen."),
                  free_vibration: Path = typer.Option(..., "--free-vibration", help="Measured tilt history CSV: "
                                                      "columns t [s] and theta [rad] (or theta_deg)."),
                  as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print JSON (SI units)."),
                  plot: Optional[Path] = typer.Option(None, "--plot", help="Measured vs simulated θ/α (png/svg/pdf)."),
                  half_cycles: int = typer.Option(20, "--half-cycles", min=2, help="Use at most this many half-cycles."),
                  min_amplitude: float = typer.Option(0.05, "--min-amplitude", help="Ignore half-cycles with "
                                                      "θ0 below this fraction of α.")):
        """Back-calculate p, λ and c_r (left/right) from a free-vibration test (thesis Sec 6.3.5, 6.4.3)."""
        import rockdesign as rd
        from .inputs import FIGURE_SUFFIXES, output_file
        output_file(plot, "--plot", FIGURE_SUFFIXES)
        proj = rd.load_project(project)
        run = rd.calibration(proj, free_vibration, half_cycles=half_cycles, min_amplitude=min_amplitude)
        cal, history = run.calibration, run.history
        if plot is not None:
            run.write_figure(plot, say=make_console(stderr=True).print)
        if as_json:
            sys.stdout.write(json.dumps(cal.as_json(), indent=2) + "\n")
            return
        console = _console()
        if history.dropped_rows:
            console.print(f"{history.dropped_rows} row(s) with missing values skipped")
        calibration_table(cal, console)
        console.print(f"use it: restitution = {cal.c_r:.4f} and mass_distribution = {cal.lam:.4f} in the project file")
        if plot is not None:
            console.print(f"plot written to {plot}")

    @app.command()
    @handle_errors
    def validate(tests: Path = typer.Option(..., "--tests", help="Test results CSV (theta_max_over_alpha, "
                                            "overturned, id)."),
                 analyses: Path = typer.Option(..., "--analyses", help="Model results CSV (theoretical c_r)."),
                 measured: Optional[Path] = typer.Option(None, "--analyses-measured-cr",
                                                         help="Model results CSV with the measured c_r."),
                 seed: int = typer.Option(1, "--seed", help="Seed of the random D1/D2 split of the tests."),
                 as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print JSON."),
                 out: Optional[Path] = typer.Option(None, "-o", "--out", help="Folder for validation.json, "
                                                    "figure, report.html/pdf."),
                 no_pdf: bool = typer.Option(False, "--no-pdf", metavar=" ", help="With -o: HTML report only."),
                 plot: Optional[Path] = typer.Option(None, "--plot", help="Write the CDF figure (png/svg/pdf).")):
        """Compare test and model statistics of θ_max/α (thesis Ch. 7: Eq 7.1, Tables 7.2, 7.3)."""
        import rockdesign as rd
        from .inputs import FIGURE_SUFFIXES, output_file, output_folder
        if out is not None:
            output_folder(out, "-o/--out")
        output_file(plot, "--plot", FIGURE_SUFFIXES)
        result = rd.validation(tests, analyses, measured=measured, seed=seed, out_dir=out, pdf=not no_pdf)
        data = result.as_json()
        if plot is not None:
            result.write_figure(plot)
        if as_json:
            sys.stdout.write(json.dumps(data, indent=2) + "\n")
            return
        console = _console()
        validation_tables(data, console)
        if out is not None:
            console.print(f"wrote {out}/validation.json, validation.png/.svg, report.html"
                          + ("" if no_pdf else ", report.pdf"))

    @app.command()
    @handle_errors
    def ensemble(project: Path = typer.Argument(..., help="Project file (TOML)."),
                 suite: str = typer.Option(..., "--suite", help="Ensemble: suite name or manifest path (e.g. the "
                                           "ensemble.toml written by 'records synth')."),
                 out: Path = typer.Option(..., "-o", "--out", help="analyses.csv to write."),
                 scale: float = typer.Option(1.0, "--scale", help="Factor on every motion."),
                 restitution: Optional[float] = typer.Option(None, "--restitution", help="c_r to use instead "
                                                             "of the project's (e.g. measured)."),
                 records_dir: Optional[Path] = typer.Option(None, "--records-dir", help="Folder of PEER AT2 files."),
                 as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print the results as JSON.")):
        """Run a project over a ground-motion ensemble and write the analyses.csv that 'validate' reads."""
        import rockdesign as rd
        from .inputs import output_file
        output_file(out, "-o/--out")
        proj = rd.load_project(project)
        err = make_console(stderr=True)
        with rd.progress_bars(err, disable=as_json and not err.is_terminal) as progress:
            result = rd.ensemble(proj, suite, scale=scale, restitution=restitution, records_dir=records_dir,
                                 progress=progress, say=err.print)
        result.write_csv(out)
        data = result.as_json()
        if as_json:
            sys.stdout.write(json.dumps(data, indent=2) + "\n")
            return
        _console().print(f"{data['n']} analyses of {proj.name} over {result.suite} ({result.model}, c_r = "
                         f"{result.c_r:.4f}): {data['n_overturned']} overturned (p_o = {data['p_overturn']:.3f}); "
                         f"wrote {out}")
