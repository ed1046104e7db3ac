"""MORSE's Armature: a kinematic chain of revolute and prismatic joints (an arm), commanded joint by joint,
by trajectories or by placing its end with inverse kinematics.

The arm is the component's own model, a xacro file of its folder (`xacro`, read by the compiler: URDF
link L becomes body `<fqn>/L`, joint J `<fqn>/J`). Each joint is a real MuJoCo joint held by a position
servo of the same name (actuator.xml.j2); this actuator moves the servos' setpoints at the joint speeds
(`RotationSpeed`, `LinearSpeed` or a service's `speed`) with velocity and gravity feed-forward
(`morsec.kits.servos.JointServos`). `local_data` is the joint dict {joint: target}, root to tip: what a
stream sends in (joints it leaves out keep their targets). A movement is over when every joint is within
`AngleTolerance` (rad) or `DistanceTolerance` (m) of its target: a pending `rotate`, `translate`,
`rotate_joints` or `translate_joints` then answers SUCCESS.

Inverse kinematics, as MORSE's: an IK target is a pose of its own (MORSE's empty `ik_target.<arm>.<bone>`),
at first the pose of its link (the end of the arm) with the arm at rest, kept in the arm's base frame;
`place_IK_target` and `move_IK_target` move it (relative moves are relative to it, not to where the arm
got), and the joints follow by inverse kinematics: MuJoCo's own Jacobians (`morsec.kits.ik`), damped least
squares on `mj_jac` of the link, on a scratch MjData, joint limits clamped at each step. A target out of
reach leaves the arm at the least-squares compromise between its position and its orientation (an angle
error counting IK_ROT_WEIGHT m/rad), as MORSE's IK did, and the services succeed.
Subclasses (KukaLWR, the PR2's armatures) set `xacro`, `mount_body` (where appended components go: they are
placed in the arm's frame, joints at zero, and ride on that body), `ik_targets`, `joint_armature` and
`joint_suffix`.
"""

from __future__ import annotations

import logging
import math
from typing import Any, ClassVar

import mujoco
import numpy as np
from pydantic import Field

from morsec.component import Actuator, ComponentProperties, DataField, async_service, service
from morsec.kits.geometry import euler_to_quat, quat_to_matrix
from morsec.kits.ik import InverseKinematics, rotation_error, slerp
from morsec.kits.servos import JointServos

log = logging.getLogger("morsec.actuators.armature")

IK_SETTLE_S = 2.0  # after a move_IK_target's target got there, at most this long for the arm to settle
# an orientation error of 1 rad weighs as much as IK_ROT_WEIGHT m of position error when a target is out of
# reach: the compromise MORSE's Blender IK (iTaSC) found for the KUKA (base/armature_testing.py: a target 1 m
# away at shoulder height, kept pointing up, leaves the tip at x 0.778, z 0.363, tilted 0.02 rad)
IK_ROT_WEIGHT = 1.5


class Armature(Actuator):
    """A chain of revolute and prismatic joints: the joint dict {joint: value} (rad or m) streams in;
    services set joints at once (`set_rotation(s)`, `set_translation(s)`), move them at a speed
    (`rotate`, `translate`, ...: asynchronous), follow a timed trajectory (`trajectory`), or place the end
    of the arm by inverse kinematics (`place_IK_target`, `move_IK_target`). Its own arm is a small example
    (shoulder yaw and pitch, elbow, a telescopic end); KukaLWR is a real one. Read the joints with an
    `armature_pose` sensor appended to it."""

    short_descr = "Kinematic chain of revolute and prismatic joints (an arm), by joints, trajectories or IK"
    builder_name = "Armature"
    frequency = 60.0

    # read by the compiler: the arm's description and the body its children components are mounted in
    xacro: ClassVar[str] = "armature.urdf.xacro"
    mount_body: ClassVar[str | None] = "extension"
    mount_in_own_frame: ClassVar[bool] = True  # children placed in the arm's frame (MORSE's armatures)
    joint_armature: ClassVar[dict[str, float]] = {"shoulder_yaw": 0.05, "shoulder_pitch": 0.05, "elbow": 0.05,
                                                  "extension": 0.2}
    # MORSE's IK targets: {name (MORSE's bone): link whose origin and frame the target is}
    ik_targets: ClassVar[dict[str, str]] = {"extension": "extension"}
    # a suffix services may leave out of a joint's name (the PR2's "_joint": `head_pan` for `head_pan_joint`)
    joint_suffix: ClassVar[str] = ""

    class Properties(ComponentProperties):
        DistanceTolerance: float = Field(0.005, gt=0, description="tolerance when translating a joint or "
                                         "placing an IK target, m")
        AngleTolerance: float = Field(0.01, gt=0, description="tolerance when rotating a joint or orienting "
                                      "an IK target, rad")
        RotationSpeed: float = Field(0.8, gt=0, description="default speed of the revolute joints, rad/s")
        LinearSpeed: float = Field(0.05, gt=0, description="default speed of the prismatic joints, m/s")
        IKRotationSpeed: float = Field(0.5, gt=0, description="default rotation speed of an IK target, rad/s")
        IKLinearSpeed: float = Field(0.5, gt=0, description="default linear speed of an IK target, m/s")

    data = ()  # the joints, from the model: {joint name: position}, root to tip
    extra_field = DataField("<joint>", 0.0, "float", "target of each joint named (its name in the arm's model), "
                            "rad (revolute) or m (prismatic); joints left out keep their targets")

    # ------------------------------------------------------------------ set up
    def start(self):
        m = self.sim.model
        self.servos = JointServos(self.sim, self.name)
        if not self.servos.names:
            raise ValueError("its model has no joints: an armature needs revolute or prismatic joints")
        q = self.servos.positions()
        self.local_data.clear()
        self.local_data.update((n, float(v)) for n, v in zip(self.servos.names, q))
        self._targets = q.copy()
        self.joint_speed: dict[str, float] = {}
        self._trajectory: dict | None = None
        self._ik_move: dict | None = None
        self._warned: set[str] = set()
        self._base = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, self.name)
        self._ik_bodies = {}
        self._ik_poses = {}  # {target: (position, rotation) in the arm's base frame}: MORSE's empties
        for target, link in self.ik_targets.items():
            body = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, f"{self.name}/{link}")
            if body >= 0:
                self._ik_bodies[target] = body
                self._ik_poses[target] = self._to_base(self.sim.data.xpos[body], self.sim.data.xmat[body])
        self._ik = InverseKinematics(m, self.servos)
        self.servos.command(q)

    def reset(self):
        self.start()  # joint targets back to the (restored) initial positions

    # ------------------------------------------------------------------ joints
    @property
    def names(self) -> list[str]:
        return self.servos.names

    def _index(self, joint: str) -> int:
        if joint not in self.servos.index and self.joint_suffix and f"{joint}{self.joint_suffix}" in self.servos.index:
            joint = f"{joint}{self.joint_suffix}"
        if joint not in self.servos.index:
            raise ValueError(f"joint <{joint}> does not exist in armature {self.name} "
                             f"(joints: {', '.join(self.names)})")
        return self.servos.index[joint]

    def _revolute(self, joint: str) -> int:
        i = self._index(joint)
        if self.servos.prismatic[i]:
            raise ValueError(f"joint {joint} is not a revolute joint: cannot set its rotation")
        return i

    def _prismatic(self, joint: str) -> int:
        i = self._index(joint)
        if not self.servos.prismatic[i]:
            raise ValueError(f"joint {joint} is not a prismatic joint: cannot set its translation")
        return i

    def joint_values(self) -> dict[str, float]:
        return {n: float(v) for n, v in zip(self.names, self.servos.positions())}

    def _read_targets(self) -> np.ndarray:
        """The targets in local_data (a stream message may leave joints out: they keep theirs), clamped to
        the joint limits and written back."""
        local = self.local_data
        for key in [k for k in local if k not in self.servos.index]:
            if key not in self._warned:
                self._warned.add(key)
                log.warning("%s: no joint %r (joints: %s): ignored", self.name, key, ", ".join(self.names))
            del local[key]
        values = np.array([float(local.get(n, t)) for n, t in zip(self.names, self._targets)])
        values = self.servos.clamp(values)
        self._targets = values
        for n, v in zip(self.names, values):
            local[n] = float(v)
        return values

    def _set_targets(self, values) -> None:
        values = self.servos.clamp(values)
        self._targets = values
        for n, v in zip(self.names, values):
            self.local_data[n] = float(v)

    def _tolerances(self) -> np.ndarray:
        p = self.properties
        return np.where(self.servos.prismatic, p.DistanceTolerance, p.AngleTolerance)

    def _reached(self, targets, scale: float = 1.0) -> bool:
        """Every joint within tolerance (times `scale`) of its target, and settled (slower than 10 tolerances
        per second)."""
        tol = self._tolerances() * scale
        speed = np.abs(self.sim.data.qvel[self.servos.dof])
        return bool(np.all(np.abs(np.asarray(targets) - self.servos.positions()) < tol) and np.all(speed < 10 * tol))

    def _stop_motions(self) -> None:
        """A joint-level command ends IK moves and trajectories (MORSE suspends its IK targets)."""
        self._ik_move = None
        self._trajectory = None

    # ------------------------------------------------------------------ the tick
    def default_action(self):
        if self._ik_move is not None:
            self.servos.release()
            self._exec_ik_move()
            return
        if self._trajectory is not None:
            self._exec_trajectory()
            return
        targets = self._read_targets()
        servos = self.servos
        p = self.properties
        speeds = np.array([self.joint_speed.get(n) or (p.LinearSpeed if pr else p.RotationSpeed)
                           for n, pr in zip(self.names, servos.prismatic)])
        delta = np.clip(targets - servos.setpoint, -speeds / self.frequency, speeds / self.frequency)
        servos.command(servos.setpoint + delta, delta * self.frequency, held=1.0 / self.frequency)
        if self._reached(targets):
            self.joint_speed.clear()
            self.servos.hold(targets)
            self.completed("SUCCESS")
        else:
            self.servos.release()

    # ------------------------------------------------------------------ services: joints
    def _teleport(self, indices: list[int], values: list[float]) -> None:
        self._stop_motions()
        targets = self._read_targets().copy()
        targets[indices] = values
        targets = self.servos.clamp(targets)
        self._set_targets(targets)
        self.servos.teleport(targets[indices], indices)

    @service
    def set_rotation(self, joint: str, rotation: float) -> None:
        """Turn a revolute joint to `rotation` (rad, from its origin, clamped to its limits) at once."""
        self._teleport([self._revolute(joint)], [float(rotation)])

    @service
    def set_rotations(self, rotations: list[float]) -> None:
        """Set the first len(rotations) joints, root to tip (`get_joints`), at once; they must all be revolute
        (else nothing moves). Extra values are ignored."""
        n = min(len(rotations), len(self.names))
        for i in range(n):
            if self.servos.prismatic[i]:
                raise ValueError(f"joint {self.names[i]} is not a revolute joint: cannot apply the rotation set")
        self._teleport(list(range(n)), [float(r) for r in rotations[:n]])

    @service
    def set_translation(self, joint: str, translation: float) -> None:
        """Move a prismatic joint to `translation` (m, from its origin, clamped to its limits) at once."""
        self._teleport([self._prismatic(joint)], [float(translation)])

    @service
    def set_translations(self, translations: list[float]) -> None:
        """Set the first len(translations) joints, root to tip, at once; they must all be prismatic."""
        n = min(len(translations), len(self.names))
        for i in range(n):
            if not self.servos.prismatic[i]:
                raise ValueError(f"joint {self.names[i]} is not a prismatic joint: cannot apply the translation set")
        self._teleport(list(range(n)), [float(t) for t in translations[:n]])

    def _move(self, joints: dict[str, float], speed: float | None, check) -> None:
        indices = {joint: check(joint) for joint in joints}  # all checked before anything moves
        self._stop_motions()
        targets = self._read_targets().copy()
        for joint, value in joints.items():
            targets[indices[joint]] = float(value)
            self.joint_speed[self.names[indices[joint]]] = abs(float(speed)) if speed else None
        self._set_targets(targets)

    @async_service(interruptible=True)
    def rotate(self, joint: str, rotation: float, speed: float | None = None) -> None:
        """Turn a revolute joint to `rotation` (rad, clamped to its limits) at `speed` rad/s (default:
        RotationSpeed); answers when it is there."""
        self._move({joint: rotation}, speed, self._revolute)

    @async_service(interruptible=True)
    def rotate_joints(self, joint_rotations: dict[str, float], speed: float | None = None) -> None:
        """Turn several revolute joints {joint: rad} at `speed` rad/s; answers when all are there."""
        self._move(dict(joint_rotations), speed, self._revolute)

    @async_service(interruptible=True)
    def translate(self, joint: str, translation: float, speed: float | None = None) -> None:
        """Move a prismatic joint to `translation` (m, clamped) at `speed` m/s (default: LinearSpeed)."""
        self._move({joint: translation}, speed, self._prismatic)

    @async_service(interruptible=True)
    def translate_joints(self, joint_translations: dict[str, float], speed: float | None = None) -> None:
        """Move several prismatic joints {joint: m} at `speed` m/s; answers when all are there."""
        self._move(dict(joint_translations), speed, self._prismatic)

    @service
    def get_joints(self) -> list[str]:
        """The names of the joints, root to tip (the order of set_rotations and trajectories)."""
        return list(self.names)

    @service
    def get_dofs(self) -> dict[str, list[bool]]:
        """{joint: [x, y, z]}: the axes (of the joint's own frame) it turns about or slides along."""
        m = self.sim.model
        return {n: [bool(abs(a) > 1e-6) for a in m.jnt_axis[j]] for n, j in zip(self.names, self.servos.joints)}

    @service
    def get_IK_limits(self, joint: str) -> list[float] | None:
        """[min, max] of a joint (rad or m), None when it has no limits."""
        i = self._index(joint)
        return [float(v) for v in self.servos.range[i]] if self.servos.limited[i] else None

    # ------------------------------------------------------------------ services: trajectories
    @async_service
    def trajectory(self, trajectory: dict[str, Any]) -> None:
        """Follow a joint trajectory, MORSE's (ROS JointTrajectory's) format: {"starttime": t (optional,
        simulation clock, s: not before now), "points": [{"positions": [...], "time_from_start": s}, ...]}.
        Positions are root to tip (`get_joints`; joints left out keep their targets); velocities and
        accelerations, if given, are ignored: the joints go linearly from point to point, each reached at its
        time. Answers SUCCESS once the last point's time has passed and the joints are there."""
        try:
            points = trajectory["points"]
            parsed, last = [], -math.inf
            for p in points:
                t = float(p["time_from_start"])
                if t < last:
                    raise ValueError("trajectory points must be in time order (time_from_start)")
                last = t
                values = self._read_targets().copy()
                positions = [float(v) for v in p["positions"]][:len(self.names)]
                values[:len(positions)] = positions
                parsed.append((t, self.servos.clamp(values)))
        except KeyError as err:
            raise ValueError(f"invalid trajectory: key {err} was expected") from None
        except (TypeError, AttributeError):
            raise ValueError("invalid trajectory: expected {\"points\": [{\"positions\": [...], "
                             "\"time_from_start\": s}, ...]}") from None
        if not parsed:
            raise ValueError("invalid trajectory: no points")
        now = self.sim.clock.now()
        start = max(now, float(trajectory.get("starttime", now) or now))
        self._ik_move = None
        self._trajectory = {"start": start, "points": parsed, "origin": None}

    def _exec_trajectory(self) -> None:
        traj = self._trajectory
        t = self.sim.clock.now() - traj["start"]
        servos = self.servos
        servos.release()
        if t < 0:
            servos.command(servos.setpoint)
            return
        if traj["origin"] is None:
            traj["origin"] = (t, servos.setpoint.copy())
        previous = traj["origin"]
        for time, values in traj["points"]:
            if time > t:
                span = time - previous[0]
                frac = (t - previous[0]) / span if span > 0 else 1.0
                velocity = (values - previous[1]) / span if span > 0 else np.zeros_like(values)
                servos.command(previous[1] + frac * (values - previous[1]), velocity, held=1.0 / self.frequency)
                self._set_targets(values)
                return
            previous = (time, values)
        final = traj["points"][-1][1]
        servos.command(final)
        self._set_targets(final)
        if self._reached(final):
            self._trajectory = None
            servos.hold(final)
            self.completed("SUCCESS")

    # ------------------------------------------------------------------ services: inverse kinematics
    @service
    def list_IK_targets(self) -> list[str]:
        """The IK targets of this armature, MORSE's names: `ik_target.<armature>.<bone>` (`ik_target.robot.arm.
        kuka_7`): the ends of the arm that `place_IK_target` / `move_IK_target` place."""
        return [self._ik_name(target) for target in sorted(self._ik_bodies)]

    def _ik_name(self, target: str) -> str:
        return f"ik_target.{self.name}.{target}"

    def _ik_target(self, name: str) -> str:
        """The target named as list_IK_targets names it, or by its bone alone (`kuka_7`)."""
        prefix = self._ik_name("")
        target = name[len(prefix):] if name.startswith(prefix) else name
        if target not in self._ik_bodies:
            raise ValueError(f"IK target <{name}> does not exist for armature {self.name} "
                             f"(targets: {', '.join(self.list_IK_targets()) or 'none'})")
        return target

    def _base_frame(self) -> tuple[np.ndarray, np.ndarray]:
        d = self.sim.data
        return d.xpos[self._base].copy(), d.xmat[self._base].reshape(3, 3).copy()

    def _to_base(self, pos, xmat) -> tuple[np.ndarray, np.ndarray]:
        origin, frame = self._base_frame()
        return frame.T @ (np.asarray(pos) - origin), frame.T @ np.asarray(xmat).reshape(3, 3)

    def _to_world(self, pos, rot) -> tuple[np.ndarray, np.ndarray]:
        origin, frame = self._base_frame()
        return origin + frame @ pos, frame @ rot

    def _ik_goal(self, name: str, translation, euler_rotation, relative: bool):
        """(target, its pose now, its goal pose), world frame: MORSE's rules. Translation in the world frame,
        added to the target's position when `relative`; rotation XYZ Euler in the world frame, turning the
        target's orientation when `relative`; no rotation: the target keeps its orientation."""
        target = self._ik_target(name)
        pos, rot = self._to_world(*self._ik_poses[target])
        translation = np.asarray([float(v) for v in translation], dtype=float)
        if translation.shape != (3,):
            raise ValueError("translation must be [x, y, z]")
        goal_pos = pos + translation if relative else translation
        goal_rot = rot
        if euler_rotation:
            if len(euler_rotation) != 3:
                raise ValueError("euler_rotation must be [rx, ry, rz]")
            delta = quat_to_matrix(euler_to_quat(*(float(v) for v in euler_rotation)))
            goal_rot = delta @ rot if relative else delta
        return target, pos, rot, goal_pos, goal_rot

    def _orientation_counts(self) -> bool:
        """An arm of 6 joints or more holds its target's orientation too; a shorter one, the position only."""
        return len(self.names) >= 6

    def solve_ik(self, body: int, pos, rot=None, start=None, iterations: int = 200,
                 restarts: int = 0) -> tuple[np.ndarray, float, float]:
        """Joint values (within the limits) putting body `body`'s origin at `pos` (and its frame at `rot`),
        from `start` (default: the current joints), within the tolerances, else as near as the arm gets:
        `morsec.kits.ik`. Returns (joints, remaining distance m, remaining angle rad)."""
        p = self.properties
        return self._ik.solve(self.sim.data, body, pos, rot, tolerances=(p.DistanceTolerance, p.AngleTolerance),
                              start=start, iterations=iterations, restarts=restarts, rot_weight=IK_ROT_WEIGHT)

    def _solve_target(self, target: str, pos, rot, **kwargs) -> tuple[np.ndarray, float, float]:
        return self.solve_ik(self._ik_bodies[target], pos, rot if self._orientation_counts() else None, **kwargs)

    @service
    def place_IK_target(self, name: str, translation: list[float], euler_rotation: list[float] | None = None,
                        relative: bool = True) -> None:
        """Put the IK target `name` at `translation` (world frame, m; added to the target's position when
        `relative`) and, if given, turn it by `euler_rotation` (XYZ Euler in the world frame, rad; from the
        target's orientation when `relative`), at once: the joints jump to the inverse kinematics solution.
        A target out of reach leaves the arm as near as it gets (as MORSE's)."""
        target, _, _, goal_pos, goal_rot = self._ik_goal(name, translation, euler_rotation, relative)
        self._ik_poses[target] = self._to_base(goal_pos, goal_rot)
        q, err_p, err_a = self._solve_target(target, goal_pos, goal_rot, restarts=8)
        self._stop_motions()
        self.joint_speed.clear()
        self._set_targets(q)
        self.servos.teleport(q)
        self._log_reach(name, err_p, err_a)

    def _log_reach(self, name: str, err_p: float, err_a: float) -> None:
        p = self.properties
        if err_p > p.DistanceTolerance or err_a > p.AngleTolerance:
            log.info("%s: IK target %s out of reach: the arm stops %.3f m and %.3f rad from it",
                     self.name, name, err_p, err_a)

    @async_service(interruptible=True)
    def move_IK_target(self, name: str, translation: list[float], euler_rotation: list[float] | None = None,
                       relative: bool = True, linear_speed: float | None = None,
                       radial_speed: float | None = None) -> None:
        """Move the IK target `name` to `translation` / `euler_rotation` (as `place_IK_target`) at
        `linear_speed` m/s along each axis (default IKLinearSpeed), turning at `radial_speed` rad/s (default
        IKRotationSpeed); the joints follow by inverse kinematics. Answers SUCCESS once the target is there
        and the arm has settled (as near as it gets, if the target is out of reach)."""
        target, pos, rot, goal_pos, goal_rot = self._ik_goal(name, translation, euler_rotation, relative)
        p = self.properties
        lspeed = abs(float(linear_speed)) if linear_speed else p.IKLinearSpeed
        rspeed = abs(float(radial_speed)) if radial_speed else p.IKRotationSpeed
        angle = float(np.linalg.norm(rotation_error(goal_rot, rot)))
        self._trajectory = None
        self.joint_speed.clear()
        self._ik_move = {"name": name, "target": target, "goal_pos": goal_pos, "rot": rot, "goal_rot": goal_rot,
                         "t0": self.sim.clock.now(), "turn": angle / rspeed, "step": lspeed / self.frequency,
                         "there": None}

    def _exec_ik_move(self) -> None:
        """One tick: the target steps towards its goal (each axis at most the linear speed, MORSE's way; the
        orientation turns along the shortest arc in angle / radial speed), the joints follow."""
        move, servos = self._ik_move, self.servos
        target = move["target"]
        now = self.sim.clock.now()
        pos, _ = self._to_world(*self._ik_poses[target])
        tol = self.properties.DistanceTolerance
        dist = move["goal_pos"] - pos
        pos = move["goal_pos"].copy() if np.all(np.abs(dist) < tol) else \
            pos + np.clip(dist, -move["step"], move["step"])
        turned = (now - move["t0"]) / move["turn"] if move["turn"] > 0 else 1.0
        rot = slerp(move["rot"], move["goal_rot"], min(1.0, turned))
        self._ik_poses[target] = self._to_base(pos, rot)
        there = bool(np.all(pos == move["goal_pos"])) and turned >= 1.0
        # on the way, a few iterations a tick follow the target; once it is there, the solver runs to the end
        q, _, _ = self._solve_target(target, pos, rot, start=servos.setpoint, iterations=200 if there else 30)
        servos.command(q, (q - servos.setpoint) * self.frequency, held=1.0 / self.frequency)
        self._set_targets(q)
        if not there:
            return
        if move["there"] is None:
            move["there"] = now
        # the arm's end within a few mm of the solution: joints within a tenth of their tolerances
        if self._reached(q, 0.1) or now - move["there"] > IK_SETTLE_S:
            self._ik_move = None
            self.completed("SUCCESS")

    # ------------------------------------------------------------------ cancel
    def interrupt(self) -> None:
        """A cancelled (or preempted) movement stops where the arm is."""
        self._stop_motions()
        self.joint_speed.clear()
        q = self.servos.positions()
        self._set_targets(q)
        self.servos.command(q)


COMPONENT = Armature
