"""The `morsec` command: a typer app (`morsec.cli.assemble`), assembled for the command a command line names.

`morsec run` with options it knows is read without typer (`morsec.cli.run_args`): a start does not pay for
typer and its click parameters. Anything else (`--help`, a mistake, another command) goes to typer."""

from __future__ import annotations

import gc
import sys

# command -> the module of morsec.cli defining it (a function of the same name), in the order --help lists them
COMMANDS = {
    "build": "scenes", "check": "scenes", "schema": "scenes", "run": "running", "replay": "running",
    "docs": "catalogue",
    "render": "running", "components": "catalogue", "convert": "scenes", "create": "scaffold", "add": "scaffold",
    "rm": "scaffold", "import-blend": "scaffold", "sweep": "sweeping", "multinode-server": "multinode",
}


def command_of(args: list[str]) -> str | None:
    """The command a command line names, when it names a known one first; None otherwise."""
    return args[0] if args and args[0] in COMMANDS else None


def main(args: list[str] | None = None, prog_name: str | None = None) -> None:
    """Run the command line `args` (sys.argv's by default); exits, as typer does, with the command's code."""
    args = sys.argv[1:] if args is None else list(args)
    command = command_of(args)
    if command == "run":
        # start-up makes long-lived objects only (modules, classes, models): the cyclic garbage collector's
        # passes over them are wasted, a tenth of the start. morsec.runtime.launch turns it on again, once
        # the simulation is initialized
        gc.disable()
        from morsec.cli.run_args import parse_run_args
        options = parse_run_args(args[1:])
        if options is not None:
            from morsec.cli.run_scene import run_command
            run_command(options)
    from morsec.cli.assemble import make_app
    make_app(command)(args=args, prog_name=prog_name)


def __getattr__(name: str):
    if name == "app":  # the whole command line (typer.testing's CliRunner, docs)
        from morsec.cli.assemble import make_app
        return make_app()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["COMMANDS", "main"]
