"""Command-line interface: thin wrappers over the library API (CONTRACT §2).

The commands import the library (:mod:`rockdesign.library`) inside their bodies, not at the top:
mounting the commands must not load numpy, numba, pint or scipy (``rockdesign --help`` and ``init``
answer in ≈ 0.2 s instead of ≈ 0.65 s; tests/cli/test_startup.py).  That measured start-up cost is
the one exception to imports at module top in this package.

Every command turns a :class:`~rockdesign.errors.RockdesignError` into one line on stderr and exit
code 2 (no traceback); ``check`` exits 1 when the design fails a criterion.
"""
from __future__ import annotations

import functools
import json
import sys
from pathlib import Path
from typing import Optional

import typer
from rich.markup import escape

from .. import __version__
from ..console import make_console
from ..errors import RockdesignError
from .. import discard_unfinished, forget_created
from .inputs import OptionsOnce

app = typer.Typer(cls=OptionsOnce, add_completion=False, no_args_is_help=True,
                  help="Design checks for rocking columns, rocking frames, rocking podium buildings and free-standing "
                       "cylinders.\n\nExit codes: 0 = success (check: PASS), 1 = the design fails (check FAIL, "
                       "design: no variant passes, records scale-model: a table limit exceeded), 2 = input error, "
                       "3 = internal error (a bug: please report it), 4 = not decided (check), 130 = interrupted.")
err_console = make_console(stderr=True)
FLAG = " "
"""metavar of on/off options (typer would print "<bool>" after them in --help)."""
console = make_console()


INTERRUPTED = 130
INTERNAL_ERROR = 3
"""Exit code of a bug in rockdesign (not in the input): distinct from 1, which means the design failed."""
"""Exit code after Ctrl-C (128 + SIGINT), as shells report it."""


def interrupted(exc: BaseException) -> bool:
    """True for Ctrl-C, also when numba re-raises it from a parallel kernel as ``SystemError:
    CPUDispatcher(...) returned a result with an exception set`` (the KeyboardInterrupt is its context)."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False


def _interrupt_exit():
    err_console.print("interrupted (Ctrl-C): nothing more was written", highlight=False)
    raise typer.Exit(INTERRUPTED)


_CLICK_EXCEPTION = next(c for c in typer.BadParameter.__mro__ if c.__name__ == "ClickException")
"""click's ClickException (typer vendors click): usage errors stay click's to report (exit 2)."""


def handle_errors(func=None, /, **aliases):
    """Convert user-input errors to a clean message and exit code 2; Ctrl-C to one line and exit 130; any
    other exception (a bug) to its traceback, one line saying so and exit code 3 (never 1, which means FAIL).

    The library names the parameter an error is about (``key="motion"``); the message names the command's
    option instead (``--motion``): a parameter named like an option of the command maps to it, others through
    ``aliases`` (``@handle_errors(executor="--dask")``)."""
    if func is None:
        return lambda f: handle_errors(f, **aliases)

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        forget_created()
        try:
            return func(*args, **kwargs)
        except BaseException as exc:   # a failed run leaves no empty output folder (outdir.created_folder)
            if getattr(exc, "exit_code", getattr(exc, "code", 1)) not in (0, None):
                discard_unfinished()
            raise
    return _report_errors(wrapper, {**_project_argument(func), **command_options(func), **aliases})


def _project_argument(func) -> dict[str, str]:
    """``rd.load_project`` names its parameter ``path``; a command's PROJECT argument is its file, which the
    message already names: no key is shown for it."""
    import inspect
    return {"path": ""} if "project" in inspect.signature(func).parameters else {}


def command_options(func) -> dict[str, str]:
    """Parameter name → its option as the user types it (``records_dir`` → ``--records-dir``,
    ``out`` → ``-o/--out``), read from the command function's typer options."""
    import inspect
    out = {}
    for name, param in inspect.signature(func).parameters.items():
        decls = getattr(param.default, "param_decls", None)
        if isinstance(param.default, typer.models.OptionInfo) and decls:
            out[name] = "/".join(sorted((d for d in decls if d.startswith("-")), key=len))
    return out


def option_of(key: str | None, options: dict[str, str]) -> str | None:
    """The command-line option that the library parameter ``key`` stands for, or None when it names none:
    ``records_dir`` → ``--records-dir``, an item of a parameter ``table.d`` → ``--table d``, two parameters
    ``x/y`` → ``--x/--y``."""
    if not key:
        return None
    head, dot, rest = key.partition(".")
    names = head.split("/")
    if not all(name in options for name in names):
        return None
    return "/".join(options[name] for name in names) + (f" {rest}" if dot else "")


def _report_errors(func, options: dict[str, str] | None = None):
    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except RockdesignError as exc:
            flag = option_of(exc.key, options or {})
            if flag is not None:
                exc.key = flag
                exc.args = (exc.format(),)
            err_console.print(f"[bold red]error:[/] {escape(str(exc))}", highlight=False, markup=True, soft_wrap=True)
            raise typer.Exit(2) from None
        except (KeyboardInterrupt, SystemError) as exc:
            if not interrupted(exc):
                _internal_error(exc)
            _interrupt_exit()
        except (typer.Exit, typer.Abort, SystemExit, _CLICK_EXCEPTION):
            raise
        except Exception as exc:   # a bug: say so, keep the traceback for the report, never exit 1 (= FAIL)
            _internal_error(exc)

    return wrapper


def _internal_error(exc: BaseException):
    import traceback
    err_console.print("".join(traceback.format_exception(exc)), highlight=False, markup=False, soft_wrap=True)
    err_console.print(f"[bold red]internal error[/] (a bug in rockdesign {__version__}, not in the input): "
                      f"{escape(type(exc).__name__)}: {escape(str(exc))} — please report it with the traceback "
                      f"above; exit code {INTERNAL_ERROR}", highlight=False, markup=True, soft_wrap=True)
    raise typer.Exit(INTERNAL_ERROR) from None


def _version_callback(value: bool):
    if value:
        from importlib.metadata import version  # here, not at the top: ≈ 20 ms of every CLI start-up
        console.print(f"rockdesign {version('rockdesign')}")  # the installed package's metadata
        raise typer.Exit()


@app.callback()
def _root(version: bool = typer.Option(False, "--version", callback=_version_callback, is_eager=True,
                                       metavar=FLAG,
                                       help="Print the version and exit.")):
    """rockdesign: uplift thresholds, capacities, time-history analysis and Polyakov checks."""


@app.command()
@handle_errors
def init(kind: str = typer.Argument(..., help="podium | column | cylinder"),
         path: Optional[Path] = typer.Argument(None, help="Where to write (default: KIND.toml)"),
         force: bool = typer.Option(False, "--force", metavar=FLAG, help="Overwrite an existing file.")):
    """Write a commented template project file."""
    from ..templates import write_template
    out = write_template(kind, path, force=force)
    console.print(f"wrote {out}")


@app.command()
@handle_errors
def quantities(project: Path = typer.Argument(..., help="Project file (TOML)"),
               as_json: bool = typer.Option(False, "--json", metavar=FLAG, help="Print JSON (SI units)."),
               units: Optional[str] = typer.Option(None, "--units",
                                                   help="Display units, comma separated, e.g. 'mm,deg,kN,g'."),
               pushover: Optional[Path] = typer.Option(None, "--pushover", help="Write the pushover curve "
                                                       "F_R/(m g) vs θ: .csv for the numbers, .png/.svg/.pdf for a plot.")):
    """Closed-form design quantities (thesis Ch. 3–5; docs/model.md §3)."""
    from .. import library as rd
    from ..display import quantities_table
    from . import inputs as cli_inputs
    cli_inputs.output_file(pushover, "--pushover", (".csv",) + cli_inputs.FIGURE_SUFFIXES)
    proj = rd.load_project(project)
    if pushover is not None:
        rd.write_capacity_curve(proj, pushover)
    q = rd.design_quantities(proj)
    if as_json:
        sys.stdout.write(json.dumps(q.as_json(), indent=2) + "\n")
        return
    from .. import report_citation
    quantities_table(q, console, units, proj.system.g, q.title, proj.warnings, cite=report_citation)


@app.command()
@handle_errors(motion="--motion")
def simulate(project: Path = typer.Argument(..., help="Project file (TOML)"),
             motion: str = typer.Option(..., "--motion", "-m", help="e.g. 'ricker-anti:ap=0.38g,Tp=0.95s', "
                                        "'free:theta0=0.8alpha', 'record:p695-ff/11a,scale=1.5', 'file:X.AT2'"),
             model: str = typer.Option("auto", "--model", help="exact | linear | linear-exact | auto"),
             as_json: bool = typer.Option(False, "--json", metavar=FLAG, help="Print JSON (SI units)."),
             plot: Optional[Path] = typer.Option(None, "--plot", help="Write a time-history figure (png/svg/pdf)."),
             csv: Optional[Path] = typer.Option(None, "--csv", help="Write the time history as CSV."),
             t_end: Optional[float] = typer.Option(None, "--t-end", help="End time [s] (default: motion + "
                                                   "free vibration)."),
             rtol: Optional[float] = typer.Option(None, "--rtol", help="Relative tolerance (default: project)."),
             records_dir: Optional[Path] = typer.Option(None, "--records-dir", help="Folder of PEER AT2 files.")):
    """One nonlinear time-history analysis (docs/model.md §4; a cylinder: docs/cylinder.md)."""
    from .. import library as rd
    from ..display import response_table
    from . import inputs as cli_inputs
    cli_inputs.positive_time(t_end, "--t-end")
    cli_inputs.rtol(rtol)
    cli_inputs.output_file(plot, "--plot", cli_inputs.FIGURE_SUFFIXES)
    cli_inputs.output_file(csv, "--csv")
    proj = rd.load_project(project)
    # bad input is reported before a first run compiles the engine
    request = rd.simulation_request(proj, motion, model=model, t_end=t_end, rtol=rtol, records_dir=records_dir)
    result = rd.run_simulation(request, say=err_console.print)
    if csv:
        result.write_csv(csv)
    if plot:
        result.write_figure(plot)
        err_console.print(f"wrote {plot}", highlight=False, soft_wrap=True)
    if as_json:
        sys.stdout.write(json.dumps(result.as_json(), indent=2) + "\n")
    else:
        response_table(result, console)
    if result.failed:
        err_console.print(f"[bold red]error:[/] the analysis failed: {escape(result.response.status)} — its "
                          "θ_max and verdict are not results (check the model and the motion)", highlight=False,
                          soft_wrap=True)
        raise typer.Exit(2)


def _mount_command_modules():
    """Mount the commands that live in their own modules (records, check, spectrum, bench)."""
    from . import bench as cli_bench, check as cli_check, experiments as cli_experiments, spectrum as cli_spectrum
    from . import design as cli_design
    from .records import app as records_app
    for command in records_app.registered_commands:
        command.callback = handle_errors(command.callback)
    app.add_typer(records_app, name="records", help="Ground-motion tools: list, show, spectrum, synth, scale-model.")
    for module in (cli_check, cli_spectrum, cli_bench, cli_experiments, cli_design):
        module.register(app, handle_errors)


_mount_command_modules()


_SIGINT_SEEN = [False]


def _on_sigint(signum, frame):
    _SIGINT_SEEN[0] = True
    raise KeyboardInterrupt


def main():  # console-script entry point
    """Run the CLI.  Ctrl-C inside a command (also in a numba kernel) ends with one line and exit 130
    (:func:`handle_errors`); outside one (while parsing options) typer aborts, and the exit code is
    still 130."""
    import signal
    signal.signal(signal.SIGINT, _on_sigint)
    try:
        app()
    except SystemExit as exc:
        # the command is over (its files written or not): a Ctrl-C during the interpreter's shutdown would
        # kill the process by SIGINT instead of ending with the command's exit code
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        if _SIGINT_SEEN[0] and exc.code not in (0, INTERRUPTED):
            sys.exit(INTERRUPTED)
        raise


if __name__ == "__main__":
    main()
