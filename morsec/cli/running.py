"""Commands that run a scene: run, render."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from morsec.cli.common import fail
from morsec.constants import (
    DEFAULT_BIND,
    MAX_PORT,
    MAX_TIME_SCALE,
    MIN_TIME_SCALE,
    SERVICE_PORT,
    SERVICE_PORT_ATTEMPTS,
    STREAM_PORT_BASE,
    TimeStrategy,
)
from morsec.errors import MorsecError
from morsec.runtime.view import ViewKind


def run(
    scene: Annotated[Path, typer.Argument(help="scene file (.yaml, .toml, .py) or a build folder")],
    time_strategy: Annotated[TimeStrategy | None, typer.Option(
        "--time-strategy", help="best_effort follows the wall clock; fixed_step runs as fast as possible "
        "(default: the scene's)")] = None,
    duration: Annotated[float | None, typer.Option(help="stop after this many simulated seconds")] = None,
    time_scale: Annotated[float | None, typer.Option(
        help="simulated seconds per wall-clock second (best_effort)")] = None,
    bind: Annotated[str, typer.Option(help="address the servers listen on")] = DEFAULT_BIND,
    service_port: Annotated[int | None, typer.Option(
        help=f"service port (default {SERVICE_PORT}, else the next {SERVICE_PORT_ATTEMPTS} ports)")] = None,
    port_base: Annotated[int | None, typer.Option(
        help=f"first stream port instead of {STREAM_PORT_BASE} (0: ports the OS picks; see the table or "
        "get_stream_port)")] = None,
    seed: Annotated[int | None, typer.Option(help="random seed for noise (default: the scene's)")] = None,
    out: Annotated[Path | None, typer.Option("-o", "--out", help="build folder (default: build/<scene name>)")] = None,
    view: Annotated[ViewKind | None, typer.Option(
        help="web: MuJoCo Studio's web viewer on --bind (prints the URL); native: mujoco.viewer "
        "(needs a display)")] = None,
    view_port: Annotated[int, typer.Option(help="web viewer HTTP port")] = 8080,
    output_dir: Annotated[Path | None, typer.Option(
        "--output-dir", help="folder the text streams write their files into (default: the current folder)")] = None,
    wait_for_client: Annotated[bool, typer.Option(
        "--wait-for-client", help="no frame runs before a client's first request or stream connection, and the "
        "simulation ends when the service clients that made requests have all left (runs started with their "
        "client, as `morsec sweep` does)")] = False,
    node: Annotated[str | None, typer.Option(
        "--node", "--name", help="multinode scenes: this node's name in the distribution (default: $MORSE_NODE, "
        "else the host name); see `morsec multinode-server`")] = None,
) -> None:
    """Build SCENE if needed and run it; MORSE clients (pymorse) connect to the printed ports."""
    import logging

    from morsec.app.project import prepare_build
    from morsec.runtime.launch import run_simulation
    from morsec.runtime.simulation import RunOptions
    logging.basicConfig(level=logging.WARNING, format="%(levelname)s %(name)s: %(message)s")
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
        build_dir = prepare_build(scene, out)
        options = RunOptions(strategy=time_strategy, time_scale=time_scale, bind=bind, service_port=service_port,
                             port_base=port_base, seed=seed, view=view, view_port=view_port,
                             output_dir=output_dir or Path.cwd(), wait_for_client=wait_for_client, node=node)
        simulated, wall = run_simulation(build_dir, options, duration)
    except MorsecError as err:
        fail(err)
    factor = f" ({simulated / wall:.1f}x real time)" if wall > 0 else ""
    typer.echo(f"simulated {simulated:.6f} s in {wall:.3f} s{factor}")
    typer.echo("EXITING SIMULATION")


def render(
    scene: Annotated[Path, typer.Argument(help="scene file (.yaml, .toml, .py) or a build folder")],
    out: Annotated[Path, typer.Option("-o", "--out", help="PNG file to write")] = Path("scene.png"),
    camera: Annotated[str | None, typer.Option(help="camera name (default: the environment's camera)")] = None,
    width: Annotated[int, typer.Option(min=16, max=1920, help="image width, pixels")] = 800,
    height: Annotated[int, typer.Option(min=16, max=1080, help="image height, pixels")] = 600,
) -> None:
    """Render a picture of SCENE headless on the CPU (EGL, else OSMesa), from the environment's camera."""
    import logging

    from morsec.app.project import prepare_build
    from morsec.kits.render import render_build
    logging.basicConfig(level=logging.WARNING, format="%(levelname)s %(name)s: %(message)s")
    try:
        build_dir = prepare_build(scene, None)
        path = render_build(build_dir, out, camera, width, height)
    except MorsecError as err:
        fail(err)
    typer.echo(f"wrote {path}")
