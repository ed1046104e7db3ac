"""Commands that run a scene: run, render, replay."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from morsec.cli.common import check_ports, fail
from morsec.constants import (
    DEFAULT_BIND,
    FOXGLOVE_PORT,
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
    foxglove: Annotated[bool, typer.Option(
        "--foxglove", help="serve the simulation on Foxglove's WebSocket protocol on --bind (transforms, lasers, "
        "cameras, the scene's bodies, every stream; docs/foxglove.md)")] = False,
    foxglove_port: Annotated[int, typer.Option(
        "--foxglove-port", help="the Foxglove WebSocket server's port (0: a port the OS picks)")] = FOXGLOVE_PORT,
    wait_for_client: Annotated[bool, typer.Option(
        "--wait-for-client", help="no frame runs before a client's first request or stream connection, and the "
        "simulation ends when the service clients that made requests have all left (runs started with their "
        "client, as `morsec sweep` does)")] = False,
    record: Annotated[Path | None, typer.Option(
        help="record every stream into this MCAP file, in simulated time (ROS 2 messages where ROS has them, "
        "JSON otherwise; docs/recording.md)")] = None,
    record_services: Annotated[bool, typer.Option(
        "--record-services", help="also record the service requests and their answers (with --record)")] = False,
    node: Annotated[str | None, typer.Option(
        "--node", "--name", help="multinode scenes: this node's name in the distribution (default: $MORSE_NODE, "
        "else the host name); see `morsec multinode-server`")] = None,
) -> None:
    """Build SCENE if needed and run it; MORSE clients (pymorse) connect to the printed ports."""
    options = dict(locals())  # exactly run's parameters, as run_scene takes them
    from morsec.cli.run_scene import run_scene
    run_scene(**options)


def replay(
    recording: Annotated[Path, typer.Argument(help="an MCAP file made by morsec run --record")],
    rate: Annotated[float, typer.Option(help="recorded (simulated) seconds per wall-clock second")] = 1.0,
    bind: Annotated[str, typer.Option(help="address the servers listen on")] = DEFAULT_BIND,
    service_port: Annotated[int | None, typer.Option(
        help=f"service port (default {SERVICE_PORT}, else the next {SERVICE_PORT_ATTEMPTS} ports)")] = None,
    port_base: Annotated[int | None, typer.Option(
        help=f"first stream port instead of {STREAM_PORT_BASE} (0: ports the OS picks)")] = None,
    wait_for_client: Annotated[bool, typer.Option(
        "--wait-for-client", help="start replaying at a client's first request or stream connection")] = False,
    info: Annotated[bool, typer.Option(
        "--info", help="print what the recording holds (channels, schemas, message counts) and exit")] = False,
) -> None:
    """Serve a recording's sensor streams again on the socket ports of its scene, at the recorded pace."""
    import signal
    import sys

    from morsec.app.replay import Replay, ReplayOptions, describe_recording
    if info:
        try:
            typer.echo(describe_recording(recording))
        except MorsecError as err:
            fail(err)
        return
    if not rate > 0:
        fail(MorsecError(f"--rate must be a positive number, got {rate}"))
    check_ports(("--service-port", service_port), ("--port-base", port_base))
    try:
        player = Replay(recording, ReplayOptions(rate=rate, bind=bind, service_port=service_port,
                                                 port_base=port_base, wait_for_client=wait_for_client))
    except MorsecError as err:
        fail(err)

    def stop(*_) -> None:
        player.quitting = True

    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, stop)
    player.announce(sys.stdout)
    replayed, sent = player.run()
    typer.echo(f"replayed {replayed} messages ({sent} sent to clients)")
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
