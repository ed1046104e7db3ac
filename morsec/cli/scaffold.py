"""Commands that write a user's project: create, add, rm, import-blend."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from morsec.cli.common import fail
from morsec.errors import MorsecError


def create(
    name: Annotated[str, typer.Argument(help="project name (a Python identifier): the folder ./NAME")],
    force: Annotated[bool, typer.Option("--force", "-f", help="write into an existing folder")] = False,
) -> None:
    """Create a simulation project: a default scene and its builder twin, a pymorse client, components/, tests/."""
    from morsec.app.scaffold import create_project
    try:
        root = create_project(name, Path.cwd(), force)
    except MorsecError as err:
        fail(err)
    typer.echo(f"created {root}\n  cd {name}\n  morsec run scenes/default.yaml\n  python scripts/{name}_client.py")


def add(
    kind: Annotated[str, typer.Argument(help="sensor, actuator or robot")],
    name: Annotated[str, typer.Argument(help="component name (a Python identifier, e.g. thermal_cam)")],
    project: Annotated[Path, typer.Argument(help="the project folder")] = Path("."),
    description: Annotated[str | None, typer.Option(help="one-line description (asked when omitted)")] = None,
    force: Annotated[bool, typer.Option("--force", "-f", help="overwrite, or shadow a built-in")] = False,
) -> None:
    """Add a component to a project from the templates: its folder (component.py, README, model) and a test."""
    from morsec.app.scaffold import add_component, usage
    if description is None:
        description = typer.prompt("One-line description", default=f"A custom {kind}") if sys.stdin.isatty() \
            else f"A custom {kind}"
    try:
        written = add_component(kind, name, project, description, force)
    except MorsecError as err:
        fail(err)
    for path in written:
        typer.echo(f"  wrote {path}")
    typer.echo(usage(kind, name))


def rm(
    kind: Annotated[str, typer.Argument(help="sensor, actuator or robot")],
    name: Annotated[str, typer.Argument(help="component name")],
    project: Annotated[Path, typer.Argument(help="the project folder")] = Path("."),
    force: Annotated[bool, typer.Option("--force", "-f", help="do not ask")] = False,
) -> None:
    """Remove a component that `morsec add` generated (its folder and its test)."""
    from morsec.app.scaffold import remove_component
    if not force and not typer.confirm(f"remove {kind} {name}?", default=False):
        raise typer.Exit(1)
    try:
        removed = remove_component(kind, name, project)
    except MorsecError as err:
        fail(err)
    typer.echo(f"removed {kind} {name} ({len(removed)} files and its folder)")


def import_blend(
    file: Annotated[Path, typer.Argument(help="the .blend file (Blender 2.5 to 3.4; MORSE's are 2.6x and 2.7x)")],
    out: Annotated[Path | None, typer.Option("--out", "-o", help="the components folder to write into "
                                             "(default: the project's)")] = None,
    kind: Annotated[str, typer.Option(help="environment (a world and its objects) or props (one prop per "
                                      "object)")] = "environment",
    name: Annotated[str | None, typer.Option(help="its id (default: the file's name)")] = None,
    force: Annotated[bool, typer.Option("--force", "-f", help="replace folders an earlier import wrote")] = False,
    list_objects: Annotated[bool, typer.Option("--list", help="print the objects as the importer reads them "
                                               "(physics, bounds, mass, properties); write nothing")] = False,
) -> None:
    """Import a Blender environment or props file: its meshes, transforms, names, parenting, colours, game
    properties and physics as component folders that scenes name."""
    from morsec.app.blend import import_blend_file, list_blend
    try:
        lines = list_blend(file, kind) if list_objects else import_blend_file(file, out, kind, name, force)
    except MorsecError as err:
        fail(err)
    typer.echo("\n".join(lines))
