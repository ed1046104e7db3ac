"""MORSE's KukaLWR: the KUKA LWR 4+ arm, an armature with 7 revolute joints (kuka_1 .. kuka_7).

Everything but the arm's description comes from `armature`: joint services, trajectories, inverse
kinematics (IK target `kuka_7`: the tip of the arm, link kuka_7_tip, in MORSE's frame), streaming joint
targets in. Components appended to it (a gripper) are placed in the arm's frame, as MORSE's (the arm
straight up, its tip 1.3105 m above its base), and ride on its last link, kuka_7.
"""

from morsec.component.catalogue import component_class

Armature = component_class("actuators", "armature")


class KukaLWR(Armature):
    """The KUKA LWR 4+ lightweight arm, as MORSE's model: 7 revolute joints kuka_1 .. kuka_7 (A1, A3, A5, A7
    along the arm, A2, A4, A6 across it), segments 0.3105, 0.20, 0.20, 0.20, 0.19, 0.08 and 0.13 m, straight
    up at zero. IK target `kuka_7` (the tip, 1.3105 m above the base); appended components are placed in the
    arm's frame and ride on its last link."""

    short_descr = "KUKA LWR 4+ arm: 7 revolute joints, joint services, trajectories and IK"
    builder_name = "KukaLWR"
    xacro = "kuka_lwr.urdf.xacro"
    mount_body = "kuka_7"
    ik_targets = {"kuka_7": "kuka_7_tip"}
    # reflected drive inertia (harmonic drive and motor), kg m^2: keeps the stiff joint servos stable
    joint_armature = {f"kuka_{i}": 0.1 for i in range(1, 8)}


COMPONENT = KukaLWR
