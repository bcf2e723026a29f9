"""``rockdesign spectrum PROJECT [options]``: the rocking spectrum of a project's kind (CONTRACT §2, §4;
docs/spectra.md).

Mounted by :mod:`rockdesign.cli` through :func:`register`.  The command's function declares only the options every
kind's spectrum shares through ``rd.spectrum`` (``--relative``, ``--dask``, ``-o/--out``, ``--figures``) and those of
the printing (``--json``, ``-q/--quiet``).  The other options are the kinds' own: each kind declares them in neutral
words (:attr:`~rockdesign.kinds.base.StructureKind.spectrum_cli`, a tuple of
:class:`~rockdesign.kinds.options.CliOption`: name, value type, help), the package merges those of the registered
kinds (``rd.spectrum_cli_options``, :func:`rockdesign.kinds.spectrum_cli_options`: one option for a name several kinds declare, their helps
joined) and :class:`KindOptionsCommand` adds them to the command when it is parsed or its help shown — never when
the command line starts (``rockdesign --version`` and the other commands load no kind; reading the kinds'
declarations loads no pint, scipy or engine either).  A kind with options of its own edits nothing here.

This module spells the kinds' flags (the library names parameters; only the command line speaks of flags): an
option named ``grid_step`` is ``--grid-step``, an on/off option also has ``--no-grid-step``, a short form is one
letter (``-g``).  The command calls ``rd.spectrum`` (the project's kind runs the spectrum and writes the folder),
draws the progress through a callback and prints the summary.  An option left out is passed as None: the kind's
default applies, and an option the kind does not use is refused by it, the error naming its flag.
"""
from __future__ import annotations

import inspect
import json
import sys
from pathlib import Path
from typing import List, Optional

import typer
from rich.console import Console
from rich.markup import escape
from typer.core import TyperCommand

from ..console import make_console

ON = " "
"""metavar of on/off options (typer would print "<bool>" after them in --help)."""
KIND_VALUES = "spectrum.kind_values"
"""The key of ``ctx.meta`` under which :meth:`KindOptionsCommand.invoke` hands the kinds' option values over."""
TAKEN = frozenset({"project", "progress", "say", "help"})
"""Names no kind's option may take besides the command's own parameters: ``rd.spectrum``'s own keywords and
``--help``."""


def long_flag(name: str) -> str:
    """The long flag of an option named ``name`` (a keyword of ``rd.spectrum``): ``grid_step`` → ``--grid-step``."""
    return "--" + name.replace("_", "-")


def flags_of(option) -> tuple[str, ...]:
    """The flags of a kind's option (a :class:`~rockdesign.kinds.options.CliOption`) as typer declares them: the
    long flag — with its off form, ``--grid-step/--no-grid-step``, when the option is negatable — then the short
    one."""
    flag = long_flag(option.name)
    if option.negatable:
        flag = f"{flag}/--no-{flag[2:]}"
    return (flag, f"-{option.short}") if option.short else (flag,)


def _annotation(option):
    value = List[option.type] if option.multiple else option.type
    return Optional[value]


def typer_options(options) -> list:
    """The click parameters of the kinds' ``options``, made by typer from a function signature as if each were
    written ``name: Optional[T] = typer.Option(None, *flags, help=…, metavar=…)`` (a repeatable option
    ``Optional[List[T]]``): the same parsing, conversion and help as the options of any other command."""
    def options_of_the_kinds(**values):
        """The kinds' options (never called: typer reads its signature)."""

    parameters = [inspect.Parameter(option.name, inspect.Parameter.KEYWORD_ONLY, annotation=_annotation(option),
                                    default=typer.Option(None, *flags_of(option), help=option.help,
                                                         metavar=ON if option.type is bool else option.metavar))
                  for option in options]
    options_of_the_kinds.__signature__ = inspect.Signature(parameters)
    options_of_the_kinds.__annotations__ = {p.name: p.annotation for p in parameters}
    holder = typer.Typer(add_completion=False)
    holder.command()(options_of_the_kinds)
    return list(typer.main.get_command(holder).params)


def _spellings(param) -> set[str]:
    return {*param.opts, *param.secondary_opts} if param.param_type_name == "option" else set()


class KindOptionsCommand(TyperCommand):
    """The ``spectrum`` command: the parameters of its function, and the options the registered kinds declare for
    their spectrum (:func:`typer_options`), read from the registry when the command is parsed or its help shown and
    kept until the registry changes.  :meth:`invoke` hands the kinds' values to the function in ``ctx.meta``."""

    def __init__(self, *args, **kwargs):
        self._built: tuple[tuple | None, list] = (None, [])
        super().__init__(*args, **kwargs)

    @property
    def params(self) -> list:
        """The command's arguments, the kinds' options, then the command's own options: one list for each state of
        the registry (click appends its help option to it and takes it off again)."""
        options = self.kind_options()
        if self._built[0] is not options:
            own = self.own_params
            self._built = (options, [*(p for p in own if p.param_type_name != "option"), *self._kind_params(options),
                                     *(p for p in own if p.param_type_name == "option")])
        return self._built[1]

    @params.setter
    def params(self, value) -> None:
        self.own_params = list(value)
        self._built = (None, [])

    def kind_options(self) -> tuple:
        """The options the registered kinds declare (merged by name; imports the kinds), the same tuple while the
        registry does not change."""
        import rockdesign as rd
        return rd.spectrum_cli_options()

    def _kind_params(self, options) -> list:
        """The click parameters of the kinds' ``options``.  An option that takes the name or a flag of another —
        one of the command's own or another kind's (``-g`` twice) — is a mistake in a kind: a TypeError naming
        both."""
        taken = {p.name: _spellings(p) for p in self.own_params}
        taken.update({name: set() for name in TAKEN})
        for option in options:
            spelled = {flag for part in flags_of(option) for flag in part.split("/")}
            clash = next((name for name, flags in taken.items() if option.name == name or spelled & flags), None)
            if clash is not None:
                raise TypeError(f"a kind's spectrum option {option.name!r} ({'/'.join(flags_of(option))}) takes the "
                                f"name or a flag of {clash!r}, an option of the command or of a kind: rename it")
            taken[option.name] = spelled
        return typer_options(options)

    def invoke(self, ctx):
        """Run the command with the kinds' option values moved from ``ctx.params`` to ``ctx.meta[KIND_VALUES]``
        (name → value; a repeatable option left out is None, given it is a list), then call its function."""
        values = {}
        for option in self.kind_options():
            value = ctx.params.pop(option.name, None)
            if option.multiple:
                value = list(value) if value else None
            values[option.name] = value
        ctx.meta[KIND_VALUES] = values
        return super().invoke(ctx)

    def error_keys(self) -> dict[str, str]:
        """Library parameter → the option as the user types it: the command's own options as declared
        (``out_dir`` → ``-o/--out``, ``figures`` → ``--figures/--no-figures``), the kinds' by their long flag
        (``grid_step`` → ``--grid-step``, or ``--grid-step/--no-grid-step`` for an on/off option; not ``-g``)."""
        keys = {p.name: "/".join(sorted(_spellings(p), key=len))
                for p in self.own_params if _spellings(p)}
        keys.update({option.name: flags_of(option)[0] for option in self.kind_options()})
        return keys


def register(app: typer.Typer, handle_errors) -> None:
    """Add the ``spectrum`` command to the main typer app.  Errors are reported by ``handle_errors`` around the
    work, applied when the command runs: the flags it names come from the kinds' declarations then."""

    @app.command(cls=KindOptionsCommand)
    def spectrum(
        ctx: typer.Context,
        project: Path = typer.Argument(..., help="Project file (TOML)"),
        relative: Optional[Path] = typer.Option(None, "--relative", help="Reference project of the same kind: the "
                                                "relative spectrum against it, on the same grid (docs/spectra.md)."),
        executor: Optional[str] = typer.Option(None, "--dask", help="Run on dask.distributed: local:N (LocalCluster "
                                               "of N workers) or a scheduler address tcp://host:8786."),
        out_dir: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder (default: named after the "
                                               "project and the excitation, e.g. pier-spectrum-sine)."),
        figures: bool = typer.Option(True, "--figures/--no-figures", metavar=ON, help="Write the figures."),
        as_json: bool = typer.Option(False, "--json", metavar=ON, help="Print summary.json to stdout."),
        quiet: bool = typer.Option(False, "--quiet", "-q", metavar=ON, help="No progress bar."),
    ):
        """Rocking spectra: the peak response and overturning over a grid of excitations, with the limit states and
        figures of the project's kind of structure; the options before --relative depend on its kind
        (docs/spectra.md)."""
        run = handle_errors(_spectrum, **ctx.command.error_keys())
        run(project, ctx.meta[KIND_VALUES], relative=relative, executor=executor, out_dir=out_dir, figures=figures,
            as_json=as_json, quiet=quiet)


def _spectrum(project: Path, kind_values: dict, *, relative, executor, out_dir, figures: bool, as_json: bool,
              quiet: bool) -> None:
    """The work of ``rockdesign spectrum``: ``rd.spectrum`` with the kinds' option values and the command's own."""
    import rockdesign as rd
    console = make_console(stderr=True, highlight=False)
    proj = rd.load_project(project)
    with rd.progress_bars(console, disable=quiet or (as_json and not console.is_terminal)) as progress:
        try:
            result = rd.spectrum(proj, **kind_values, relative=relative, out_dir=out_dir, executor=executor,
                                 figures=figures, progress=progress, say=console.print)
        except KeyboardInterrupt as exc:
            if not exc.args:
                raise
            console.print(f"[yellow]interrupted[/]: {escape(str(exc.args[0]))}")   # (the chunks kept)
            raise typer.Exit(130) from None
    if as_json:
        sys.stdout.write(json.dumps(result.as_json(), indent=1, ensure_ascii=False) + "\n")
        return
    _print_summary(make_console(highlight=False), result)


def _print_summary(console: Console, result) -> None:
    from rich.table import Table
    t = Table(title=escape(result.title), show_header=False, title_justify="left")
    t.add_column("quantity")
    t.add_column("value")
    for quantity, value in result.summary_rows():
        t.add_row(escape(quantity), escape(value))
    console.print(t)
