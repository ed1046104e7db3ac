"""Requests answered while a frame's physics runs: while a client converses, a frame runs its physics
sub-steps one at a time and answers the requests of `anytime` services between them (fixed_step flat out
no longer holds such an answer for the whole frame); every other request waits for the frame's end, and
the physics is the same, bit for bit."""

from __future__ import annotations

import select
import socket
from pathlib import Path

import numpy as np
import pytest

from morsec.app.project import build_scene
from morsec.runtime.simulation import RunOptions, Simulation
from morsec.testing import Harness

SCENE = """\
environment:
  name: empty
  time: {strategy: fixed_step, frequency: 60}
robots:
  - name: robot
    type: atrv
    components:
      - {name: pose, type: pose, frequency: 60, streams: [socket]}
      - {name: motion, type: motion_vw, frequency: 60, streams: [socket]}
"""


@pytest.fixture
def build(tmp_path) -> Path:
    source = tmp_path / "scene.yaml"
    source.write_text(SCENE)
    return build_scene(source, tmp_path / "build")


def simulation(build: Path) -> Simulation:
    return Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))


class Client:
    def __init__(self, sim: Simulation):
        self.sim = sim
        server = sim.middlewares["socket"].server
        self.sock = socket.create_connection(("127.0.0.1", server.port), timeout=10)
        self.buffer = b""
        while not server.clients:
            sim.poller.poll(0.1)
        self.peer = server.clients[-1].sock  # the simulation's end of the connection

    def send(self, text: str) -> None:
        """Write request lines, and wait until the simulation's end can read them."""
        self.sock.sendall(text.encode())
        assert select.select([self.peer], [], [], 10)[0], "the request never reached the simulation"

    def answers(self) -> list[str]:
        """The answer lines that arrived so far."""
        while select.select([self.sock], [], [], 0)[0]:
            data = self.sock.recv(65536)
            assert data, "the simulation closed the connection"
            self.buffer += data
        *lines, self.buffer = self.buffer.split(b"\n")
        return [line.decode() for line in lines]

    def converse(self) -> None:
        """A request answered by a poll, as the loop does at a frame's start: the client converses."""
        self.send("hello time now\n")
        self.sim.poller.poll(0.0)
        assert [line.split()[0] for line in self.answers()] == ["hello"]


def test_anytime_requests_are_answered_within_the_frames_physics_the_others_at_its_end(build):
    sim = simulation(build)
    try:
        client = Client(sim)
        client.converse()
        client.send("z time now\n")
        sim.frame()  # not in the first frame: its start is time 0 with relative time, which no answer carries
        assert client.answers() == []
        sim.poller.poll(0.0)
        assert client.answers() == [f"z SUCCESS {sim.clock.now()!r}"]
        before = sim.clock.now()
        # a command between two `time now`s: the second waits behind it, each client's answers keep its order
        client.converse()  # again: the step below starts within CONVERSATION of a request, however loaded the machine
        client.send("a time now\nb simulation set_object_dynamics [\"robot\", true]\nc time now\nd time mode\n")
        sim.step()  # the physics reads the connection between its sub-steps
        assert client.answers() == [f"a SUCCESS {before!r}"]  # the time the frame started from
        sim.frame()  # ... and the next frame's end serves the rest, in order
        after = client.answers()
        assert [line.split()[0] for line in after] == ["b", "c", "d"]
        assert after[1] == f"c SUCCESS {sim.clock.now()!r}" and after[1] != f"c SUCCESS {before!r}"
    finally:
        sim.close()


def test_a_conversing_client_leaves_the_physics_bit_identical(build):
    """Two runs of the same commands, one with a client whose `time now` is answered between the sub-steps
    of every frame, one with none: the same state, bit for bit."""
    quiet, talked = Harness(simulation(build)), Harness(simulation(build))
    try:
        client = Client(talked.sim)
        mid_frame = 0
        for frame in range(121):
            for harness in (quiet, talked):
                harness.command("robot.motion", v=1.0 + frame / 100, w=0.4)
            quiet.step()
            client.converse()
            before = talked.sim.clock.now()
            client.send(f"t{frame} time now\n")
            talked.step()
            talked.sim.poller.poll(0.0)  # answered here if the frame did not converse (a loaded machine's pause)
            mid_frame += client.answers() == [f"t{frame} SUCCESS {before!r}"]
        assert mid_frame >= 100  # the sub-steps did run one at a time
        for name in ("qpos", "qvel", "qacc", "act"):
            assert np.array_equal(getattr(quiet.sim.data, name), getattr(talked.sim.data, name)), name
        assert quiet.sim.data.qpos[0] > 1.0  # the robot drove
    finally:
        quiet.sim.close()
        talked.sim.close()
