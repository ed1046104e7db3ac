"""What every command shares: user errors in one line with their exit code, output for a terminal or a pipe."""

from __future__ import annotations

import sys
from typing import NoReturn

import typer
from rich.console import Console

from morsec.errors import MorsecError

# rich writes colour and progress bars only on a terminal (and honours NO_COLOR); piped output stays plain
console = Console(highlight=False)
err_console = Console(stderr=True, highlight=False)


def fail(err: MorsecError) -> NoReturn:
    typer.echo(f"error: {err}", err=True)
    raise typer.Exit(err.exit_code)


def on_terminal() -> bool:
    return sys.stdout.isatty()
