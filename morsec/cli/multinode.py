"""`morsec multinode-server`: MORSE's multinode_server (docs/multinode.md)."""

from __future__ import annotations

from typing import Annotated

import typer

from morsec.cli.common import fail
from morsec.constants import DEFAULT_BIND, MAX_PORT, MULTINODE_PORT
from morsec.errors import MorsecError


def multinode_server(
    delay: Annotated[float, typer.Argument(
        help="wall-clock seconds at least between two answers to a node: slows every node down (MORSE's "
        "synchronisation delay)")] = 0.0,
    bind: Annotated[str, typer.Option(help="address to listen on (0.0.0.0: nodes on other machines)")] = DEFAULT_BIND,
    port: Annotated[int, typer.Option(help="port to listen on (the scene's server_port)")] = MULTINODE_PORT,
) -> None:
    """Serve the nodes of a multinode simulation (`morsec run SCENE --node NAME`): each sends its robots' poses
    and gets the others'; a node that runs ahead waits for the others. p then Enter pauses them all."""
    from morsec.app.multinode_server import serve
    if not (delay >= 0 and delay < float("inf")):
        fail(MorsecError(f"DELAY must be 0 or more seconds, got {delay}"))
    if not 0 <= port <= MAX_PORT:
        fail(MorsecError(f"--port must be a port number from 0 to {MAX_PORT}, got {port}"))
    try:
        serve(bind, port, delay)
    except MorsecError as err:
        fail(err)
