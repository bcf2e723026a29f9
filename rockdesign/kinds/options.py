"""The command-line options a kind of structure declares for its rocking spectrum (``rockdesign spectrum``).

A kind lists them in :attr:`~rockdesign.kinds.base.StructureKind.spectrum_cli`, one :class:`CliOption` for each
option of ``rd.spectrum`` its spectrum takes that the command line offers: its name (the keyword of
``rd.spectrum``), the type of its value, its help text.  The command line spells the flags (the library names
parameters, only the command line speaks of flags: docs/architecture.md): the name ``grid_step`` is typed
``--grid-step``, an on/off option (``negatable``) also has its ``--no-`` form, and ``short`` adds a one-letter flag.

:func:`merged_options` merges the declarations of kinds (``rockdesign.kinds.spectrum_cli_options``: of every
registered kind): an option several kinds declare (the axes ``x`` and ``y``) is one option, its help joined from each
kind's.  Adding a kind with options of its own edits no module of the command line.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, replace

VALUE_TYPES = (str, int, float, bool)
"""The types of a value the command line reads (bool: an option given without a value)."""


class OptionConflict(TypeError):
    """Two kinds declare one spectrum option differently, or a kind declares one its spectrum does not take: a
    mistake in a kind's declarations (a programming error, not an input error)."""


@dataclass(frozen=True)
class CliOption:
    """One command-line option of a kind's spectrum, in neutral words.

    Attributes:
        name: the keyword of ``rd.spectrum`` the value is passed as (one of the kind's ``spectrum_options``); the
            command line's flag is the name with ``-`` for ``_``.
        type: the type of the value: ``str``, ``int``, ``float`` or ``bool`` (an option without a value: given,
            it passes True).
        help: what the option does and its default (the kind's default applies when the option is left out).
        metavar: the placeholder of the value in the help (None: the type's).
        short: a one-letter short form ("" none).
        multiple: the option may be repeated; its values are passed as a list.
        negatable: (bool only) the option also has an "off" form that passes False.
        applies_to: the structures the option is for, in the help's words ("" none), written before its help;
            when several kinds declare the option, before each kind's part of the joined help (the kind's name when
            empty).
    """

    name: str
    type: type = str
    help: str = ""
    metavar: str | None = None
    short: str = ""
    multiple: bool = False
    negatable: bool = False
    applies_to: str = ""

    def __post_init__(self):
        if not self.name.isidentifier() or self.name.startswith("_"):
            raise OptionConflict(f"a spectrum option's name is a keyword of rd.spectrum, not {self.name!r}")
        if self.type not in VALUE_TYPES:
            raise OptionConflict(f"spectrum option {self.name!r}: type {self.type!r} is not one of "
                                 f"{', '.join(t.__name__ for t in VALUE_TYPES)}")
        if self.negatable and self.type is not bool:
            raise OptionConflict(f"spectrum option {self.name!r}: only a bool option has an off form (negatable)")
        if self.multiple and self.type is bool:
            raise OptionConflict(f"spectrum option {self.name!r}: a bool option cannot be repeated (multiple)")
        if self.short and not (len(self.short) == 1 and self.short.isalpha()):
            raise OptionConflict(f"spectrum option {self.name!r}: short is one letter, not {self.short!r}")

    def shape(self) -> tuple:
        """What two kinds declaring this option must agree on: its type and how it is typed (all but the help)."""
        return self.type, self.metavar, self.short, self.multiple, self.negatable

    def labelled_help(self, label: str = "") -> str:
        """The help after the structures it applies to (:attr:`applies_to`, else ``label``)."""
        who = self.applies_to or label
        return f"{who}: {self.help}" if who else self.help


def merged_options(kinds) -> tuple[CliOption, ...]:
    """The spectrum options of ``kinds`` (each a :class:`~rockdesign.kinds.base.StructureKind`), one per name, in the
    order the kinds declare them (``kinds`` in the order given), each with the help the command line shows: after
    :attr:`CliOption.applies_to` (capitalised) when it has one, ``applies_to`` then empty.  The help of an option
    several kinds declare joins each kind's (after its ``applies_to``, or the kind's name), separated by "; ".

    Raises :class:`OptionConflict` when two kinds declare a name with a different shape (:meth:`CliOption.shape`),
    a kind declares a name twice, or a kind declares an option its spectrum does not take (not in its
    ``spectrum_options``)."""
    declared: dict[str, list[tuple[object, CliOption]]] = {}
    for kind in kinds:
        for option in kind.spectrum_cli:
            if option.name not in kind.spectrum_options:
                raise OptionConflict(f"the kind {kind.name!r} declares the spectrum option {option.name!r}, which its "
                                     f"spectrum does not take (spectrum_options: {', '.join(kind.spectrum_options)})")
            first = declared.setdefault(option.name, [(kind, option)])[0]
            if first[0] is kind:
                if first[1] is not option:
                    raise OptionConflict(f"the kind {kind.name!r} declares the spectrum option {option.name!r} twice")
                continue
            if option.shape() != first[1].shape():
                raise OptionConflict(
                    f"the kinds {first[0].name!r} and {kind.name!r} declare the spectrum option {option.name!r} "
                    f"differently (type, metavar, short, multiple, negatable: {_shape(first[1])} against "
                    f"{_shape(option)}): one option of the command line has one form")
            declared[option.name].append((kind, option))
    merged = []
    for owners in declared.values():
        labels = [kind.name if len(owners) > 1 else "" for kind, _ in owners]
        text = "; ".join(option.labelled_help(label) for (_, option), label in zip(owners, labels))
        if owners[0][1].applies_to or labels[0]:        # a label starts the text; a help's own first word stays
            text = text[:1].upper() + text[1:]
        merged.append(replace(owners[0][1], help=text, applies_to=""))
    return tuple(merged)


def _shape(option: CliOption) -> str:
    value_type, metavar, short, multiple, negatable = option.shape()
    return f"({value_type.__name__}, {metavar!r}, {short!r}, {multiple}, {negatable})"


@functools.lru_cache(maxsize=1)
def registry_options(kinds: tuple) -> tuple[CliOption, ...]:
    """:func:`merged_options` of ``kinds`` (the registry's, as a tuple), kept while the same kinds are asked again: the
    command line builds its options once for each state of the registry (:func:`rockdesign.kinds.spectrum_cli_options`
    asks the registry)."""
    return merged_options(kinds)
