"""The `morsec` command: a typer app assembled from one module per command group; each command calls
one function of the application layer.

Typer builds a command's adapter (its click parameters) from the function's signature, and each command
module imports what its annotations name: a command line that names its command (`morsec run ...`)
assembles that command only, so `morsec run` pays for neither the other commands nor their imports.
`morsec`, `morsec --help` or an unknown command assemble all of them."""

from __future__ import annotations

import gc
import importlib
import sys
from typing import Annotated

import typer

from morsec import __version__

# command -> the module of morsec.cli defining it (a function of the same name), in the order --help lists them
COMMANDS = {
    "build": "scenes", "check": "scenes", "schema": "scenes", "run": "running", "replay": "running",
    "docs": "catalogue",
    "render": "running", "components": "catalogue", "convert": "scenes", "create": "scaffold", "add": "scaffold",
    "rm": "scaffold", "import-blend": "scaffold", "sweep": "sweeping", "multinode-server": "multinode",
}


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


def command_of(args: list[str]) -> str | None:
    """The command a command line names, when it names a known one first; None otherwise."""
    return args[0] if args and args[0] in COMMANDS else None


def main(args: list[str] | None = None, prog_name: str | None = None) -> None:
    args = sys.argv[1:] if args is None else list(args)
    command = command_of(args)
    if command == "run":
        # start-up makes long-lived objects only (modules, classes, models): the cyclic garbage collector's
        # passes over them are wasted, a tenth of the start. morsec.runtime.launch turns it on again, once
        # the simulation is initialized
        gc.disable()
    make_app(command)(args=args, prog_name=prog_name)


def __getattr__(name: str):
    if name == "app":  # the whole command line (typer.testing's CliRunner, docs)
        return make_app()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["COMMANDS", "main", "make_app"]
