"""Fields whose shape on the wire is MORSE's socket encoder's, not a plain list: what MORSE's own test files
read (base/attitude_testing.py: `attitude['rotation']['yaw']`)."""

from __future__ import annotations

import json
import socket
from pathlib import Path

import jsonschema
import pytest
from runtime_helpers import stream_client

from morsec.app.schemas import MESSAGES_DIR
from morsec.testing import simulate

ROOT = Path(__file__).resolve().parent.parent

SCENE = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: fake_robot
    rotate: [0.1, -0.2, 0.3]
    components:
      - {name: attitude, type: attitude, streams: [socket]}
"""


def _line(client: socket.socket) -> bytes:
    client.settimeout(5.0)
    data = b""
    while b"\n" not in data:
        chunk = client.recv(65536)
        assert chunk, "the stream closed"
        data += chunk
    return data.split(b"\n", 1)[0]


def test_attitude_rotation_is_a_yaw_pitch_roll_object(tmp_path):
    """MORSE's attitude put a mathutils.Euler in `rotation`, which its socket encoder (MorseEncoder) wrote
    as {"yaw": z, "pitch": y, "roll": x}."""
    with simulate(SCENE, tmp_path) as sim:
        client = stream_client(sim, "robot.attitude")
        sim.run_for(0.1)
        line = _line(client)
        client.close()
        local = sim.data("robot.attitude")
    message = json.loads(line)
    assert list(message) == ["timestamp", "rotation", "angular_velocity"]
    assert list(message["rotation"]) == ["yaw", "pitch", "roll"]
    assert line.count(b'"rotation": {"yaw": ') == 1  # json.dumps' separators, MORSE's key order
    rotation = message["rotation"]
    assert (rotation["roll"], rotation["pitch"], rotation["yaw"]) == pytest.approx((0.1, -0.2, 0.3), abs=1e-6)
    assert local["rotation"] == pytest.approx({"yaw": 0.3, "pitch": -0.2, "roll": 0.1}, abs=1e-6)
    assert isinstance(message["angular_velocity"], list) and len(message["angular_velocity"]) == 3
    schema = json.loads((ROOT / MESSAGES_DIR / "sensors" / "attitude.schema.json").read_text(encoding="utf-8"))
    jsonschema.validate(message, schema)
    assert schema["properties"]["rotation"]["type"] == "object"
