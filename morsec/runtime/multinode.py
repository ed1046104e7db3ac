"""This process as one node of a multinode simulation (configure_multinode; docs/multinode.md).

The node simulates the robots the scene's distribution gives it: their components tick (cameras render), their
streams and services are served here. Every other robot is a ghost: kinematic — placed where the multinode
server last saw it and held there through the physics (too heavy for anything to move it), a wall to this
node's moving bodies but touching neither the static world nor other ghosts (its owner simulates its
collisions) — and none of its components runs.

At the start of every frame (`Simulation.frame`'s hook) the node sends its robots' poses and its simulated time
to the server and waits for the answer, serving its own clients meanwhile: the server holds a node that runs
ahead of the others. The answer places the ghosts. Before its first frame a node waits until every node the
distribution names has connected (the world's time starts when they are all there)."""

from __future__ import annotations

import logging
import os
import socket
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import mujoco
import numpy as np

from morsec.errors import RuntimeFailure
from morsec.kits.geometry import euler_of_xmat, euler_to_quat
from morsec.middleware import multinode as wire
from morsec.runtime.robot import free_joint

if TYPE_CHECKING:
    from morsec.scene.manifest import Manifest

log = logging.getLogger("morsec.multinode")

CONNECT_WAIT = 5.0  # wall-clock s: a node started with (or just before) its server keeps trying that long
JOIN_POLL = 0.05  # wall-clock s between two looks for the nodes not connected yet, before the first frame
ANSWER_POLL = 0.05  # wall-clock s: the longest single wait on the sockets while the server holds this node
GHOST_BIT = 1 << 3  # contype bit of ghost geoms; the moving bodies of this node have it in their conaffinity
# armature (kg, kg m^2) of a ghost's degrees of freedom: within a frame neither gravity nor a robot pushing it
# moves it (1e-8 m), as a kinematic body; MuJoCo's gravity compensation cannot be switched on after compiling
GHOST_ARMATURE = 1e6


def node_name(option: str | None) -> str:
    """This node's name: `--node`, else $MORSE_NODE, else the host name (as MORSE's)."""
    return option or os.environ.get("MORSE_NODE") or socket.gethostname()


@dataclass(frozen=True)
class NodePlan:
    """Who simulates what, decided before the simulation is built."""

    name: str
    address: str
    port: int
    distribution: dict[str, list[str]]

    @classmethod
    def of(cls, spec: dict, option: str | None) -> NodePlan:
        if spec.get("protocol", "socket") != "socket":  # refused at build; a build folder edited by hand
            raise RuntimeFailure(f"multinode protocol {spec['protocol']!r} is not supported: use 'socket'")
        return cls(node_name(option), str(spec["server_address"]), int(spec["server_port"]),
                   {node: list(robots) for node, robots in spec["distribution"].items()})

    @property
    def owned(self) -> set[str]:
        return set(self.distribution.get(self.name, []))

    def local(self, manifest: Manifest) -> Manifest:
        """The part of the build this node runs: the components of its robots, their streams and services
        (the other nodes serve theirs, on the ports the build gave them)."""
        owned = self.owned
        components = [c for c in manifest.components if c.robot in owned]
        kept = {c.fqn for c in components}
        return manifest.model_copy(update={
            "components": components,
            "streams": [s for s in manifest.streams if s.component in kept],
            "services": [s.model_copy(update={"components": [c for c in s.components if c in kept]})
                         for s in manifest.services],
        })


class MultinodeLink:
    """The connection to the multinode server, the ghosts, and the exchange once a frame."""

    def __init__(self, sim, plan: NodePlan):
        self.sim = sim
        self.plan = plan
        self.owned = [(r.name, r.handle.body_id) for r in sim.robots if r.name in plan.owned]
        self.ghosts = Ghosts(sim, [r.name for r in sim.robots if r.name not in plan.owned])
        if plan.name not in plan.distribution:
            log.warning("node %s is not in the scene's distribution (%s): it simulates no robot", plan.name,
                        ", ".join(plan.distribution) or "empty")
        self.sock: socket.socket | None = self._connect()
        self.lines = wire.Lines()
        self.answer: bytes | None = None
        self.joined = False  # every node of the distribution was connected once
        self.left: set[str] = set()  # nodes reported gone
        sim.poller.register(self.sock, self._readable)

    def describe(self) -> str:
        """The line of the table printed at SCENE INITIALIZED."""
        here = ", ".join(name for name, _ in self.owned) or "no robot"
        return f"  {'multinode':<14} node {self.plan.name} of {self.plan.address}:{self.plan.port} ({here})"

    def _connect(self) -> socket.socket:
        where = f"{self.plan.address}:{self.plan.port}"
        deadline = time.monotonic() + CONNECT_WAIT
        while True:
            try:
                sock = socket.create_connection((self.plan.address, self.plan.port), timeout=CONNECT_WAIT)
                break
            except OSError as err:
                if time.monotonic() >= deadline or isinstance(err, socket.gaierror):
                    raise RuntimeFailure(f"cannot reach the multinode server at {where} "
                                         f"({err.strerror or err}): start `morsec multinode-server` first") from None
                time.sleep(0.2)
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        sock.setblocking(False)
        return sock

    # ---- the exchange
    def exchange(self) -> None:
        """Send this node's robots and time, wait for the server's answer, place the ghosts. Before the first
        frame, first wait for the other nodes."""
        if self.sock is None:
            return
        if not self.joined:
            self._join()
        answer = self._round_trip()
        if answer is not None:
            self._apply(answer)

    def _message(self) -> bytes:
        d = self.sim.data
        poses = {name: [d.xpos[body].tolist(), list(euler_of_xmat(d.xmat[body]))] for name, body in self.owned}
        clock = self.sim.clock
        return wire.node_message(self.plan.name, poses, clock.elapsed, clock.dt, time.time())

    def _round_trip(self) -> bytes | None:
        """Send, then poll this node's sockets (its clients are served) until the answer arrives; None when
        the server went away or the simulation is quitting."""
        assert self.sock is not None
        self.answer = None
        try:
            self._send(self._message())
        except OSError as err:
            self._lost(err.strerror or str(err))
            return None
        sim = self.sim
        while self.answer is None and self.sock is not None and not sim.quitting:
            sim.poller.poll(ANSWER_POLL)
            sim._flush()
        return self.answer

    def _send(self, data: bytes) -> None:
        """Blocking: a line is a few hundred bytes, and a server that does not read holds this node anyway."""
        assert self.sock is not None
        self.sock.setblocking(True)
        try:
            self.sock.sendall(data)
        finally:
            self.sock.setblocking(False)

    def _readable(self, sock: socket.socket) -> None:
        try:
            data = sock.recv(65536)
        except (BlockingIOError, InterruptedError):
            return
        except OSError as err:
            self._lost(err.strerror or str(err))
            return
        if not data:
            self._lost("it closed the connection")
            return
        try:
            lines = self.lines.feed(data)
        except ValueError as err:
            self._lost(str(err))
            return
        if lines:
            self.answer = lines[-1]  # one message, one answer: a later one is the freshest

    def _lost(self, why: str) -> None:
        log.warning("multinode server at %s:%d lost (%s): node %s goes on alone, the other nodes' robots stay "
                    "where they were last seen", self.plan.address, self.plan.port, why, self.plan.name)
        self.close()

    def _join(self) -> None:
        """Before the first frame: exchange until the server reports every node of the distribution connected
        (a server that does not report nodes, as MORSE's, is not waited for)."""
        expected = set(self.plan.distribution) | {self.plan.name}
        said = False
        while self.sock is not None and not self.sim.quitting:
            answer = self._round_trip()
            if answer is None:
                return
            nodes = self._apply(answer)
            missing = sorted(expected - {name for name, state in (nodes or {}).items()
                                         if isinstance(state, dict) and state.get("connected")})
            if nodes is None or not missing:
                break
            if not said:
                said = True
                log.warning("node %s waits for %s to connect to the multinode server", self.plan.name,
                            ", ".join(missing))
            self.sim._pause(JOIN_POLL)
        self.joined = True
        clock = self.sim.clock
        if clock.origin:  # absolute timestamps: every node's count from the moment they were all there
            clock.origin = time.time() - clock.elapsed
        clock.restart()  # best_effort: the wait is not owed

    def _apply(self, line: bytes) -> dict[str, Any] | None:
        try:
            poses, nodes = wire.parse_answer(line)
        except ValueError as err:
            log.warning("multinode server: an answer that is not one was ignored (%s)", err)
            return None
        self.ghosts.place(poses)
        if nodes is not None:
            self._report(nodes)
        return nodes

    def _report(self, nodes: dict[str, Any]) -> None:
        """Say once when another node leaves (its robots stay where they were last seen) or comes back."""
        for name, state in nodes.items():
            if name == self.plan.name or not isinstance(state, dict):
                continue
            connected = bool(state.get("connected"))
            if not connected and name not in self.left:
                self.left.add(name)
                robots = ", ".join(self.plan.distribution.get(name, [])) or "no robot"
                when = state.get("time")
                at = f" at simulated time {when:.3f} s" if isinstance(when, (int, float)) else ""
                log.warning("node %s left%s: its robots (%s) stay where they were last seen", name, at, robots)
            elif connected and name in self.left:
                self.left.discard(name)
                log.warning("node %s is back", name)

    def close(self) -> None:
        if self.sock is not None:
            self.sim.poller.unregister(self.sock)
            try:
                self.sock.close()
            except OSError:
                pass
            self.sock = None


class Ghosts:
    """The other nodes' robots on this node: kinematic, where the server says."""

    def __init__(self, sim, names: list[str]):
        self.sim = sim
        m, d = sim.model, sim.data
        self.bodies: dict[str, tuple[int, tuple[int, int] | None]] = {}
        ghost_bodies: list[int] = []
        for robot in sim.robots:
            if robot.name in names:
                handle = robot.handle
                self.bodies[robot.name] = (handle.body_id, free_joint(m, handle.body_id))
                ghost_bodies.extend(int(b) for b in handle.bodies)
                self._hold_joints(robot.name, handle.bodies)
        if not ghost_bodies:
            return
        ghost = np.isin(m.geom_bodyid, ghost_bodies)
        solid = (m.geom_contype != 0) | (m.geom_conaffinity != 0)
        root = m.body_rootid[m.geom_bodyid]
        moving = (m.body_dofnum[root] > 0) & ~ghost
        m.geom_conaffinity[moving & solid] |= GHOST_BIT
        m.geom_contype[ghost & solid] = GHOST_BIT
        m.geom_conaffinity[ghost & solid] = 0
        m.dof_armature[np.isin(m.dof_bodyid, ghost_bodies)] = GHOST_ARMATURE
        for body, joint in self.bodies.values():
            if joint is not None:
                sim.set_frozen(body, True)
        mujoco.mj_kinematics(m, d)

    def _hold_joints(self, name: str, bodies) -> None:
        """A ghost's own joints (wheels, arms) stay as they are: the server sends its base's pose only."""
        m, d = self.sim.model, self.sim.data
        qpos: list[int] = []
        dofs: list[int] = []
        for j in range(m.njnt):
            if int(m.jnt_bodyid[j]) in bodies and m.jnt_type[j] != mujoco.mjtJoint.mjJNT_FREE:
                width = 4 if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_BALL else 1
                qpos.extend(range(m.jnt_qposadr[j], m.jnt_qposadr[j] + width))
                dofs.extend(range(m.jnt_dofadr[j], m.jnt_dofadr[j] + (3 if width == 4 else 1)))
        if qpos:
            index = np.array(qpos)
            self.sim.joint_holds[("multinode", name)] = (index, np.array(dofs), d.qpos[index].copy())

    def place(self, poses: dict[str, wire.Pose]) -> None:
        m, d = self.sim.model, self.sim.data
        moved = False
        for name, (position, euler) in poses.items():
            entry = self.bodies.get(name)
            if entry is None:  # a robot of this node, or one this scene does not have
                continue
            body, joint = entry
            quat = euler_to_quat(*euler)
            if joint is None:
                m.body_pos[body] = position
                m.body_quat[body] = quat
            else:
                adr, dof = joint
                d.qpos[adr:adr + 3] = position
                d.qpos[adr + 3:adr + 7] = quat
                d.qvel[dof:dof + 6] = 0.0
                self.sim.frozen[body] = (adr, dof, d.qpos[adr:adr + 7].copy())
            moved = True
        if moved:
            mujoco.mj_kinematics(m, d)

