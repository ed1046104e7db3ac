"""The one exception for mistakes a user can make; the CLI prints it in one or two lines and exits 2."""

from __future__ import annotations

import difflib
from collections.abc import Iterable


class MorsecError(Exception):
    """A user's mistake: bad scene, bad request, unknown component. Never shown with a traceback."""

    exit_code = 2

    def __init__(self, message: str, file: str | None = None, line: int | None = None, column: int | None = None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line
        self.column = column

    def __str__(self) -> str:
        where = location(self.file, self.line, self.column)
        return f"{where}: {self.message}" if where else self.message


class SceneError(MorsecError):
    """A scene that cannot be loaded, validated or compiled."""


class RuntimeFailure(MorsecError):
    """The simulation could not start or had to stop (exit code 1)."""

    exit_code = 1


def location(file: str | None, line: int | None, column: int | None) -> str:
    if not file:
        return ""
    if line is None:
        return str(file)
    return f"{file}:{line}:{column or 1}"


def did_you_mean(word: str, choices: Iterable[str], n: int = 3) -> str:
    """' (did you mean 'x'?)' or ' (did you mean one of 'x', 'y'?)' or '' when nothing is close."""
    matches = difflib.get_close_matches(word, list(choices), n=n, cutoff=0.6)
    if not matches:
        return ""
    if len(matches) == 1:
        return f"; did you mean {matches[0]!r}?"
    return "; did you mean one of " + ", ".join(repr(m) for m in matches) + "?"
