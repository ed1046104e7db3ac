"""The PR2's torso lift (MORSE's BasePR2 `torso`): an armature with one prismatic joint, torso_lift_joint."""

from morsec.component.catalogue import component_class

Armature = component_class("actuators", "armature")


class PR2Torso(Armature):
    """The PR2's torso lift: one prismatic joint, torso_lift_joint (0 .. 0.31 m, up), raising the upper body
    (torso_lift_link), on which the PR2's head and arms are mounted. Every armature service (`translate`,
    `set_translation`, trajectories ...); joint names may be given without `_joint` (`torso_lift`)."""

    short_descr = "PR2 torso lift: the prismatic torso_lift_joint (armature)"
    builder_name = "PR2Torso"
    xacro = "pr2_torso.urdf.xacro"
    mount_body = "torso_lift_link"
    ik_targets: dict[str, str] = {}
    joint_suffix = "_joint"
    # the lift's drive (a ball screw) reflected on the joint, kg: steadies the servo under the upper body
    joint_armature = {"torso_lift_joint": 20.0}


COMPONENT = PR2Torso
