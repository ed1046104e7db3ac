"""The one exception for mistakes a user can make; the CLI prints it in one or two lines and exits 2.

A scene error reads `file:line:col: <yaml path>: <message>`, e.g.

    scenes/x.yaml:12:7: robots[0].components[2].translte: unknown key 'translte'; did you mean 'translate'?
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence


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


class Unsupported(RuntimeFailure):
    """A component asked for something morsec does not do (a MORSE API the `morse` package has no equivalent of):
    the build or the run stops with this line, which names the component's file and line."""


def location(file: str | None, line: int | None, column: int | None) -> str:
    if not file:
        return ""
    if line is None:
        return str(file)
    return f"{file}:{line}:{column or 1}"


def yaml_path(path: Sequence) -> str:
    """('robots', 0, 'components', 1, 'type') -> 'robots[0].components[1].type'."""
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def close_matches(word: str, choices: Iterable[str], n: int = 3) -> list[str]:
    """The choices closest to `word`, best first; case differences count as close, and a word without a
    folder is compared with the last part of the choices that have one ('indoor-2' is close to
    'indoors-1/indoor-1')."""
    import difflib  # a mistake's message only: a start does not import it
    choices = list(dict.fromkeys(choices))
    matches = difflib.get_close_matches(word, choices, n=n, cutoff=0.6)
    if "/" not in word:
        tails: dict[str, str] = {}
        for choice in choices:
            if "/" in choice:
                tails.setdefault(choice.rsplit("/", 1)[1], choice)
        by_tail = [tails[t] for t in difflib.get_close_matches(word, tails, n=n, cutoff=0.6)]
        matches = list(dict.fromkeys([*by_tail, *matches]))[:n]
    folded = {c.lower(): c for c in choices}
    exact = folded.get(word.lower())
    if exact is not None and exact not in matches:
        matches = [exact, *matches][:n]
    return matches


def did_you_mean(word: str, choices: Iterable[str], n: int = 3) -> str:
    """"; did you mean 'x'?" or "; did you mean one of 'x', 'y'?" or '' when nothing is close."""
    matches = close_matches(str(word), choices, n)
    if not matches:
        return ""
    if len(matches) == 1:
        return f"; did you mean {matches[0]!r}?"
    return "; did you mean one of " + ", ".join(repr(m) for m in matches) + "?"


def one_of(choices: Iterable[str], limit: int = 12) -> str:
    """"'a', 'b' or 'c'" (at most `limit` shown, then '...')."""
    items = [repr(c) for c in choices]
    if not items:
        return "(none)"
    if len(items) > limit:
        return ", ".join(items[:limit]) + ", ..."
    if len(items) == 1:
        return items[0]
    return ", ".join(items[:-1]) + " or " + items[-1]
