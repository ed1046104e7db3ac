"""A robot at run time: its base body, free joint and base velocity servos, and the ways actuators move it."""

from __future__ import annotations

import functools
import logging
import math
import os
import struct

import mujoco
import numpy as np

from morsec.constants import MAX_FORCE, MAX_POSITION, MAX_SPEED
from morsec.kits import ground_friction, mjcf_names
from morsec.kits.bounds import bounded, bounded_floats
from morsec.kits.geometry import (
    euler_to_quat,
    matrix_to_quat,
    quat_to_matrix,
)
from morsec.runtime import trim

log = logging.getLogger("morsec.robot")


def warn_if_stale(module) -> bool:
    """Whether a compiled module (docs/architecture.md#compiled-module) is older than its source beside it (edited,
    pulled, merged since it was installed): `import` finds the compiled one first, which runs the old code. Said
    on the log (an install writes both files within a second: so much is not counted)."""
    compiled = module.__file__
    if compiled.endswith(".py"):
        return False
    source = os.path.join(os.path.dirname(compiled), module.__name__.rpartition(".")[2] + ".py")
    try:
        stale = os.stat(source).st_mtime > os.stat(compiled).st_mtime + 2.0
    except OSError:
        return False
    if stale:
        log.warning("%s changed after it was compiled: the old compiled code runs until the package is installed "
                    "again (pip install -e .)", source)
    return stale


warn_if_stale(trim)


def free_joint(model, body: int) -> tuple[int, int] | None:
    """(qpos address, dof address) of a body's free joint, or None for a body fixed in its parent."""
    if model.body_jntnum[body] > 0:
        jnt = model.body_jntadr[body]
        if model.jnt_type[jnt] == mujoco.mjtJoint.mjJNT_FREE:
            return int(model.jnt_qposadr[jnt]), int(model.jnt_dofadr[jnt])
    return None


def place(model, data, body: int, pos, rot) -> None:
    """Put a body (a robot's base or a passive object) at a world pose and stop it: through its free joint,
    or by moving a static body in the model."""
    place_with(model, data, body, free_joint(model, body), pos, rot)


def place_with(model, data, body: int, joint: tuple[int, int] | None, pos, rot) -> None:
    """place, the body's free_joint known."""
    pos = bounded(pos, MAX_POSITION, "a position (m)")
    if joint is not None:
        adr, dof = joint
        data.qpos[adr:adr + 3] = pos
        data.qpos[adr + 3:adr + 7] = matrix_to_quat(rot)
        data.qvel[dof:dof + 6] = 0.0
    else:
        model.body_pos[body] = pos
        model.body_quat[body] = matrix_to_quat(rot)
    mujoco.mj_kinematics(model, data)


_THREE_FLOATS = struct.Struct("=3d")  # the base servos' controls, as MjData's ctrl holds them
FOLLOW_FRACTION = 0.25  # RobotHandle.follow's defaults: the trim's limit, as a share of the command
FOLLOW_SETTLE = 2  # ... and how many calls a command is held before its trim is corrected


class RobotHandle:
    def __init__(self, sim, name: str, properties):
        m = sim.model
        self.sim = sim
        self.name = name
        self.properties = properties
        self.ground = bool(getattr(properties, "GroundRobot", False))
        self.body_id = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, name)
        self.qpos_adr: int | None  # None: no free joint (a static robot)
        self.qvel_adr: int | None
        self.qpos_adr, self.qvel_adr = free_joint(m, self.body_id) or (None, None)
        self.free = self.qpos_adr is not None
        ids = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, mjcf_names.base_servo(name, axis))
               for axis in mjcf_names.BASE_SERVO_AXES]
        self.servo = ids if min(ids) >= 0 else None
        self._follow: dict[str, trim.Follow] = {}  # the commands followed (see follow), by who drives
        self.friction: float | None = None  # set_friction's value (None: Blender's default)
        self.damping = 0.0  # Blender's linear damping of its body (the robot class's `damping`)
        self._slid: tuple[float, float] | None = None  # (vx, vy) at the end of the last interval slid (coast)
        # speed at the end of each tick to come, as a share of the held one (sample_tick_end; empty: none to
        # sample, all at the held speed)
        self.ticks: list[float] = []
        self._gravity = float(np.linalg.norm(m.opt.gravity))
        # the last slide computed and its inputs: a command held unchanged slides the same way every tick
        self._last_slide: tuple[tuple, ground_friction.Slide, list[float]] | None = None
        # the last command _drive_on_ground planned, and what it planned: (its inputs, the command friction left
        # of it, the slide's end velocity on the ground, its ticks)
        self._planned: tuple[tuple, float, float, float, tuple[float, float] | None, list[float]] | None = None
        self.sampled: tuple[np.ndarray, np.ndarray] | None = None  # linear qvel (as sampled, as held)
        self._touched: float | None = None  # simulated s: when it last touched something not its own
        self.bodies = np.array(self.subtree(), dtype=int) if self.body_id >= 0 else np.zeros(0, dtype=int)
        self._masses = m.body_mass[self.bodies].copy()
        self.index = -1  # its place among the simulation's robots (see Simulation.touching)
        # views of its base's world position and row-major rotation in MjData (whose arrays stay put)
        self._xpos, self._xmat = sim.data.xpos[self.body_id], sim.data.xmat[self.body_id]
        # how the base servos' three controls are written at every tick: in one struct.pack_into on the bytes of
        # MjData's ctrl where they follow one another (as the compiler declares them), a third of the cost of
        # three numpy item writes
        self._set_servos = self._servo_writer(sim.data.ctrl)

    def _servo_writer(self, ctrl: np.ndarray):
        if self.servo is None:
            return None
        first, second, third = self.servo
        if second == first + 1 and third == first + 2 and ctrl.flags["C_CONTIGUOUS"] and ctrl.dtype == np.float64:
            return functools.partial(_THREE_FLOATS.pack_into, ctrl.data.cast("B"), first * ctrl.itemsize)

        def write(vx: float, vy: float, wz: float) -> None:
            ctrl[first], ctrl[second], ctrl[third] = vx, vy, wz
        return write

    def _base_qvel(self) -> np.ndarray:
        """The free joint's 6 velocities in qvel, a view: writing it sets the robot's velocity."""
        assert self.qvel_adr is not None, f"robot {self.name} has no free joint"
        return self.sim.data.qvel[self.qvel_adr:self.qvel_adr + 6]

    def pose(self) -> tuple[np.ndarray, np.ndarray]:
        d = self.sim.data
        return d.xpos[self.body_id].copy(), d.xmat[self.body_id].reshape(3, 3).copy()

    def apply_speed(self, control_type: str, linear, angular, frequency: float) -> None:
        """MORSE's robot.apply_speed. 'Velocity': body-frame velocity, held by the base servos inside the
        physics steps (ground robots keep vertical velocity, roll and pitch from physics; a new command is set
        on their body at once, as MORSE's, the servos then hold it, trimmed: see follow). 'Position':
        displace by linear/frequency and rotate by angular/frequency, kinematically."""
        linear = bounded_floats(linear, MAX_SPEED, "a linear speed (m/s)")
        angular = bounded_floats(angular, MAX_SPEED, "an angular speed (rad/s)")
        if control_type == "Position":
            self.ticks = []
            if self.servo:
                self.sim.data.ctrl[self.servo] = 0.0
                self._follow.pop("base servos", None)
            self.displace(np.asarray(linear, float) / frequency, np.asarray(angular, float) / frequency)
            return
        self._apply_velocity(linear, angular, frequency)

    def apply_planar_speed(self, control_type: str, v: float, w: float, frequency: float) -> None:
        """apply_speed(control_type, [v, 0, 0], [0, 0, w], frequency) for floats v and w: the same, checked
        in fewer steps (motion_vw gives its robot these at every tick)."""
        if control_type == "Position" or not (abs(v) <= MAX_SPEED and abs(w) <= MAX_SPEED):  # NaN fails them too
            self.apply_speed(control_type, [v, 0.0, 0.0], [0.0, 0.0, w], frequency)
        elif self.servo and self.free and self.ground:
            self._drive_on_ground(v, 0.0, w, frequency)
        else:
            self._apply_velocity((v, 0.0, 0.0), (0.0, 0.0, w), frequency)

    def _apply_velocity(self, linear: tuple[float, ...], angular: tuple[float, ...], frequency: float) -> None:
        """apply_speed's 'Velocity', the speeds checked."""
        if self.servo:
            if self.free and self.ground:
                self._drive_on_ground(linear[0], linear[1], angular[2], frequency)
                return
            self._set_servos(*self._follow_floats("base servos", linear[0], linear[1], angular[2]))
            if self.free:
                # the servos hold vx, vy, wz; a robot off the ground also gets vz, wx, wy set (MORSE sets the
                # whole body velocity of any robot that is not a GroundRobot)
                _, rot = self.pose()
                v = self._base_qvel()
                v[:3] = rot @ np.asarray(linear, float)
                v[3:] = angular
        elif self.free:
            _, rot = self.pose()
            v = self._base_qvel()
            world = rot @ np.asarray(linear, float)
            if self.ground:
                world[2] = v[2]
                v[:3] = world
                v[5] = angular[2]
            else:
                v[:3] = world
                v[3:] = angular

    def _drive_on_ground(self, vx: float, vy: float, wz: float, frequency: float) -> None:
        """_apply_velocity for a free ground robot with base servos: what MORSE's ground friction leaves of the
        command over the period (kits.ground_friction), followed by the servos (see follow). Ticks at every frame
        of every robot driven so: a command held unchanged reuses what the last tick planned from it."""
        on_ground = self._on_ground()
        key = (vx, vy, wz, on_ground, self.friction, frequency, self.damping)
        planned = self._planned
        if planned is None or planned[0] != key:
            slid, ticks = self._slid_for(vx, vy, on_ground, frequency)
            p0, p1, p2 = ground_friction.turned(vx, vy, wz, slid.mean)
            planned = self._planned = (key, p0, p1, p2, slid.end if on_ground else None, ticks)
        _, p0, p1, p2, self._slid, ticks = planned
        self.ticks = ticks.copy()
        state = self._follow.get("base servos")
        if state is None:
            state = self._follow["base servos"] = trim.Follow()
        self._set_servos(*state.drive(p0, p1, p2, self.sim.clock.elapsed, self._xpos.tolist(), self._xmat.tolist(),
                                      FOLLOW_FRACTION, FOLLOW_SETTLE, True))
        if state.held == 0:
            # a new command: the body takes it at once, as MORSE's (no servo force to speed it up, which pushing
            # at the origin, below the centre of mass, would rock it); the servos then hold it
            _, rot = self.pose()
            v = self._base_qvel()
            world = rot @ np.array([p0, p1, 0.0])
            v[0], v[1] = world[0], world[1]
            v[5] = p2

    # ---- MORSE's ground friction between the ticks that set a ground robot's velocity (kits.ground_friction)
    def _slide(self, vx: float, vy: float, frequency: float) -> tuple[float, float]:
        """The mean planar velocity over the actuator's period of a ground robot set going at (vx, vy), body
        frame, that the ground's friction (on the ground) and Bullet's damping then slow down."""
        on_ground = self._on_ground()
        slid, ticks = self._slid_for(vx, vy, on_ground, frequency)
        self._slid = slid.end if on_ground else None
        self.ticks = ticks.copy()
        return slid.mean

    def _slid_for(self, vx: float, vy: float, on_ground: bool, frequency: float) -> tuple[ground_friction.Slide,
                                                                                          list[float]]:
        """The slide of a robot set going at (vx, vy), and the shares of the held speed at the end of its ticks
        (empty: every tick ends at the held speed)."""
        key = (vx, vy, on_ground, self.friction, frequency, self.damping)  # all mu and the slide depend on
        if self._last_slide is None or self._last_slide[0] != key:  # (the clock's frequency never changes)
            mu = ground_friction.ground_friction(self.friction) if on_ground else 0.0
            slid = ground_friction.slide(vx, vy, mu, self._gravity, 1.0 / frequency,
                                         1.0 / self.sim.clock.frequency, self.damping)
            # ticks that end at the held speed leave it as it is (sample_tick_end): none to keep then
            ticks = [] if all(share == 1.0 for share in slid.ticks) else list(slid.ticks)
            self._last_slide = (key, slid, ticks)
        return self._last_slide[1], self._last_slide[2]

    # MORSE's body went at the speed set at the start of each tick, less what damping and friction took in
    # the tick (kits.ground_friction): its sensors read it at the end of the tick, at its lowest. The servos
    # hold the tick's mean (the robot goes as far as MORSE's); after the physics step the body is given the
    # speed MORSE's had at that moment, in its own plane, for the sensors, and the held one back before the
    # next step.
    def sample_tick_end(self) -> bool:
        """After a physics step: the body's planar velocity scaled to what MORSE's was at the tick's end.
        Whether it changed."""
        if not self.ticks:
            return False
        share = self.ticks.pop(0)
        if share == 1.0 or not self.free:
            return False
        v = self._base_qvel()
        held = v[:3].copy()
        _, rot = self.pose()
        body = rot.T @ held
        body[:2] *= share
        v[:3] = rot @ body
        self.sampled = (v[:3].copy(), held)
        return True

    def resume_held(self) -> None:
        """Before a physics step: the velocity held by the servos back, unless something set another since."""
        if self.sampled is None:
            return
        sampled, held = self.sampled
        self.sampled = None
        v = self._base_qvel()
        if np.array_equal(v[:3], sampled):
            v[:3] = held

    def coast(self, frequency: float) -> None:
        """No actuator sets the velocity this period (MORSE's Waypoint once arrived or stopped): a ground
        robot slides on, slowed by the ground's friction until it stops, as MORSE's; the servos then hold
        it still. A robot that is not on the ground is just held still."""
        if not self.servo:
            return
        if self._slid is None or not (self.free and self.ground):
            self.apply_speed("Velocity", [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], frequency)
            return
        slid = self._slid
        mean = self._slide(float(slid[0]), float(slid[1]), frequency)
        if self._slid is None or not any(self._slid):
            self._slid = None  # stopped (or lifted off): from now on held still
        self.sim.data.ctrl[self.servo] = [mean[0], mean[1], 0.0]
        self._follow.pop("base servos", None)

    GROUND_MEMORY = 0.25  # s: a robot that touched the ground this long ago still rests on it

    def _on_ground(self) -> bool:
        """Whether the robot rests on something that is not part of it (the ground, an object): it touched
        it within GROUND_MEMORY (a robot bouncing over a bump, off the ground for a tick or two, still
        rests on it)."""
        now = self.sim.clock.elapsed
        if self.index in self.sim.touching():
            self._touched = now
        return self._touched is not None and now - self._touched <= self.GROUND_MEMORY

    # ---- following a held command (morsec.runtime.trim)
    def follow(self, key: str, command, fraction: float = FOLLOW_FRACTION,
               settle: int = FOLLOW_SETTLE) -> tuple[float, float, float]:
        """What to drive the robot with so that it goes at `command` (vx, vy, wz: body frame; wz about the
        vertical for a ground robot): the command plus its trim (trim.Follow). `key` names who drives (one trim
        each); all trims are dropped when the robot is teleported. The trim is corrected once the command has
        been held `settle` calls."""
        c0, c1, c2 = (float(c) for c in command)
        if not (math.isfinite(c0) and math.isfinite(c1) and math.isfinite(c2)):
            raise ValueError(f"{key}: a command must be finite numbers, got {list(command)}")
        return self._follow_floats(key, c0, c1, c2, float(fraction), int(settle))

    def _follow_floats(self, key: str, c0: float, c1: float, c2: float, fraction: float = FOLLOW_FRACTION,
                       settle: int = FOLLOW_SETTLE) -> tuple[float, float, float]:
        """follow, the command given as floats."""
        state = self._follow.get(key)
        if state is None:
            state = self._follow[key] = trim.Follow()
        return state.drive(c0, c1, c2, self.sim.clock.elapsed, self._xpos.tolist(), self._xmat.tolist(), fraction,
                           settle, self.ground)

    def displace(self, body_translation: np.ndarray, body_rotation: np.ndarray) -> None:
        if not self.free:
            return
        pos, rot = self.pose()
        delta = quat_to_matrix(euler_to_quat(*body_rotation))
        self.set_pose(pos + rot @ body_translation, rot @ delta)

    def set_pose(self, pos, rot) -> None:
        """Put the base at a world pose and stop it."""
        joint = (self.qpos_adr, self.qvel_adr) if self.qpos_adr is not None and self.qvel_adr is not None else None
        place_with(self.sim.model, self.sim.data, self.body_id, joint, pos, rot)
        self.sim.poses_changed()
        self.stop()

    def base_qpos(self) -> np.ndarray:
        """The free joint's 7 positions in qpos (a view)."""
        assert self.qpos_adr is not None, f"robot {self.name} has no free joint"
        return self.sim.data.qpos[self.qpos_adr:self.qpos_adr + 7]

    def stop(self) -> None:
        """Stop the robot where it is: the velocity it had, and what followed from it, gone."""
        if self.free:
            self._base_qvel()[:] = 0.0
        self._follow.clear()
        self._slid = None
        self.ticks, self.sampled = [], None

    def place_frame(self, frame_body: int, pos, rot) -> None:
        """Move the robot so that the frame of body `frame_body` (one of its components) is at pos/rot."""
        d = self.sim.data
        base_pos, base_rot = self.pose()
        frame_pos, frame_rot = d.xpos[frame_body], d.xmat[frame_body].reshape(3, 3)
        rel_rot = base_rot.T @ frame_rot
        rel_pos = base_rot.T @ (frame_pos - base_pos)
        new_rot = np.asarray(rot) @ rel_rot.T
        self.set_pose(np.asarray(pos) - new_rot @ rel_pos, new_rot)

    # ---- forces: actuators that fly a robot (rotorcraft controllers) push its base body through
    # d.xfrc_applied, which MuJoCo keeps applying over the physics sub-steps until it is changed
    def subtree(self) -> list[int]:
        """The robot's bodies: its base and every body below it."""
        m = self.sim.model
        return [b for b in range(self.body_id, m.nbody)
                if b == self.body_id or _descends(m, b, self.body_id)]

    @property
    def mass(self) -> float:
        return float(self.sim.model.body_subtreemass[self.body_id])

    def centre_of_mass(self) -> np.ndarray:
        """The whole robot's centre of mass, world frame, from its bodies' (d.xipos: right after a teleport
        too, which updates the kinematics but not d.subtree_com)."""
        total = float(self._masses.sum())
        if total <= 0:
            return self.sim.data.xipos[self.body_id].copy()
        return self._masses @ self.sim.data.xipos[self.bodies] / total

    def weight(self) -> float:
        """Magnitude of the gravity force the robot feels, N (parts compensated by gravcomp excluded)."""
        m = self.sim.model
        g = float(np.linalg.norm(m.opt.gravity))
        return g * sum(float(m.body_mass[b]) * (1.0 - float(m.body_gravcomp[b])) for b in self.subtree())

    def inertia(self) -> np.ndarray:
        """3x3 inertia tensor of the whole robot about its centre of mass, in the base frame, kg m^2."""
        m, d = self.sim.model, self.sim.data
        base_pos, base_rot = self.pose()
        com = d.subtree_com[self.body_id]
        total = np.zeros((3, 3))
        for b in self.subtree():
            mass = float(m.body_mass[b])
            if mass <= 0:
                continue
            rot = base_rot.T @ d.ximat[b].reshape(3, 3)
            total += rot @ np.diag(m.body_inertia[b]) @ rot.T
            r = base_rot.T @ (d.xipos[b] - com)
            total += mass * (float(r @ r) * np.eye(3) - np.outer(r, r))
        return total

    def velocity(self) -> tuple[np.ndarray, np.ndarray]:
        """(linear, angular) velocity of the base frame's origin, world frame (of a free robot: read from
        qvel, so that a velocity just written there is seen at once)."""
        if self.free:
            v = self._base_qvel()
            return v[:3].copy(), self.pose()[1] @ v[3:]
        res = np.zeros(6)
        mujoco.mj_objectVelocity(self.sim.model, self.sim.data, mujoco.mjtObj.mjOBJ_BODY, self.body_id, res, 0)
        return res[3:].copy(), res[:3].copy()

    def apply_wrench(self, key: str, force, torque) -> None:
        """Set the world-frame force and torque that `key` (an actuator's name) applies to the robot, the
        force through the whole robot's centre of mass (as MORSE's applyForce: a Blender robot is one body
        whose origin is its centre of mass); the contributions of several actuators add up. Stays applied
        until changed."""
        if not hasattr(self, "_wrenches"):
            self._wrenches: dict[str, np.ndarray] = {}
        d = self.sim.data
        force = bounded(force, MAX_FORCE, "a force (N)")
        torque = bounded(torque, MAX_FORCE, "a torque (N m)")
        # MuJoCo applies xfrc_applied at the base body's own centre of mass: moved to the robot's
        lever = self.centre_of_mass() - d.xipos[self.body_id]
        self._wrenches[key] = np.concatenate([force, torque + np.cross(lever, force)])
        d.xfrc_applied[self.body_id] = np.sum(list(self._wrenches.values()), axis=0)


def _descends(m, body: int, ancestor: int) -> bool:
    while body:
        body = int(m.body_parentid[body])
        if body == ancestor:
            return True
    return False
