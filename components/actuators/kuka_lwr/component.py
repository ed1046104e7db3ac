"""MORSE's KukaLWR: the KUKA LWR 4+ arm, an armature with 7 revolute joints (kuka_1 .. kuka_7).

Everything but the arm's description comes from `armature`: joint services, trajectories, inverse
kinematics (IK target `kuka_7`, the tool flange), streaming joint targets in. Components appended to it
(a gripper) are mounted on the flange, link kuka_7, whose z axis points out of the arm.
"""

from morsec.component.catalogue import component_class

Armature = component_class("actuators", "armature")


class KukaLWR(Armature):
    """The KUKA LWR 4+ lightweight arm: 7 revolute joints kuka_1 .. kuka_7 (A1, A3, A5, A7 along the arm,
    A2, A4, A6 across it), 0.31 / 0.40 / 0.39 / 0.078 m between base, shoulder, elbow, wrist and flange,
    straight up at zero. IK target `kuka_7` (the flange); appended components ride on the flange."""

    short_descr = "KUKA LWR 4+ arm: 7 revolute joints, joint services, trajectories and IK"
    builder_name = "KukaLWR"
    xacro = "kuka_lwr.urdf.xacro"
    mount_body = "kuka_7"
    ik_targets = ("kuka_7",)
    # reflected drive inertia (harmonic drive and motor), kg m^2: keeps the stiff joint servos stable
    joint_armature = {f"kuka_{i}": 0.1 for i in range(1, 8)}


COMPONENT = KukaLWR
