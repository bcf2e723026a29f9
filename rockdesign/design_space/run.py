"""The design chart of a project (``rockdesign design``, :func:`design`): variants → grid → files (SPEC §15)."""
from __future__ import annotations

import json
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..errors import ProjectError, RockdesignError
from ..kinds import kind_of
from ..kinds import parse_document
from ..library import load_project
from .grid import GridRun, check_exit_code, recommended, run_grid
from .variants import parse_vary, variants


@dataclass
class DesignResult:
    """A design chart: the base project, the grid's cells and the recommendation; ``as_json()`` is design.json."""

    project: object
    grid: GridRun
    recommended: dict | None
    settings: dict

    def as_json(self) -> dict:
        from ..report.design_results import design_json
        return design_json(self.project, self.grid, self.recommended, settings=self.settings)

    @property
    def exit_code(self) -> int:
        return check_exit_code(self.grid.cells)


def design(project_path, vary: list[str], *, records_dir: str | None = None, executor=None, store: Path | None = None,
           progress=None, stage_progress=None, option_keys: dict | None = None) -> DesignResult:
    """Check every variant of ``vary`` (one or two ``TABLE.KEY=FROM:TO:N``) of the project file at
    ``project_path``; ``store``: folder of per-variant results (resume); ``progress(done, total, cell)``;
    ``option_keys``: the command-line names of ``records_dir``/``executor`` for error messages.

    Raises:
        RockdesignError: an unreadable project or ``--vary``, an option the project's kind has no use for
            (a cylinder's pairs are built in and analysed in this process: no ``records_dir``/``executor``),
            or an excitation no variant can run.
    """
    base = load_project(project_path)
    if not vary or len(vary) > 2:
        raise RockdesignError("one or two variables", key="--vary", expected="--vary once or twice",
                              found=f"{len(vary)} time(s)")
    kind = kind_of(base)
    kind.check_options(base, records_dir=records_dir, executor=executor)
    raw = tomllib.loads(base.source_text) if base.source_text else base.raw
    variables = [parse_vary(v, raw, alternatives=kind.key_alternatives) for v in vary]
    if len(variables) == 2 and variables[0].key == variables[1].key:
        raise RockdesignError("the same key twice", key="--vary", expected="two different keys",
                              found=variables[0].key)
    cells = variants(raw, variables, file=str(project_path))
    if base.excitation_raw is None:
        raise ProjectError("the design chart needs an excitation", file=base.path, key="excitation.design_pga",
                           expected="[excitation] with design_pga", found="no [excitation] table")
    grid = run_grid(cells, variables, records_dir=records_dir, executor=executor, store=store, progress=progress,
                    stage_progress=stage_progress)
    settings = {"early_stopping": kind.design_skipped, "verdict_rule": kind.design_rule,
                "executor": "dask" if executor is not None else "local",
                "shared_batches": grid.shared_batches}
    return DesignResult(base, grid, recommended(grid.cells, kind.design_material), settings)


def recommended_check(result: DesignResult, *, records_dir: str | None = None):
    """The full ``rockdesign check`` (every stage) of the recommended variant: its summary goes into the
    design report, and its verdict must be PASS like its cell's."""
    from .variants import variant_document, variant_toml
    idx = tuple(result.recommended["index"])
    base = result.project
    raw = tomllib.loads(base.source_text) if base.source_text else base.raw
    doc, _ = variant_document(raw, result.grid.variables, idx)
    proj = parse_document(doc, file=f"{result.project.path} [recommended]", text=variant_toml(doc))
    return kind_of(proj).check(proj, progress=None, records_dir=records_dir, margins=True, executor=None)


OPTION_KEYS = {"records_dir": "--records-dir", "executor": "--dask"}
"""The command-line options of :func:`design`'s parameters (errors of ``rockdesign design`` name these)."""


def design_command(project, vary, out, *, as_json: bool, no_pdf: bool, records_dir, dask, console, stdout) -> int:
    """The CLI's ``design``: run, write DIR (design.json, design.csv, design.html/pdf, figures), print."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
    from ..execution.compilation import prepare
    target = Path(out if out is not None else f"{Path(project).stem}_design").expanduser()
    if target.exists() and not target.is_dir():
        raise RockdesignError("not a folder", key="-o/--out", expected="a folder (created if missing)",
                              found=f"a file {target}")
    base = load_project(project)     # input errors before compiling anything
    kind = kind_of(base)
    kind.check_options(base, records_dir=records_dir, executor=dask)
    prepare(kind.check_kernels, console.print)
    executor = None
    if dask:
        from ..execution.executor import make_executor
        executor = make_executor(dask)
        executor.start()
    target.mkdir(parents=True, exist_ok=True)
    bar = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                   console=console, disable=as_json and not console.is_terminal)

    def on_variant(done, total, cell):
        labels = ", ".join(f"{k} = {v}" for k, v in cell["labels"].items())
        how = " (stored)" if cell.get("resumed") else ""
        bar.console.print(f"[{done}/{total}] {labels}: {cell['verdict']}{how}", highlight=False)
        bar.update(task, completed=done, total=total)

    try:
        with bar:
            task = bar.add_task("design variants", total=None)
            result = design(project, vary, records_dir=records_dir, executor=executor, store=target / "variants",
                            progress=on_variant, option_keys=OPTION_KEYS)
    finally:
        if executor is not None:
            executor.close()
    data = result.as_json()
    from ..report.design_results import write_design_csv, write_design_json
    write_design_json(data, target / "design.json")
    write_design_csv(data, target / "design.csv")
    if not no_pdf:
        from ..report.design_report import write_design_report
        full = None
        if result.recommended is not None:
            with console.status("full check of the recommended design"):
                full = recommended_check(result, records_dir=records_dir)
            data["recommended"]["check"] = {"verdict": full.verdict, "reason": full.verdict_reason}
            if full.verdict != "PASS":      # the grid's cell and the full check must agree: say so loudly
                console.print(f"[bold red]warning:[/] the full check of the recommended design gives "
                              f"{full.verdict}: {full.verdict_reason}", highlight=False)
            write_design_json(data, target / "design.json")
        with console.status("writing the design report (charts, PDF)"):
            write_design_report(result, data, target, recommended_check=full)
    if as_json:
        stdout.write(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    else:
        _summary(data, target, console)
    return result.exit_code


def _summary(data: dict, target: Path, console) -> None:
    counts = {}
    for c in data["cells"]:
        counts[c["verdict"]] = counts.get(c["verdict"], 0) + 1
    console.print(f"{len(data['cells'])} variants: " + ", ".join(f"{n} {v}" for v, n in sorted(counts.items())),
                  highlight=False)
    rec = data["recommended"]
    if rec:
        console.print("recommended: " + ", ".join(f"{k} = {v}" for k, v in rec["labels"].items())
                      + f" — {rec['reason']}", highlight=False)
    else:
        console.print("no variant passes", highlight=False)
    console.print(f"analyses run: {data['analyses_run']}; saved by shared work and early stopping: at least "
                  f"{data['analyses_saved']}", highlight=False)
    console.print(f"written: {target}", highlight=False)
