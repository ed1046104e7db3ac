"""Joint servos for components with moving parts of their own (a pan-tilt unit, an arm): the hinge and
slide joints of the component's model, each held by a MuJoCo position servo, and the setpoints sent to
them with velocity and gravity feed-forward."""

from __future__ import annotations

import mujoco
import numpy as np

from morsec.constants import MAX_POSITION, MAX_SPEED
from morsec.kits import mjcf_names
from morsec.kits.bounds import bounded

# a bone turning about several axes (a human's): joint `<bone>` about its first axis, `<bone>:<axis>` about the
# others; the bone (MORSE's channel) reads as its first joint
AXIS_SEPARATOR = ":"


def is_bone(joint: str) -> bool:
    """Whether a joint of an armature is a bone's own (MORSE's channel), not one of its further axes."""
    return AXIS_SEPARATOR not in joint


class JointServos:
    """The hinge and slide joints of a component's own model (a pan-tilt unit, an arm: joints named
    `<fqn>/<joint>`), each held by the MuJoCo position actuator of the same name (the component's
    actuator.xml.j2). `command` sets the servos' setpoints; the control sent to MuJoCo adds velocity and
    gravity feed-forward, (kv * velocity + qfrc_bias) / kp, so that a joint follows a moving setpoint
    without lag and does not sag under the weight of the links it carries."""

    def __init__(self, sim, prefix: str):
        m = sim.model
        self.sim = sim
        self.prefix = prefix
        ids = [j for j in range(m.njnt)
               if mjcf_names.belongs_to(mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) or "", prefix)
               and int(m.jnt_type[j]) in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))]
        self.names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j)[len(mjcf_names.part(prefix, "")):]
                      for j in ids]
        self.joints = np.array(ids, dtype=int)
        self.qpos = m.jnt_qposadr[self.joints].astype(int)
        self.dof = m.jnt_dofadr[self.joints].astype(int)
        self.prismatic = m.jnt_type[self.joints] == int(mujoco.mjtJoint.mjJNT_SLIDE)
        self.limited = m.jnt_limited[self.joints].astype(bool)
        self.range = m.jnt_range[self.joints].copy()
        acts = []
        for name in self.names:
            act = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, mjcf_names.part(prefix, name))
            if act < 0:
                raise ValueError(f"joint {name!r} of {prefix} has no position servo named "
                                 f"{mjcf_names.part(prefix, name)} in "
                                 "scene.xml (the component's actuator.xml.j2): rebuild the scene")
            acts.append(act)
        self.actuators = np.array(acts, dtype=int)
        self.kp = m.actuator_gainprm[self.actuators, 0].copy()
        self.kv = -m.actuator_biasprm[self.actuators, 2].copy()
        self.index = {name: i for i, name in enumerate(self.names)}
        self.setpoint = self.positions()

    def positions(self) -> np.ndarray:
        return self.sim.data.qpos[self.qpos].copy()

    def clamp(self, values) -> np.ndarray:
        values = np.asarray(values, dtype=float)
        return np.where(self.limited, np.clip(values, self.range[:, 0], self.range[:, 1]), values)

    def command(self, setpoint, velocity=None, held: float = 0.0) -> None:
        """Hold the joints at `setpoint` (moving at `velocity`, per joint, when given). `held`: how long (s)
        this command stays, when the setpoint is where the joints must be at its end (a component moving
        its setpoints tick by tick): the servos aim at the middle of that span, so that the joints get to
        the setpoint at its end rather than overshooting it by half the step."""
        d = self.sim.data
        self.setpoint = bounded(setpoint, MAX_POSITION, "a joint setpoint (rad or m)").copy()
        # gravity and Coriolis forces, less what MuJoCo's gravity compensation already cancels (the arm of
        # a floating robot)
        ff = d.qfrc_bias[self.dof] - d.qfrc_gravcomp[self.dof]
        aim = self.setpoint
        if velocity is not None:
            velocity = bounded(velocity, MAX_SPEED, "a joint speed (rad/s or m/s)")
            ff += self.kv * velocity
            aim = aim - velocity * held / 2
        d.ctrl[self.actuators] = aim + ff / np.where(self.kp > 0, self.kp, 1.0)

    def hold(self, values) -> None:
        """Keep the joints exactly at `values` (within their limits) after every physics step, until `release`:
        joints at rest stay where they were put, not where the servo settles (a micron off), as MORSE's
        kinematic armatures did. The servos still push: what the joints carry weighs on the robot."""
        self.sim.joint_holds[self] = (self.qpos, self.dof, self.clamp(values))

    def release(self) -> None:
        self.sim.joint_holds.pop(self, None)

    def teleport(self, values, which=None) -> None:
        """Put joints at `values` at once, at rest, and hold them there: all of them, or those of the
        indices `which` (`values` then gives theirs, in that order)."""
        d = self.sim.data
        which = np.arange(len(self.names)) if which is None else np.asarray(which, dtype=int)
        values = bounded(values, MAX_POSITION, "a joint position (rad or m)")
        d.qpos[self.qpos[which]] = values
        d.qvel[self.dof[which]] = 0.0
        mujoco.mj_kinematics(self.sim.model, d)
        self.sim.poses_changed()
        setpoint = self.setpoint.copy()
        setpoint[which] = values
        self.command(setpoint)
