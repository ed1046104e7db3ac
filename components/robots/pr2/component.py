"""Willow Garage's PR2, MORSE's BasePR2: the body with its armatures (torso lift, head, arms) and joint-state
sensors, as MORSE's builder equipped it."""

from typing import ClassVar

from morsec.component import Robot, RobotProperties


def _armature(name: str, type_: str, translate: list[float]) -> dict:
    return {"name": name, "type": type_, "translate": translate,
            "components": [{"name": "pose", "type": "armature_pose"}]}


# the PR2's armatures and the names of their controllers on the real robot
_CONTROLLERS = (("torso", "torso_controller"), ("head", "head_traj_controller"), ("l_arm", "l_arm_controller"),
                ("r_arm", "r_arm_controller"))


class DrivenPR2Builder:
    """MORSE's builder of the PR2s it equipped to move, LocalizedPR2 and NavPR2: (name=None,
    with_keyboard=True, show_laser=False); with_keyboard=False leaves the keyboard out, show_laser shows the
    base laser's arc (NavPR2's `base_scan`; LocalizedPR2 has none)."""

    def __init__(self, name=None, with_keyboard=True, show_laser=False):
        super().__init__(name, _without=() if with_keyboard else ("keyboard",))
        if show_laser and "base_scan" in vars(self):
            self.base_scan.properties(Visible_arc=True)


class BasePR2(Robot):
    """Willow Garage's PR2 with its armatures, MORSE's BasePR2: `torso` (pr2_torso: torso_lift_joint, 0 ..
    0.31 m), `head` (pr2_head: head_pan_joint, head_tilt_joint), `l_arm` and `r_arm` (pr2_l_arm, pr2_r_arm:
    seven joints each), each with an armature_pose `pose`; the head and the arms ride on the torso lift.
    `joint_state` (pr2_joint_state) gives the PR2's 45 joints by their ROS names, `posture` (pr2_posture) the
    armatures' joints by their short names. `add_interface('socket')` streams the two and serves the
    armatures' services. The body is an omnidirectional base (0.65 m square) and a tower, one rigid body of
    136 kg, its origin on the floor."""

    short_descr = "Willow Garage PR2: base, torso lift, head and two arms (armatures)"
    builder_name = "BasePR2"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.0

    # MORSE's BasePR2.__init__: the torso 0.790675 m up (0.739675 m above base_link, itself 0.051 m up) and
    # 0.05 m back; on it, the head 0.38145 m up and the shoulders 0.188 m on each side (the PR2's URDF)
    default_components = (
        _armature("torso", "pr2_torso", [-0.05, 0.0, 0.790675]),
        _armature("head", "pr2_head", [-0.01707, 0.0, 0.38145]),
        _armature("l_arm", "pr2_l_arm", [0.0, 0.188, 0.0]),
        _armature("r_arm", "pr2_r_arm", [0.0, -0.188, 0.0]),
        {"name": "joint_state", "type": "pr2_joint_state"},
        {"name": "posture", "type": "pr2_posture"},
    )
    # the head and the arms ride on the torso lift: {component: (component, body of its model)}
    component_mounts: ClassVar[dict[str, tuple[str, str]]] = {
        "head": ("torso", "torso_lift_link"),
        "l_arm": ("torso", "torso_lift_link"),
        "r_arm": ("torso", "torso_lift_link"),
    }
    # what the builder's add_interface(middleware) (and add_stream) does on a BasePR2, as MORSE's. ROS: the
    # real PR2's interfaces (/joint_states, /torso_controller ... as PR2 software expects them), each also in
    # the robot's namespace (/pr2/joint_states ...: MORSE's /robot/component naming, and two PR2s apart)
    builder_interface: ClassVar[dict[str, dict[str, tuple]]] = {
        "*": {"streams": ("joint_state", "posture"), "services": ("torso", "head", "l_arm", "r_arm")},
        "ros": {
            "streams": tuple(
                (component, {"method": f"morse.middleware.ros.{method}", "topic": prefix + topic})
                for prefix in ("", "/{robot}")
                for component, method, topic in (
                    ("joint_state", "jointstate.JointStatePR2Publisher", "/joint_states"),
                    *((f"{part}_pose", "jointtrajectorycontrollers.JointTrajectoryControllerStatePublisher",
                       f"/{controller}/state") for part, controller in _CONTROLLERS))),
            "overlays": tuple(
                (part, "morse.middleware.ros.overlays.armatures.ArmatureController",
                 {"namespace": f"{prefix}/{controller}"})
                for prefix in ("", "/{robot}") for part, controller in _CONTROLLERS),
        },
    }

    # what MORSE's LocalizedPR2 and NavPR2 (robots localized_pr2, nav_pr2) append to move the base: the
    # holonomic motion, applied as a displacement every tick (MORSE's ControlType Position there: the
    # keyboard's displacement and the motion's add up), and a keyboard; and their builder's arguments
    drive_components: ClassVar[tuple[dict, ...]] = (
        {"name": "motion", "type": "motion_xyw", "properties": {"ControlType": "Position"}},
        {"name": "keyboard", "type": "keyboard"},
    )
    drive_builder: ClassVar[type] = DrivenPR2Builder

    class Properties(RobotProperties):
        GroundRobot: bool = True


COMPONENT = BasePR2
