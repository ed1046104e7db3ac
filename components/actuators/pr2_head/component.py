"""The PR2's head (MORSE's BasePR2 `head`): an armature with head_pan_joint and head_tilt_joint."""

from morsec.component.catalogue import component_class

Armature = component_class("actuators", "armature")


class PR2Head(Armature):
    """The PR2's pan-tilt head: head_pan_joint (about z, +-3.007 rad) and head_tilt_joint (about y,
    -0.471 .. 1.396 rad, positive looks down). Every armature service (`rotate`, `set_rotation` ...); joint
    names may be given without `_joint` (`head_pan`). Components appended to it (cameras) ride on the tilting
    head, link head_tilt_link."""

    short_descr = "PR2 head: head_pan_joint and head_tilt_joint (armature)"
    builder_name = "PR2Head"
    xacro = "pr2_head.urdf.xacro"
    mount_body = "head_tilt_link"
    ik_targets: dict[str, str] = {}
    joint_suffix = "_joint"
    joint_armature = {"head_pan_joint": 0.05, "head_tilt_joint": 0.05}


COMPONENT = PR2Head
