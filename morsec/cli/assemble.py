"""The typer app: one module per command group, each command calling one function of the application layer.

Typer builds a command's adapter (its click parameters) from the function's signature, and each command
module imports what its annotations name: a command line that names its command (`morsec run ...`)
assembles that command only, so it pays for neither the other commands nor their imports. `morsec`,
`morsec --help` or an unknown command assemble all of them."""

from __future__ import annotations

import importlib
from typing import Annotated

import typer

from morsec import __version__
from morsec.cli import COMMANDS


def _versions() -> str:
    import mujoco
    return f"morsec {__version__} (MuJoCo {mujoco.__version__})"


def _print_version(value: bool) -> None:
    if value:
        typer.echo(_versions())
        raise typer.Exit()


def _options(
    version: Annotated[bool | None, typer.Option("--version", callback=_print_version, is_eager=True,
                                                    help="print the versions of morsec and MuJoCo")] = None,
) -> None:
    """morsec: MORSE scenes compiled to MuJoCo."""


def version() -> None:
    """Print the versions of morsec and MuJoCo."""
    typer.echo(_versions())


def make_app(only: str | None = None) -> typer.Typer:
    """The command line with every command, or with the command `only` alone (a known command's name)."""
    app = typer.Typer(no_args_is_help=True, pretty_exceptions_enable=False,
                      help="morsec: MORSE scenes compiled to MuJoCo.")
    for name, module in COMMANDS.items():
        if only is None or only == name:
            function = getattr(importlib.import_module(f"morsec.cli.{module}"), name.replace("-", "_"))
            app.command(name=name)(function)
    app.callback()(_options)
    app.command()(version)
    return app
