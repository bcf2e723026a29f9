"""User-facing errors: each names the file, the key, what was expected and what was found.

The CLI turns any :class:`RockdesignError` into one clean message on stderr and exit code 2.
Library users catch them like any other exception.
"""
from __future__ import annotations


class RockdesignError(Exception):
    """An input error a user can fix (bad project file, motion string, record file...)."""

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None,
                 expected: str | None = None, found: str | None = None,
                 line: int | None = None, hint: str | None = None):
        self.file = file
        self.key = key
        self.expected = expected
        self.found = found
        self.line = line
        self.hint = hint
        self.detail = message
        super().__init__(self.format())

    def format(self) -> str:
        where = []
        if self.file:
            where.append(f"{self.file}" + (f":{self.line}" if self.line else ""))
        if self.key:
            where.append(f"key '{self.key}'")
        head = ", ".join(where)
        parts = [f"{head}: {self.detail}" if head else self.detail]
        if self.expected is not None:
            parts.append(f"expected {self.expected}")
        if self.found is not None:
            parts.append(f"found {self.found}")
        text = "; ".join(parts)
        if self.hint:
            text += f" ({self.hint})"
        return text


class ProjectError(RockdesignError):
    """Invalid project file content."""


class MotionError(RockdesignError):
    """Invalid ground-motion specification (motion string, pulse parameters, scaling)."""


class RecordError(RockdesignError):
    """Unreadable or malformed ground-motion record file, or unknown record id."""


class ModelError(RockdesignError):
    """A requested model cannot represent the system (e.g. linear-exact for a 2DOF podium)."""
