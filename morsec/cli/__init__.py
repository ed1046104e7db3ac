"""The `morsec` command: a typer app assembled from one module per command group; each command calls
one function of the application layer."""

from __future__ import annotations

from typing import Annotated

import typer

from morsec import __version__
from morsec.cli import catalogue, running, scaffold, scenes

app = typer.Typer(no_args_is_help=True, pretty_exceptions_enable=False,
                  help="morsec: MORSE scenes compiled to MuJoCo.")

for command in (scenes.build, scenes.check, scenes.schema, running.run, catalogue.docs, running.render,
                catalogue.components, scenes.convert, scaffold.create, scaffold.add, scaffold.rm):
    app.command()(command)


def _versions() -> str:
    import mujoco
    return f"morsec {__version__} (MuJoCo {mujoco.__version__})"


def _print_version(value: bool) -> None:
    if value:
        typer.echo(_versions())
        raise typer.Exit()


@app.callback()
def _options(
    version: Annotated[bool | None, typer.Option("--version", callback=_print_version, is_eager=True,
                                                    help="print the versions of morsec and MuJoCo")] = None,
) -> None:
    """morsec: MORSE scenes compiled to MuJoCo."""


@app.command()
def version() -> None:
    """Print the versions of morsec and MuJoCo."""
    typer.echo(_versions())


def main() -> None:
    app()


__all__ = ["app", "main"]
