"""The PR2's right arm (MORSE's BasePR2 `r_arm`): an armature with the PR2's seven arm joints."""

from morsec.component.catalogue import component_class

Armature = component_class("actuators", "armature")

JOINTS = ("shoulder_pan", "shoulder_lift", "upper_arm_roll", "elbow_flex", "forearm_roll", "wrist_flex", "wrist_roll")


class PR2RightArm(Armature):
    """The PR2's right arm: r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint,
    r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint (the PR2
    URDF's names and limits; forearm and wrist roll are continuous), straight forward at zero. Every armature
    service, trajectories and inverse kinematics (IK target r_wrist_roll_link, the wrist); joint names may
    be given without `_joint`. Components appended to it (a gripper) ride on the wrist, link
    r_wrist_roll_link."""

    short_descr = "PR2 right arm: the seven r_*_joint (armature)"
    builder_name = "PR2RightArm"
    xacro = "pr2_r_arm.urdf.xacro"
    mount_body = "r_wrist_roll_link"
    ik_targets = {"r_wrist_roll_link": "r_wrist_roll_link"}
    joint_suffix = "_joint"
    joint_armature = {f"r_{j}_joint": 0.1 for j in JOINTS}


COMPONENT = PR2RightArm
