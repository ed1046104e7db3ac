"""The PR2's joint state, MORSE's BasePR2 `joint_state` with its PR2JointStatePublisher: every joint of
the PR2 by its ROS name, those the model does not move (casters, grippers, laser tilt) at 0."""

from __future__ import annotations

from typing import ClassVar

import mujoco
import numpy as np

from morsec.component import DataField, Sensor
from morsec.kits import mjcf_names

# the PR2's joints, as `rostopic echo /joint_states` lists them on the real robot
PR2_JOINTS = (
    "fl_caster_rotation_joint", "fl_caster_l_wheel_joint", "fl_caster_r_wheel_joint",
    "fr_caster_rotation_joint", "fr_caster_l_wheel_joint", "fr_caster_r_wheel_joint",
    "bl_caster_rotation_joint", "bl_caster_l_wheel_joint", "bl_caster_r_wheel_joint",
    "br_caster_rotation_joint", "br_caster_l_wheel_joint", "br_caster_r_wheel_joint",
    "torso_lift_joint", "torso_lift_motor_screw_joint", "head_pan_joint", "head_tilt_joint",
    "laser_tilt_mount_joint",
    "r_upper_arm_roll_joint", "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_forearm_roll_joint",
    "r_elbow_flex_joint", "r_wrist_flex_joint", "r_wrist_roll_joint", "r_gripper_joint",
    "r_gripper_l_finger_joint", "r_gripper_r_finger_joint", "r_gripper_r_finger_tip_joint",
    "r_gripper_l_finger_tip_joint", "r_gripper_motor_screw_joint", "r_gripper_motor_slider_joint",
    "l_upper_arm_roll_joint", "l_shoulder_pan_joint", "l_shoulder_lift_joint", "l_forearm_roll_joint",
    "l_elbow_flex_joint", "l_wrist_flex_joint", "l_wrist_roll_joint", "l_gripper_joint",
    "l_gripper_l_finger_joint", "l_gripper_r_finger_joint", "l_gripper_r_finger_tip_joint",
    "l_gripper_l_finger_tip_joint", "l_gripper_motor_screw_joint", "l_gripper_motor_slider_joint",
)


class PR2JointState(Sensor):
    """The joint state of the PR2 it is on: `{joint: value}` for each of the PR2's 45 joints by its ROS name
    (`torso_lift_joint`, `head_pan_joint`, `l_shoulder_pan_joint` ...), rad or m. The joints of the robot's
    armatures (torso, head, arms) are read from the model; those morsec's PR2 does not model (casters,
    grippers, laser tilt, motor screws) are 0, as MORSE's PR2JointStatePublisher filled them in. A joint of
    another armature appended to the robot is listed too, by its own name."""

    short_descr = "PR2 joint state: its 45 joints by their ROS names"
    builder_name = "PR2JointState"
    frequency = 60.0

    # every joint MORSE's message holds, value 0 unless the robot has a joint of that name
    defaults: ClassVar[tuple[str, ...]] = PR2_JOINTS

    data = ()
    extra_field = DataField("<joint>", 0.0, "float", "position of each PR2 joint by its ROS name "
                            "(torso_lift_joint, head_pan_joint ...): rad (revolute) or m (prismatic)")

    @staticmethod
    def key(joint: str) -> str:
        """The message key of a joint of the model."""
        return joint

    def start(self):
        m = self.sim.model
        robot = self.robot.name
        hinge_slide = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
        ids, names = [], []
        for j in range(m.njnt):
            full = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) or ""
            owner = mjcf_names.owner(full)
            if int(m.jnt_type[j]) in hinge_slide and (owner == robot or owner.startswith(robot + ".")):
                ids.append(j)
                names.append(self.key(full.rsplit(mjcf_names.SEPARATOR, 1)[1]))
        self.names = names
        self._adr = m.jnt_qposadr[np.array(ids, dtype=int)].astype(int) if ids else np.zeros(0, dtype=int)
        for name in self.defaults:
            self.local_data[name] = 0.0
        self.default_action()

    def default_action(self):
        q = self.sim.data.qpos[self._adr]
        for name, value in zip(self.names, q):
            self.local_data[name] = float(value)


COMPONENT = PR2JointState
