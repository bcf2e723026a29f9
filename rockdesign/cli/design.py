"""``rockdesign design``: the check over a grid of one or two project keys, with design charts (CONTRACT §6.3).

The command calls the library (:func:`rockdesign.design_space.run.plan_design`, ``run_design``,
``write_design``) step by step: every input is validated first (the project, ``--dask``, ``-o``, ``--vary``,
the records), then the kernels compile on a first run, then the variants are analysed with progress drawn
here (the library takes callbacks and draws nothing).  The library's errors name its parameters (``vary``,
``out_dir``…); this module alone names them as the command's options (:data:`OPTIONS`).
"""
from __future__ import annotations

import contextlib
import json
import sys
import threading
import time
from pathlib import Path
from typing import List, Optional

import typer
from ..console import make_console

OPTIONS = {"vary": "--vary", "out_dir": "-o/--out", "records_dir": "--records-dir", "executor": "--dask",
           "dask": "--dask", "project": "PROJECT", "prefer": "--prefer", "tolerance": "--tolerance"}
"""The library's parameter names → this command's options (in error messages)."""

SLOW = 30.0
"""Seconds without progress after which the command says what it is doing and why it takes long."""
WATCH_EVERY = 1.0
"""Seconds between two looks of the watchdog at the progress (the silence is said at most this late)."""


def register(app: typer.Typer, handle_errors) -> None:
    @app.command()
    @handle_errors(executor="--dask")
    def design(project: Path = typer.Argument(..., help="Project file (TOML)"),
               vary: List[str] = typer.Option(..., "--vary", metavar="TABLE.KEY=FROM:TO:N", help="A key of the "
                                              "project file and N values from FROM to TO in the key's units, e.g. "
                                              "podium.width=0.36m:0.60m:7 or podium.columns=6:10:3 "
                                              "(once or twice)."),
               out: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder, written when the run "
                                                  "completes; it keeps the finished variants (variants/) so an "
                                                  "interrupted run resumes (default: <project>_design)."),
               as_json: bool = typer.Option(False, "--json", metavar=" ", help="Print design.json to stdout."),
               no_pdf: bool = typer.Option(False, "--no-pdf", metavar=" ", help="Skip the report (and the full "
                                           "check of the recommended design): design.json/csv only."),
               records_dir: Optional[Path] = typer.Option(None, "--records-dir", help="Folder of PEER AT2 files."),
               dask: Optional[str] = typer.Option(None, "--dask", help="Run the analyses on dask.distributed: "
                                                  "'local:N' or a scheduler address (tcp://host:8786); the "
                                                  "variants run on the cluster together."),
               every_cell: bool = typer.Option(False, "--every-cell", metavar=" ", help="Analyse every cell "
                                               "(default: a coarse grid first, then the cells where the answer "
                                               "changes; cells between agreeing neighbours are left unanalysed "
                                               "and shown as such)."),
               prefer: Optional[str] = typer.Option(None, "--prefer", metavar="material|shear", help="What the "
                                                    "recommendation minimises among robust passing variants "
                                                    "(default: the superstructure's shear coefficient where "
                                                    "there is one, else the material)."),
               tolerance: Optional[List[str]] = typer.Option(None, "--tolerance", metavar="KEY=VALUE",
                                                             help="Construction tolerance of a varied key, "
                                                             "relative (podium.width=1%) or in the key's units "
                                                             "(podium.width=4mm); the recommendation must pass at "
                                                             "each varied key ± its tolerance (default ±1 % of a "
                                                             "length, ±2 % of another key; repeatable).")):
        """Design chart: the check of every variant of one or two keys, the pass/fail region, contours of ACMR and of the superstructure's shear coefficient (a cylinder: of its overturning record pairs), and the recommended design (exit 0 = at least one variant passes, 1 = none does, 2 = input error, 3 = internal error, 130 = interrupted)."""  # noqa: E501  (one paragraph: the help rewraps it)
        # the heavy modules (numpy, numba, pint, scipy) are imported here, not at module level: the CLI
        # mounts this command at every start-up (tests/cli/test_startup.py)
        with option_names():
            code = _design(project, vary, out, as_json=as_json, no_pdf=no_pdf, records_dir=records_dir, dask=dask,
                           every_cell=every_cell, prefer=prefer, tolerance=tolerance)
        raise typer.Exit(code)


@contextlib.contextmanager
def option_names():
    """Errors of the library name its parameters; re-name them as this command's options."""
    from ..errors import RockdesignError
    try:
        yield
    except RockdesignError as exc:
        if exc.key in OPTIONS:
            exc.key = OPTIONS[exc.key]
            exc.args = (exc.format(),)
        raise


def _design(project: Path, vary, out, *, as_json: bool, no_pdf: bool, records_dir, dask, every_cell: bool = False,
            prefer: str | None = None, tolerance=None) -> int:
    import rockdesign as rd
    from rich.markup import escape
    err = make_console(stderr=True)
    proj = rd.load_project(project)
    folder = rd.design_folder(out if out is not None else Path(f"{project.stem}_design"), key="out_dir")
    executor = rd.make_executor(dask) if dask is not None else None     # an unreachable scheduler stops here
    plan = rd.plan_design(proj, vary, records_dir=records_dir, executor=executor, every_cell=every_cell,
                          prefer=prefer, tolerance=list(tolerance) if tolerance else None)
    say = _Say(err)
    with folder.locked():                       # a busy folder stops here, before the kernels compile
        rd.prepare_design(plan, say=err.print)
        try:
            if executor is not None:
                executor.start()
            with _display(err, len(plan.variants), say) as (on_variant, on_stage):
                result = rd.run_design(plan, store=folder.store, progress=on_variant, stage_progress=on_stage,
                                       warn=say.warning, say=on_stage.new_step)
                if not no_pdf and result.recommended is not None:
                    on_stage.new_step(rd.FULL_CHECK)
                    result.recommended_check = rd.recommended_check(result, progress=on_stage)
            full = result.recommended_check
            if full is not None and full.verdict != "PASS":   # the grid's cell and the full check must agree
                say.warning(f"the full check of the recommended design gives {full.verdict}: {full.verdict_reason}")
            elif full is not None and result.recommended.get("robust") and not getattr(full, "verdict_robust", True):
                say.warning(f"the full check of the recommended design is not robust: {full.verdict_reason}")
            what = "design.json, design.csv" + ("" if no_pdf else " and the report (charts, HTML, PDF)")
            with rd.working(f"writing {what}"):
                rd.write_design(result, folder, pdf=not no_pdf, html=not no_pdf)
        finally:
            if executor is not None:
                executor.close()
    data = result.as_json()
    if as_json:
        sys.stdout.write(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    else:
        _summary(data, folder.target, make_console(stderr=True), escape)
    return result.exit_code


class _Say:
    """Lines on stderr: warnings in the command's words."""

    def __init__(self, console):
        self.console = console

    def warning(self, text: str) -> None:
        from rich.markup import escape
        self.console.print(f"[bold yellow]warning:[/] {escape(text)}", highlight=False, soft_wrap=True)


class _Stages:
    """``stage_progress(stage, done, total)`` of the variant analysed alone (a cylinder's, a dask grid's) and
    of the full check: a bar per stage in a terminal, plain lines elsewhere; after :data:`SLOW` seconds without
    progress one line says what runs and why it can take long (:data:`rockdesign.design_space.run.SLOW_ANALYSIS`)."""

    def __init__(self, bar, plain, console, why: str):
        self.bar, self.plain, self.console, self.why = bar, plain, console, why
        self.task = None
        self.stage = ""
        self.last = time.monotonic()
        self.warned = False
        self.lock = threading.Lock()

    def new_step(self, text: str) -> None:
        self._print(text)
        self.touch()

    def touch(self) -> None:
        with self.lock:
            self.last, self.warned = time.monotonic(), False

    def _print(self, text: str) -> None:
        from rich.markup import escape
        (self.bar.console if self.bar is not None else self.console).print(escape(text), highlight=False,
                                                                            soft_wrap=True)

    def __call__(self, stage: str, done: int, total: int) -> None:
        self.touch()
        self.stage = f"{stage} {min(done, total)}/{total}" if total > 1 else stage
        if self.bar is None:
            self.plain(stage, done, total)
            return
        from rich.markup import escape
        if self.task is None:
            self.task = self.bar.add_task(escape(stage), total=total)
        self.bar.update(self.task, description=escape(stage), completed=min(done, total), total=total)

    def watch(self, stop: threading.Event) -> None:
        while not stop.wait(WATCH_EVERY):
            with self.lock:
                quiet = time.monotonic() - self.last
                due = quiet >= SLOW and not self.warned
                if due:
                    self.warned = True
            if due:
                what = self.stage or "the analyses"
                self._print(f"still working ({what}; {quiet:.0f} s since the last step): {self.why}")


@contextlib.contextmanager
def _display(console, total: int, say: _Say):
    """Yield (on_variant, on_stage): a bar of the variants and one of the running stage (a terminal), or plain
    lines (elsewhere); a watchdog thread says why a long stage is long."""
    import rockdesign as rd
    from rich.markup import escape
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from ..display import verdict_words
    live = console.is_terminal or bool(getattr(console, "is_jupyter", False))
    bar = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                   console=console) if live else None
    plain_ctx = rd.progress_bars(console) if not live else contextlib.nullcontext(None)
    with plain_ctx as plain, (bar if bar is not None else contextlib.nullcontext()):
        stages = _Stages(bar, plain, console, rd.SLOW_ANALYSIS)
        variants_task = bar.add_task("design variants", total=total) if bar is not None else None

        def on_variant(done, total_, cell):
            stages.touch()
            labels = ", ".join(f"{k} = {v}" for k, v in cell["labels"].items())
            how = " (stored)" if cell.get("resumed") else ""
            text = escape(f"[{done}/{total_}] {labels}: {verdict_words(cell)}{how}")
            (bar.console if bar is not None else console).print(text, highlight=False, soft_wrap=True)
            if bar is not None:
                bar.update(variants_task, completed=done, total=total_)

        stop = threading.Event()
        watcher = threading.Thread(target=stages.watch, args=(stop,), daemon=True, name="design-watch")
        watcher.start()
        try:
            yield on_variant, stages
        finally:
            stop.set()
            watcher.join(timeout=2.0)


def _summary(data: dict, target: Path, console, escape) -> None:
    from ..display import verdict_words
    counts = {}
    for c in data["cells"]:
        words = verdict_words(c).split(":")[0].replace(" (not robust", " (not robust)")
        counts[words] = counts.get(words, 0) + 1
    console.print(f"{len(data['cells'])} variants: " + ", ".join(f"{n} {v}" for v, n in sorted(counts.items())),
                  highlight=False)
    rec = data["recommended"]
    if rec:
        if rec.get("no_robust_pass"):
            console.print(escape(rec["no_robust_pass"]), highlight=False, soft_wrap=True)
        if rec.get("no_tolerance_robust_pass"):
            console.print(escape(rec["no_tolerance_robust"]), highlight=False, soft_wrap=True)
        console.print(escape("recommended: " + ", ".join(f"{k} = {v}" for k, v in rec["labels"].items())
                             + (" (robust PASS)" if rec.get("robust") else " (PASS, not robust)")
                             + f" — {rec['reason']}"), highlight=False, soft_wrap=True)
        cell = next((c for c in data["cells"] if c["index"] == rec["index"]), {})
        if cell.get("flip_margin") is not None:
            console.print(escape(f"distance to the flip: λ = {'≥ ' if cell.get('flip_margin_is_lower_bound') else ''}"
                                 f"{cell['flip_margin']:.3g} × the design intensity ({cell.get('flip_governing')}; "
                                 "> 1 passes)"), highlight=False, soft_wrap=True)
        for n in rec.get("neighbourhood") or []:
            console.print(escape(f"  tolerance neighbour {', '.join(f'{k} = {v}' for k, v in n['labels'].items())}: "
                                 f"{n['verdict']}" + (f", {n['n_unacceptable']} unacceptable"
                                                     if n.get("n_unacceptable") is not None else "")
                                 + (f", flip margin {n['flip_margin']:.3g}" if n.get("flip_margin") is not None
                                    else "")), highlight=False, soft_wrap=True)
        full = rec.get("check")
        if full:
            robust = {True: ", robust", False: ", not robust"}.get(full.get("robust"), "")   # None: a kind without
            console.print(escape(f"full check of the recommended design: {full['verdict']}{robust}"),  # draws
                          highlight=False)
    else:
        console.print("no variant passes", highlight=False)
    audit = (data.get("settings") or {}).get("inference_audit") or {}
    inferred = (data.get("settings") or {}).get("cells_inferred") or 0
    if inferred or audit.get("n"):
        console.print(f"cells inferred from agreeing neighbours far from their flip: {inferred}; audited: "
                      f"{audit.get('agreed', 0)} of {audit.get('n', 0)} agreed", highlight=False)
    console.print(f"analyses run: {data['analyses_run']}; saved by shared work and early stopping: at least "
                  f"{data['analyses_saved']}", highlight=False)
    console.print(escape(f"written: {target}"), highlight=False, soft_wrap=True)
