"""The ROS serialisers morsec has, by name: the message each one sends or reads, the component types it is
the default of (MORSE's), the class paths MORSE scripts name it by (`add_stream('ros',
'morse.middleware.ros.pose.PoseStampedPublisher')`), and its default frame. A table only: the code that
builds and reads the messages is in `conversions` (imported at run time, with rospy).

MORSE's naming: a stream's topic is its component's name with '/' for '.' (`robot.pose` -> `/robot/pose`,
`robot.001` -> `/robot001`); its frame_id is the topic, unless the serialiser has a frame of its own
(`/map` for poses, `/odom` for odometry)."""

from __future__ import annotations

import re
from dataclasses import dataclass

MORSE = "morse.middleware.ros."


@dataclass(frozen=True)
class Serialiser:
    name: str
    direction: str  # OUT: a sensor's data published; IN: an actuator's data read
    message: str  # the ROS message type
    defaults_for: tuple[str, ...] = ()  # catalogue types it is the default serialiser of
    morse: tuple[str, ...] = ()  # MORSE's class paths for it (without the morse.middleware.ros. prefix)
    frame_id: str | None = None  # None: the topic name (MORSE's convention)
    child_frame_id: str | None = None  # odometry, tf: the moving frame
    tf: bool = False  # also broadcasts a transform on /tf


SERIALISERS = {s.name: s for s in (
    Serialiser("pose_stamped", "OUT", "geometry_msgs/PoseStamped", ("pose",),
               ("pose.PoseStampedPublisher",), frame_id="/map"),
    Serialiser("pose", "OUT", "geometry_msgs/Pose", (), ("pose.PosePublisher",)),
    Serialiser("pose_with_covariance", "OUT", "geometry_msgs/PoseWithCovarianceStamped", (),
               ("pose.PoseWithCovarianceStampedPublisher",), frame_id="/map"),
    Serialiser("pose_tf", "OUT", "tf2_msgs/TFMessage", (), ("pose.TFPublisher",), frame_id="/map",
               child_frame_id="/base_link", tf=True),
    Serialiser("static_tf", "OUT", "tf2_msgs/TFMessage", (), ("static_tf.StaticTFPublisher",),
               child_frame_id=None, tf=True),
    Serialiser("static_tf2", "OUT", "tf2_msgs/TFMessage", (), ("static_tf.StaticTF2Publisher",), tf=True),
    Serialiser("odometry", "OUT", "nav_msgs/Odometry", ("odometry",), ("odometry.OdometryPublisher",),
               frame_id="/odom", child_frame_id="/base_footprint", tf=True),
    Serialiser("joint_state", "OUT", "sensor_msgs/JointState",
               ("armature_pose", "pr2_joint_state", "pr2_posture", "ptu_posture"),
               ("jointstate.JointStatePublisher", "jointstate.JointStatePR2Publisher")),
    Serialiser("joint_trajectory_controller_state", "OUT", "control_msgs/JointTrajectoryControllerState", (),
               ("jointtrajectorycontrollers.JointTrajectoryControllerStatePublisher",)),
    Serialiser("laser_scan", "OUT", "sensor_msgs/LaserScan", ("laser_scanner",),
               ("laserscanner.LaserScanPublisher", "sick.LaserScanPublisher")),
    Serialiser("imu", "OUT", "sensor_msgs/Imu", ("imu",), ("imu.ImuPublisher",), frame_id="/imu"),
    Serialiser("nav_sat_fix", "OUT", "sensor_msgs/NavSatFix", ("gps",), ("gps.NavSatFixPublisher",),
               frame_id="/gps"),
    Serialiser("twist_stamped", "OUT", "geometry_msgs/TwistStamped", ("velocity",),
               ("velocity.TwistStampedPublisher",)),
    Serialiser("clock", "OUT", "rosgraph_msgs/Clock", ("clock",), ("clock.ClockPublisher",)),
    Serialiser("image", "OUT", "sensor_msgs/Image", ("video_camera",), ("video_camera.VideoCameraPublisher",)),
    Serialiser("point_cloud2", "OUT", "sensor_msgs/PointCloud2", ("depth_camera",),
               ("depth_camera.DepthCameraPublisher", "point_cloud2.PointCloud2Publisher")),
    Serialiser("twist", "IN", "geometry_msgs/Twist", ("motion_vw", "motion_vw_diff"),
               ("motion_vw.TwistReader", "read_vw_twist.TwistReader", "read_twist.TwistReader")),
    Serialiser("twist_xyw", "IN", "geometry_msgs/Twist", ("motion_xyw",),
               ("motion_xyw.TwistReader", "read_xyw_twist.TwistReader")),
    Serialiser("pose_in", "IN", "geometry_msgs/Pose", ("teleport",), ("read_pose.PoseReader",)),
    Serialiser("point_in", "IN", "geometry_msgs/Point", ("destination",), ("destination.PointReader",)),
    Serialiser("joint_state_in", "IN", "sensor_msgs/JointState", ("armature",),
               ("read_jointState.JointStateReader", "jointpositions.JointPositionsReader")),
)}

_BY_MORSE = {MORSE + path: s.name for s in SERIALISERS.values() for path in s.morse}


def serialiser_for(types: tuple[str, ...], direction: str, named: str | None) -> Serialiser:
    """The serialiser of a stream: the one a script named (MORSE's class path, or morsec's name), else the
    default of the component's type (or of the types it derives from); ValueError saying why there is none."""
    if named:
        key = _BY_MORSE.get(named, named if named in SERIALISERS else None)
        if key is None:
            from morsec.errors import did_you_mean
            raise ValueError(f"no ROS serialiser {named!r}{did_you_mean(named, [*_BY_MORSE, *SERIALISERS])} "
                             "(docs/ros.md lists them)")
        chosen = SERIALISERS[key]
        if chosen.direction != direction:
            raise ValueError(f"ROS serialiser {named!r} {'publishes' if chosen.direction == 'OUT' else 'reads'} "
                             f"a {chosen.message}: it does not fit a stream whose direction is {direction}")
        return chosen
    for type_id in types:
        for serialiser in SERIALISERS.values():
            if type_id in serialiser.defaults_for and serialiser.direction == direction:
                return serialiser
    kinds = sorted({t for s in SERIALISERS.values() if s.direction == direction for t in s.defaults_for})
    raise ValueError(f"morsec has no ROS message for {types[0] if types else 'this component'} streams "
                     f"({'out' if direction == 'OUT' else 'in'}): ROS streams {'from' if direction == 'OUT' else 'to'} "
                     f"{', '.join(kinds)}, or name a serialiser (add_stream('ros', '<class path>'))")


def default_topic(component: str) -> str:
    """MORSE's topic of a component: `robot.pose` -> `/robot/pose`, `robot.001.pose` -> `/robot001/pose`."""
    return "/" + re.sub(r"\.([0-9]+)", r"\1", component).replace(".", "/")
