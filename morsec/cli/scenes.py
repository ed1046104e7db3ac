"""Commands on scene files: build, check, schema, convert."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from morsec.cli.common import console, fail
from morsec.errors import MorsecError


def build(
    scene: Annotated[Path, typer.Argument(help="scene file: .yaml, .yml, .toml or a builder script .py")],
    out: Annotated[Path | None, typer.Option("-o", "--out", help="build folder (default: build/<scene name>)")] = None,
) -> None:
    """Compile SCENE into a build folder: scene.xml, robots/*.urdf, middleware.json, manifest.json."""
    from morsec.app.project import build_scene, default_build_dir
    try:
        out_dir = build_scene(scene, out or default_build_dir(scene))
    except MorsecError as err:
        fail(err)
    typer.echo(f"built {scene} -> {out_dir}")


def check(
    scenes: Annotated[list[Path], typer.Argument(help="scene files to validate")],
    strict: Annotated[bool, typer.Option(
        "--strict", help="a builder script's warnings are errors: a MORSE-only call, a property its component "
        "does not declare (kept as a tag)")] = False,
) -> None:
    """Validate scenes without writing anything (for CI): exit 0 when all are valid, 2 otherwise."""
    from morsec.app.project import check_scene
    failed = 0
    items = scenes
    if len(scenes) > 3 and console(stderr=True).is_terminal:
        from rich.progress import track
        items = track(scenes, description="checking", console=console(stderr=True), transient=True)
    for path in items:
        try:
            check_scene(path, strict)
        except MorsecError as err:
            typer.echo(f"error: {err}", err=True)
            failed += 1
        else:
            typer.echo(f"ok: {path}")
    if failed:
        raise typer.Exit(2)


def schema(
    manifest: Annotated[bool, typer.Option("--manifest", help="the schema of a build's manifest.json instead")] = False,
    messages: Annotated[Path | None, typer.Option(
        "--messages", help="instead, write the JSON Schema of each stream's message in this folder "
        "(<kind>/<id>.schema.json; the repository keeps them in schemas/messages)")] = None,
) -> None:
    """Print the JSON Schema of a scene, with every catalogue component's own properties; with --manifest,
    of a build's manifest.json; with --messages, write the schemas of the stream messages instead."""
    from morsec.component.catalogue import load_catalogue
    from morsec.scene.manifest import manifest_schema_text
    from morsec.scene.schema import json_schema_text
    try:
        if messages is not None:
            from morsec.app.schemas import write_message_schemas
            written = write_message_schemas(messages, load_catalogue())
            typer.echo(f"wrote {len(written)} message schemas in {messages}")
            return
        sys.stdout.write(manifest_schema_text() if manifest else json_schema_text(load_catalogue()))
    except MorsecError as err:
        fail(err)
    except OSError as err:
        fail(MorsecError(f"{messages}: cannot write the message schemas: {err.strerror or err}"))


def convert(
    scene: Annotated[Path, typer.Argument(help="scene to convert: a builder script .py, .yaml, .yml or .toml")],
    out: Annotated[Path, typer.Option("-o", "--out", help="file to write: .yaml, .yml or .toml")],
) -> None:
    """Write SCENE in another form (builder script -> YAML/TOML, YAML <-> TOML); the result builds the same."""
    from morsec.app.convert import convert_scene
    try:
        convert_scene(scene, out)
    except MorsecError as err:
        fail(err)
    typer.echo(f"converted {scene} -> {out}")
