"""MORSE's LocalizedPR2: BasePR2 that moves its base and knows where it is."""

from typing import ClassVar

from morsec.component.catalogue import component_class

BasePR2 = component_class("robots", "pr2")


class LocalizedPR2(BasePR2):
    """Willow Garage's PR2 as MORSE's LocalizedPR2 equipped it: BasePR2 (torso, head and arms as armatures,
    `joint_state`, `posture`) with `motion` (motion_xyw: forward, sideways and turn speeds, applied as a
    displacement every tick, MORSE's ControlType Position), `keyboard` (drive it from the viewer's keys;
    headless it warns once and does nothing) and `pose` (where the robot is: on the floor under its centre).
    `add_interface('ros')` adds to BasePR2's the motion on `/cmd_vel` (geometry_msgs/Twist) and the pose as the
    transform `/map` -> `/base_link` on `/tf`; `add_interface('socket')` gives BasePR2's alone, as MORSE's."""

    short_descr = "PR2 that drives its base (motion_xyw, keyboard) and knows its pose (tf on ROS)"
    builder_name = "LocalizedPR2"
    builder_mixin = BasePR2.drive_builder
    default_components = (*BasePR2.default_components, *BasePR2.drive_components, {"name": "pose", "type": "pose"})
    builder_interface: ClassVar[dict[str, dict[str, tuple]]] = {
        "*": BasePR2.builder_interface["*"],
        "ros": {**BasePR2.builder_interface["ros"],
                "streams": (*BasePR2.builder_interface["ros"]["streams"],
                            ("motion", {"topic": "/cmd_vel"}),
                            ("pose", {"method": "morse.middleware.ros.pose.TFPublisher"}))},
    }


COMPONENT = LocalizedPR2
