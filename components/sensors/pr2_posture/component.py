"""MORSE's PR2Posture: the PR2's armature joints by their short names (head_pan, torso_lift ...)."""

from morsec.component import DataField
from morsec.component.catalogue import component_class

PR2JointState = component_class("sensors", "pr2_joint_state")


class PR2Posture(PR2JointState):
    """The posture of the PR2 it is on: `{joint: value}` for each joint of the robot's armatures (torso, head,
    arms), by its name without `_joint` (`torso_lift`, `head_pan`, `head_tilt`, `l_shoulder_pan` ...): the
    names MORSE's older PR2 model and its PR2Posture sensor gave the head's joints, which the PR2's
    armatures accept too. rad or m."""

    short_descr = "PR2 posture: its armatures' joints by their short names (head_pan ...)"
    builder_name = "PR2Posture"
    defaults = ()
    extra_field = DataField("<joint>", 0.0, "float", "position of each joint of the robot's armatures by its "
                            "name without '_joint' (head_pan, torso_lift ...): rad or m")

    @staticmethod
    def key(joint: str) -> str:
        return joint.removesuffix("_joint")


COMPONENT = PR2Posture
