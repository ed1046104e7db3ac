"""The `morsec` command: a thin typer app; each command calls one library function."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Optional

import typer

from morsec import __version__
from morsec.errors import MorsecError

app = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="morsec: MORSE scenes compiled to MuJoCo.")


def fail(err: MorsecError) -> None:
    typer.echo(f"error: {err}", err=True)
    raise typer.Exit(err.exit_code)


def default_out(scene: Path) -> Path:
    return Path("build") / scene.stem


@app.command()
def build(
    scene: Annotated[Path, typer.Argument(help="scene file: .yaml, .yml, .toml or a builder script .py")],
    out: Annotated[Optional[Path], typer.Option("-o", "--out", help="build folder (default: build/<scene name>)")] = None,
) -> None:
    """Compile SCENE into a build folder: scene.xml, robots/*.urdf, middleware.json, manifest.json."""
    from morsec.compiler import build_scene
    try:
        out_dir = build_scene(scene, out or default_out(scene))
    except MorsecError as err:
        fail(err)
    typer.echo(f"built {scene} -> {out_dir}")


@app.command()
def check(scenes: Annotated[list[Path], typer.Argument(help="scene files to validate")]) -> None:
    """Validate scenes without writing anything (for CI): exit 0 when all are valid, 2 otherwise."""
    from morsec.catalogue import load_catalogue
    from morsec.compiler.build import compile_scene
    from morsec.scene import load_scene
    failed = 0
    for path in scenes:
        try:
            cat = load_catalogue(path.parent)
            compile_scene(load_scene(path, cat), cat)
        except MorsecError as err:
            typer.echo(f"error: {err}", err=True)
            failed += 1
        else:
            typer.echo(f"ok: {path}")
    if failed:
        raise typer.Exit(2)


@app.command()
def schema() -> None:
    """Print the JSON Schema of a scene, with every catalogue component's own properties."""
    from morsec.catalogue import load_catalogue
    from morsec.scene.schema import json_schema_text
    try:
        sys.stdout.write(json_schema_text(load_catalogue()))
    except MorsecError as err:
        fail(err)


@app.command()
def version() -> None:
    """Print the versions of morsec and MuJoCo."""
    import mujoco
    typer.echo(f"morsec {__version__} (MuJoCo {mujoco.__version__})")


def main() -> None:
    app()
