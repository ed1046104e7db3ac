"""What every command shares: user errors in one line with their exit code, output for a terminal or a pipe.
rich is imported only by the commands that print with it (`morsec run` does not)."""

from __future__ import annotations

import sys
from functools import cache
from typing import NoReturn

import typer

from morsec.errors import MorsecError


@cache
def console(stderr: bool = False):
    """rich's console on stdout (or stderr): colour and progress bars only on a terminal (it honours
    NO_COLOR); piped output stays plain."""
    from rich.console import Console
    return Console(stderr=stderr, highlight=False)


def fail(err: MorsecError) -> NoReturn:
    typer.echo(f"error: {err}", err=True)
    raise typer.Exit(err.exit_code)


def on_terminal() -> bool:
    return sys.stdout.isatty()
