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
def run(
    scene: Annotated[Path, typer.Argument(help="scene file (.yaml, .toml, .py) or a build folder")],
    time_strategy: Annotated[Optional[str], typer.Option(
        "--time-strategy", help="best_effort (follow the wall clock) or fixed_step (as fast as possible)")] = None,
    duration: Annotated[Optional[float], typer.Option(help="stop after this many simulated seconds")] = None,
    time_scale: Annotated[Optional[float], typer.Option(help="simulated seconds per wall-clock second (best_effort)")] = None,
    bind: Annotated[str, typer.Option(help="address the servers listen on")] = "127.0.0.1",
    service_port: Annotated[Optional[int], typer.Option(help="service port (default 4000, else 4001-4010)")] = None,
    port_base: Annotated[Optional[int], typer.Option(help="first stream port instead of 60000 (0: ports the OS picks; see the table or get_stream_port)")] = None,
    seed: Annotated[Optional[int], typer.Option(help="random seed for noise (default: the scene's)")] = None,
    out: Annotated[Optional[Path], typer.Option("-o", "--out", help="build folder (default: build/<scene name>)")] = None,
    view: Annotated[Optional[str], typer.Option(
        help="web: MuJoCo Studio's web viewer on --bind (prints the URL); native: mujoco.viewer (needs a display)")] = None,
    view_port: Annotated[int, typer.Option(help="web viewer HTTP port")] = 8080,
    output_dir: Annotated[Optional[Path], typer.Option(
        "--output-dir", help="folder the text streams write their files into (default: the current folder)")] = None,
) -> None:
    """Build SCENE if needed and run it; MORSE clients (pymorse) connect to the printed ports."""
    import logging
    from morsec.constants import MAX_PORT, MAX_TIME_SCALE, MIN_TIME_SCALE
    from morsec.runtime.launch import prepare_build, run_simulation
    from morsec.runtime.simulation import RunOptions
    logging.basicConfig(level=logging.WARNING, format="%(levelname)s %(name)s: %(message)s")
    if view not in (None, "web", "native"):
        fail(MorsecError(f"--view must be web or native, got {view!r}"))
    if time_strategy not in (None, "best_effort", "fixed_step"):
        fail(MorsecError(f"--time-strategy must be best_effort or fixed_step, got {time_strategy!r}"))
    if duration is not None and not duration > 0:
        fail(MorsecError(f"--duration must be a positive number, got {duration}"))
    if time_scale is not None and not MIN_TIME_SCALE <= time_scale <= MAX_TIME_SCALE:
        fail(MorsecError(f"--time-scale must be between {MIN_TIME_SCALE:g} and {MAX_TIME_SCALE:g}, got {time_scale}"))
    for name, value in (("--service-port", service_port), ("--port-base", port_base), ("--view-port", view_port)):
        if value is not None and not 0 <= value <= MAX_PORT:
            fail(MorsecError(f"{name} must be a port number from 0 to {MAX_PORT}, got {value}"))
    if seed is not None and seed < 0:
        fail(MorsecError(f"--seed must be 0 or more, got {seed}"))
    try:
        build_dir, cat = prepare_build(scene, out)
        options = RunOptions(strategy=time_strategy, time_scale=time_scale, bind=bind, service_port=service_port,
                             port_base=port_base, seed=seed, view=view, view_port=view_port,
                             output_dir=output_dir or Path.cwd())
        run_simulation(build_dir, cat, options, duration)
    except MorsecError as err:
        fail(err)
    typer.echo("EXITING SIMULATION")


@app.command()
def docs(
    out: Annotated[Path, typer.Option("-o", "--out", help="docs folder to write the generated pages into")] = Path("docs"),
    pictures: Annotated[bool, typer.Option(help="also render the gallery's pictures (slow: one scene each)")] = False,
) -> None:
    """Regenerate the reference pages (scene-format.md, components.md, the component gallery) from the
    models and the catalogue; with --pictures, the gallery's pictures too."""
    from morsec.catalogue import load_catalogue
    from morsec.docsgen import write_docs
    try:
        cat = load_catalogue()
        written = write_docs(out, cat)
        if pictures:
            from morsec.gallery import render_pictures
            written += render_pictures(cat, out)
        typer.echo(f"wrote {len(written)} files in {out}")
    except MorsecError as err:
        fail(err)
    except OSError as err:
        fail(MorsecError(f"{out}: cannot write the docs: {err.strerror or err}"))


@app.command()
def render(
    scene: Annotated[Path, typer.Argument(help="scene file (.yaml, .toml, .py) or a build folder")],
    out: Annotated[Path, typer.Option("-o", "--out", help="PNG file to write")] = Path("scene.png"),
    camera: Annotated[Optional[str], typer.Option(help="camera name (default: the environment's camera)")] = None,
    width: Annotated[int, typer.Option(min=16, max=1920, help="image width, pixels")] = 800,
    height: Annotated[int, typer.Option(min=16, max=1080, help="image height, pixels")] = 600,
) -> None:
    """Render a picture of SCENE headless on the CPU (EGL, else OSMesa), from the environment's camera."""
    from morsec.render import render_build
    from morsec.runtime.launch import prepare_build
    try:
        build_dir, _ = prepare_build(scene, None)
        path = render_build(build_dir, out, camera, width, height)
    except MorsecError as err:
        fail(err)
    typer.echo(f"wrote {path}")


@app.command()
def components(name: Annotated[Optional[str], typer.Argument(help="a component id or builder class name")] = None) -> None:
    """List the catalogue (built-in and this project's components), or describe one component."""
    from morsec.catalogue import load_catalogue
    from morsec.describe import catalogue_listing
    from morsec.docsgen import component_section
    from morsec.errors import did_you_mean
    kinds = ("sensors", "actuators", "robots", "environments", "props")
    try:
        cat = load_catalogue()
        if name is None:
            typer.echo(catalogue_listing(cat))
            return
        for kind in kinds:
            if cat.resolve(kind, name):
                cls = cat.get(kind, name)
                typer.echo(f"{cls.short_descr}\n{component_section(kind, cls, None)}")
                return
        every = [n for kind in kinds for n in cat.names(kind)]
        raise MorsecError(f"no component {name!r} in the catalogue{did_you_mean(name, every)}")
    except MorsecError as err:
        fail(err)


@app.command()
def convert(
    scene: Annotated[Path, typer.Argument(help="scene to convert: a builder script .py, .yaml, .yml or .toml")],
    out: Annotated[Path, typer.Option("-o", "--out", help="file to write: .yaml, .yml or .toml")],
) -> None:
    """Write SCENE in another form (builder script -> YAML/TOML, YAML <-> TOML); the result builds the same."""
    from morsec.convert import convert_scene
    try:
        convert_scene(scene, out)
    except MorsecError as err:
        fail(err)
    typer.echo(f"converted {scene} -> {out}")


@app.command()
def create(
    name: Annotated[str, typer.Argument(help="project name (a Python identifier): the folder ./NAME")],
    force: Annotated[bool, typer.Option("--force", "-f", help="write into an existing folder")] = False,
) -> None:
    """Create a simulation project: a default scene and its builder twin, a pymorse client, components/, tests/."""
    from morsec.scaffold import create_project
    try:
        root = create_project(name, Path.cwd(), force)
    except MorsecError as err:
        fail(err)
    typer.echo(f"created {root}\n  cd {name}\n  morsec run scenes/default.yaml\n  python scripts/{name}_client.py")


@app.command()
def add(
    kind: Annotated[str, typer.Argument(help="sensor, actuator or robot")],
    name: Annotated[str, typer.Argument(help="component name (a Python identifier, e.g. thermal_cam)")],
    project: Annotated[Path, typer.Argument(help="the project folder")] = Path("."),
    description: Annotated[Optional[str], typer.Option(help="one-line description (asked when omitted)")] = None,
    force: Annotated[bool, typer.Option("--force", "-f", help="overwrite, or shadow a built-in")] = False,
) -> None:
    """Add a component to a project from the templates: its folder (component.py, README, model) and a test."""
    from morsec.scaffold import add_component, usage
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


@app.command()
def rm(
    kind: Annotated[str, typer.Argument(help="sensor, actuator or robot")],
    name: Annotated[str, typer.Argument(help="component name")],
    project: Annotated[Path, typer.Argument(help="the project folder")] = Path("."),
    force: Annotated[bool, typer.Option("--force", "-f", help="do not ask")] = False,
) -> None:
    """Remove a component that `morsec add` generated (its folder and its test)."""
    from morsec.scaffold import remove_component
    if not force and not typer.confirm(f"remove {kind} {name}?", default=False):
        raise typer.Exit(1)
    try:
        removed = remove_component(kind, name, project)
    except MorsecError as err:
        fail(err)
    typer.echo(f"removed {kind} {name} ({len(removed)} files and its folder)")


@app.command()
def version() -> None:
    """Print the versions of morsec and MuJoCo."""
    import mujoco
    typer.echo(f"morsec {__version__} (MuJoCo {mujoco.__version__})")


def main() -> None:
    app()
