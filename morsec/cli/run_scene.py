"""What `morsec run` does once its command line is read (by typer, or by morsec.cli.run_args): check the
options, build the scene if needed, run it. Nothing here imports typer."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from morsec.cli.common import check_ports, echo, fail
from morsec.constants import MAX_TIME_SCALE, MIN_TIME_SCALE
from morsec.errors import MorsecError

if TYPE_CHECKING:
    from morsec.constants import TimeStrategy
    from morsec.runtime.view import ViewKind


def run_scene(scene: Path, *, time_strategy: TimeStrategy | None, duration: float | None, time_scale: float | None,
              bind: str, service_port: int | None, port_base: int | None, seed: int | None, out: Path | None,
              view: ViewKind | None, view_port: int, output_dir: Path | None, foxglove: bool, foxglove_port: int,
              wait_for_client: bool, record: Path | None, record_services: bool, node: str | None) -> None:
    """`morsec run`'s options, as morsec.cli.running.run declares them."""
    import logging

    from morsec.app.project import prepare_build
    from morsec.kits.render import import_mujoco_gl_on_first_use
    if view is None:  # a viewer draws from the start (and MuJoCo Studio's own way): its GL is imported at once
        import_mujoco_gl_on_first_use()
    from morsec.runtime.launch import run_simulation
    from morsec.runtime.simulation import RunOptions
    logging.basicConfig(level=logging.WARNING, format="%(levelname)s %(name)s: %(message)s")
    if duration is not None and not duration > 0:
        fail(MorsecError(f"--duration must be a positive number, got {duration}"))
    if time_scale is not None and not MIN_TIME_SCALE <= time_scale <= MAX_TIME_SCALE:
        fail(MorsecError(f"--time-scale must be between {MIN_TIME_SCALE:g} and {MAX_TIME_SCALE:g}, got {time_scale}"))
    check_ports(("--service-port", service_port), ("--port-base", port_base), ("--view-port", view_port),
                ("--foxglove-port", foxglove_port))
    if seed is not None and seed < 0:
        fail(MorsecError(f"--seed must be 0 or more, got {seed}"))
    if record_services and record is None:
        fail(MorsecError("--record-services records into the file --record names: give --record FILE.mcap"))
    try:
        build_dir = prepare_build(scene, out)
        options = RunOptions(strategy=time_strategy, time_scale=time_scale, bind=bind, service_port=service_port,
                             port_base=port_base, seed=seed, view=view, view_port=view_port,
                             output_dir=output_dir or Path.cwd(), wait_for_client=wait_for_client,
                             foxglove=foxglove_port if foxglove else None,
                             record=record, record_services=record_services, node=node)
        simulated, wall = run_simulation(build_dir, options, duration)
    except MorsecError as err:
        fail(err)
    factor = f" ({simulated / wall:.1f}x real time)" if wall > 0 else ""
    echo(f"simulated {simulated:.6f} s in {wall:.3f} s{factor}")
    echo("EXITING SIMULATION")


def run_command(options: dict[str, Any]) -> NoReturn:
    """`morsec run` read without typer: run it, and end the process as typer's command line would have
    (exit code 0; 130 on Ctrl-C before the simulation handles it; 1 on a closed pipe)."""
    import errno
    import os
    import sys
    try:
        run_scene(**options)
        sys.stdout.flush()
    except KeyboardInterrupt:
        raise SystemExit(130) from None
    except OSError as err:
        if err.errno != errno.EPIPE:
            raise
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no second error when Python flushes it
        raise SystemExit(1) from None
    raise SystemExit(0)
