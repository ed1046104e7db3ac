"""The PR2's left arm (MORSE's BasePR2 `l_arm`): an armature with the PR2's seven arm joints."""

from morsec.component.catalogue import component_class

Armature = component_class("actuators", "armature")

JOINTS = ("shoulder_pan", "shoulder_lift", "upper_arm_roll", "elbow_flex", "forearm_roll", "wrist_flex", "wrist_roll")


class PR2LeftArm(Armature):
    """The PR2's left arm: l_shoulder_pan_joint, l_shoulder_lift_joint, l_upper_arm_roll_joint,
    l_elbow_flex_joint, l_forearm_roll_joint, l_wrist_flex_joint, l_wrist_roll_joint (the PR2
    URDF's names and limits; forearm and wrist roll are continuous), straight forward at zero. Every armature
    service, trajectories and inverse kinematics (IK target l_wrist_roll_link, the wrist); joint names may
    be given without `_joint`. Components appended to it (a gripper) ride on the wrist, link
    l_wrist_roll_link."""

    short_descr = "PR2 left arm: the seven l_*_joint (armature)"
    builder_name = "PR2LeftArm"
    xacro = "pr2_l_arm.urdf.xacro"
    mount_body = "l_wrist_roll_link"
    ik_targets = {"l_wrist_roll_link": "l_wrist_roll_link"}
    joint_suffix = "_joint"
    joint_armature = {f"l_{j}_joint": 0.1 for j in JOINTS}


COMPONENT = PR2LeftArm
