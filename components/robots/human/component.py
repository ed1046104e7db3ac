"""MORSE's Human: the human avatar, a body that walks when an actuator moves it, with its skeleton posed by
five IK targets (head, wrists, feet)."""

from typing import ClassVar

from morsec.component import Robot, RobotProperties


class Human(Robot):
    """A standing person, MORSE's human avatar (human_rig.blend, made with MakeHuman): a 70 kg body on the
    ground (origin on the floor between the feet, facing +x) carrying its armature, `skeleton`
    (human_skeleton: MakeHuman's bones, IK targets `head`, `wrist_L`, `wrist_R`, `foot_L`, `foot_R`, a walk
    cycle while the human moves), and on it `joint_states` (armature_pose: {bone: angle}). Move it with a
    `waypoint`, `motion_vw`, `keyboard` ... (MORSE's accepted Position control only; both work here).
    `add_interface('socket')` streams `skeleton.joint_states` and serves the skeleton's and joint_states'
    services, as MORSE's."""

    short_descr = "Human avatar: walking body, MakeHuman skeleton posed by IK targets"
    builder_name = "Human"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.0

    default_components = (
        {"name": "skeleton", "type": "human_skeleton",
         "components": [{"name": "joint_states", "type": "armature_pose", "attribute": "joint_states"}]},
    )
    builder_interface: ClassVar[dict[str, dict[str, tuple]]] = {
        "*": {"streams": ("skeleton.joint_states",), "services": ("skeleton", "skeleton.joint_states")},
    }

    class Properties(RobotProperties):
        GroundRobot: bool = True


COMPONENT = Human
