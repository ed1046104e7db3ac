"""What every command shares: user errors in one line with their exit code, output for a terminal or a pipe.
Neither typer nor rich is imported here: rich only by the commands that print with it (`morsec run` does not),
typer by the command line's adapters (`morsec run` may be read without them: morsec.cli.run_args)."""

from __future__ import annotations

import sys
from functools import cache
from typing import NoReturn

from morsec.errors import MorsecError


@cache
def console(stderr: bool = False):
    """rich's console on stdout (or stderr): colour and progress bars only on a terminal (it honours
    NO_COLOR); piped output stays plain."""
    from rich.console import Console
    return Console(stderr=stderr, highlight=False)


def echo(line: str) -> None:
    """One line on stdout, flushed (as typer.echo)."""
    print(line, flush=True)


def fail(err: MorsecError) -> NoReturn:
    """The error's line on stderr, and exit with its code (inside a typer command as outside one)."""
    print(f"error: {err}", file=sys.stderr, flush=True)
    raise SystemExit(err.exit_code)


def on_terminal() -> bool:
    return sys.stdout.isatty()


def check_ports(*options: tuple[str, int | None]) -> None:
    """Each (option, value) given a port number from 0 to MAX_PORT, or not given (None)."""
    from morsec.constants import MAX_PORT
    for name, value in options:
        if value is not None and not 0 <= value <= MAX_PORT:
            fail(MorsecError(f"{name} must be a port number from 0 to {MAX_PORT}, got {value}"))
