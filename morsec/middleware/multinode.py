"""MORSE's multinode socket protocol: the JSON lines a simulation node and the multinode server exchange.

Once a frame, a node sends one line `[node_name, {robot: [[x, y, z], [rx, ry, rz]], ..., "__time": [t, dt,
wall]}]`: the world pose of each robot it simulates (m; XYZ Euler angles, rad), its simulated time, its frame's
length and its wall-clock time. The server answers with one line `{robot: [[x, y, z], [rx, ry, rz]], ...,
"__time": [...]}`: the last known pose of every robot of the other nodes. morsec's server adds `"__nodes":
{node: {"time": t, "connected": bool}}`; a MORSE node looks that key up as a robot of its scene, finds none
and ignores it, as it ignores any name its scene does not have.

Standard library only: the server (`morsec multinode-server`) loads neither MuJoCo nor a scene."""

from __future__ import annotations

import json
import math
from typing import Any

TIME = "__time"
NODES = "__nodes"
MAX_LINE = 1024 * 1024  # bytes of one line: a node's robots are a few dozen bytes each

Pose = list  # [[x, y, z], [rx, ry, rz]]


def encode(message: Any) -> bytes:
    return (json.dumps(message) + "\n").encode("utf-8")


def node_message(node: str, poses: dict[str, Pose], time: float, dt: float, wall: float) -> bytes:
    return encode([node, {**poses, TIME: [time, dt, wall]}])


def valid_pose(value: Any) -> bool:
    """[[x, y, z], [rx, ry, rz]] of finite numbers (MORSE's server discarded anything else)."""
    return (isinstance(value, list) and len(value) == 2
            and all(isinstance(part, list) and len(part) == 3
                    and all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                            for v in part)
                    for part in value))


def parse_node_message(line: bytes) -> tuple[str, dict[str, Pose], list[float] | None, list[str]]:
    """(node, poses, [t, dt, wall] or None, names of the entries discarded); ValueError when the line is not
    a node's message at all."""
    try:
        message = json.loads(line)
    except (ValueError, UnicodeDecodeError) as err:
        raise ValueError(f"not JSON: {err}") from None
    if not (isinstance(message, list) and len(message) == 2 and isinstance(message[0], str)
            and isinstance(message[1], dict)):
        raise ValueError("not [node_name, {robot: pose, ...}]")
    node, entries = message
    poses: dict[str, Pose] = {}
    discarded: list[str] = []
    time = None
    for name, value in entries.items():
        if name == TIME:
            if (isinstance(value, list) and len(value) == 3
                    and all(isinstance(v, (int, float)) and math.isfinite(v) for v in value)):
                time = [float(v) for v in value]
            else:
                discarded.append(name)
        elif valid_pose(value):
            poses[name] = value
        else:
            discarded.append(name)
    return node, poses, time, discarded


def parse_answer(line: bytes) -> tuple[dict[str, Pose], dict[str, dict] | None]:
    """The server's answer: (the other nodes' robot poses, the nodes' states or None from a server that does
    not send them, as MORSE's did); ValueError when it is not an answer."""
    answer = json.loads(line)
    if not isinstance(answer, dict):
        raise ValueError("the multinode server's answer is not a JSON object")
    nodes = answer.get(NODES)
    poses = {name: value for name, value in answer.items() if name not in (TIME, NODES) and valid_pose(value)}
    return poses, nodes if isinstance(nodes, dict) else None


class Lines:
    """Bytes in, complete lines out; a line longer than MAX_LINE is an error (ValueError)."""

    def __init__(self):
        self.buffer = b""

    def feed(self, data: bytes) -> list[bytes]:
        self.buffer += data
        *lines, self.buffer = self.buffer.split(b"\n")
        if len(self.buffer) > MAX_LINE:
            raise ValueError(f"a line longer than {MAX_LINE} bytes")
        return [line for line in lines if line.strip()]
