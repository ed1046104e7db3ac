"""MORSE's NavPR2: BasePR2 with what 2D navigation needs (odometry, a base laser, a holonomic base)."""

from typing import ClassVar

from morsec.component.catalogue import component_class

BasePR2 = component_class("robots", "pr2")

# MORSE's NavPR2: a Hokuyo 0.275 m ahead of the origin, 0.252 m up (the PR2's base_laser_link), 30 m range,
# one ray a degree over 180 degrees
BASE_SCAN = {"name": "base_scan", "type": "hokuyo", "translate": [0.275, 0.0, 0.252],
             "properties": {"laser_range": 30.0, "resolution": 1.0, "scan_window": 180.0}}


class NavPR2(BasePR2):
    """Willow Garage's PR2 as MORSE's NavPR2 equipped it for 2D navigation: BasePR2 (torso, head and arms as
    armatures, `joint_state`, `posture`) with `motion` (motion_xyw: forward, sideways and turn speeds, applied
    as a displacement every tick, MORSE's ControlType Position), `keyboard` (drive it from the viewer's keys;
    headless it warns once and does nothing), `odometry` (integrated) and `base_scan`, a Hokuyo 0.275 m ahead
    of the origin and 0.252 m up scanning 181 rays, one a degree from right (-90 deg) to left, up to 30 m.
    `add_interface('ros')` adds to BasePR2's the laser on `/scan` (sensor_msgs/LaserScan), the odometry on
    `/odom` (nav_msgs/Odometry and the transform `/odom` -> `/base_footprint`) and the motion on `/cmd_vel`
    (geometry_msgs/Twist), the topics ROS's navigation stack expects; `add_interface('socket')` gives BasePR2's
    alone, as MORSE's."""

    short_descr = "PR2 for 2D navigation: base laser, odometry, holonomic base (/scan, /odom, /cmd_vel on ROS)"
    builder_name = "NavPR2"
    builder_mixin = BasePR2.drive_builder
    default_components = (*BasePR2.default_components, *BasePR2.drive_components,
                          {"name": "odometry", "type": "odometry"}, BASE_SCAN)
    builder_interface: ClassVar[dict[str, dict[str, tuple]]] = {
        "*": BasePR2.builder_interface["*"],
        "ros": {**BasePR2.builder_interface["ros"],
                "streams": (*BasePR2.builder_interface["ros"]["streams"],
                            ("base_scan", {"topic": "/scan"}),
                            ("odometry", {"topic": "/odom"}),
                            ("motion", {"topic": "/cmd_vel"}))},
    }


COMPONENT = NavPR2
