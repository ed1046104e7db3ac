"""The ROS streams: a sensor's data -> its ROS message (published), a ROS message -> an actuator's data
(read), one class per serialiser of `serialisers.SERIALISERS`. Messages are stamped with the simulated
time of the data (`timestamp`), as MORSE's were."""

from __future__ import annotations

import base64
import logging
import math
import threading
from typing import Any

import rospy
from geometry_msgs.msg import (
    Point,
    Pose,
    PoseStamped,
    PoseWithCovarianceStamped,
    Quaternion,
    TransformStamped,
    Twist,
    TwistStamped,
    Vector3,
)
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import (
    CameraInfo,
    Image,
    Imu,
    JointState,
    LaserScan,
    NavSatFix,
    NavSatStatus,
    PointCloud2,
    PointField,
)
from std_msgs.msg import Header
from tf2_msgs.msg import TFMessage
from trajectory_msgs.msg import JointTrajectoryPoint

from morsec.kits.geometry import euler_to_quat, matrix_to_euler, quat_to_matrix

log = logging.getLogger("morsec.middleware.ros")


class RosOut:
    """A sensor's stream: its data, converted, on a topic (and, for some, a transform on /tf)."""

    message: Any = None  # the ROS message class

    def __init__(self, node, component: str, endpoint: dict[str, Any]):
        self.node = node
        self.component = component
        self.endpoint = endpoint
        self.frame_id = endpoint["frame_id"]
        self.child_frame_id = endpoint.get("child_frame_id")
        self.seq = 0
        self.failed: set[str] = set()
        self.pub = node.publisher(endpoint["topic"], self.message) if self.message is not None else None

    @property
    def listening(self) -> bool:
        return bool((self.pub is not None and self.pub.listening) or (self.sends_tf and self.node.tf.listening))

    sends_tf = False

    def publish(self, data: dict) -> None:
        try:
            self.send(data)
        except Exception as err:  # data this serialiser cannot read (a level without its fields ...): said once
            key = f"{type(err).__name__}: {err}"
            if key not in self.failed:
                self.failed.add(key)
                log.error("%s: ROS %s stream on %s: %s", self.component, self.endpoint["serialiser"],
                          self.endpoint["topic"], key)
        self.seq += 1

    def send(self, data: dict) -> None:
        self.pub.publish(self.convert(data))

    def convert(self, data: dict):
        raise NotImplementedError

    def header(self, data: dict, frame_id: str | None = None) -> Header:
        return Header(seq=self.seq, stamp=stamp(data), frame_id=frame_id or self.frame_id)

    def transform(self, data: dict, parent: str, child: str) -> None:
        t = TransformStamped(header=Header(stamp=stamp(data), frame_id=parent), child_frame_id=child)
        t.transform.translation = Vector3(*position(data))
        t.transform.rotation = orientation(data)
        self.node.tf.publish(TFMessage(transforms=[t]))

    def close(self) -> None:
        pass


class PoseStampedOut(RosOut):
    message = PoseStamped

    def convert(self, data):
        return PoseStamped(header=self.header(data), pose=pose(data))


class PoseOut(RosOut):
    message = Pose

    def convert(self, data):
        return pose(data)


class PoseWithCovarianceOut(RosOut):
    message = PoseWithCovarianceStamped

    def convert(self, data):
        msg = PoseWithCovarianceStamped(header=self.header(data))
        msg.pose.pose = pose(data)
        return msg


class PoseTfOut(RosOut):
    """MORSE's pose.TFPublisher: the pose as the transform frame_id (/map) -> child_frame_id (/base_link)."""

    sends_tf = True

    def send(self, data):
        self.transform(data, self.frame_id, self.child_frame_id or "/base_link")


class StaticTfOut(RosOut):
    """MORSE's static_tf.StaticTFPublisher: the component's place on its robot, parent_frame_id (base_link) ->
    frame_id, on /tf once a simulated second, stamped a second ahead (as a static_transform_publisher)."""

    sends_tf = True

    def __init__(self, node, component, endpoint):
        super().__init__(node, component, endpoint)
        self.last = -math.inf

    def transform_message(self, data) -> TFMessage:
        (x, y, z), (roll, pitch, yaw) = self.endpoint["placement"]
        t = TransformStamped(header=Header(stamp=rospy.Time.from_sec(float(data["timestamp"]) + 1.0),
                                           frame_id=self.endpoint["parent_frame_id"]),
                             child_frame_id=self.child_frame_id or self.frame_id)
        t.transform.translation = Vector3(x, y, z)
        t.transform.rotation = orientation({"roll": roll, "pitch": pitch, "yaw": yaw})
        return TFMessage(transforms=[t])

    def send(self, data):
        if float(data["timestamp"]) > self.last + 1.0:
            self.last = float(data["timestamp"])
            self.node.tf.publish(self.transform_message(data))


class StaticTf2Out(StaticTfOut):
    """MORSE's static_tf.StaticTF2Publisher: the same transform, once, latched on /tf_static (tf2's way)."""

    def __init__(self, node, component, endpoint):
        super().__init__(node, component, endpoint)
        self.static = node.publisher("/tf_static", TFMessage, latch=True)
        self.sent = False

    @property
    def listening(self) -> bool:
        return not self.sent  # published once whoever listens: the latch keeps it for those who come later

    def send(self, data):
        self.static.publish(self.transform_message(data))
        self.sent = True


class OdometryOut(RosOut):
    """nav_msgs/Odometry in frame_id (/odom) of child_frame_id (/base_footprint), and that transform on /tf."""

    message = Odometry
    sends_tf = True

    def send(self, data):
        msg = Odometry(header=self.header(data), child_frame_id=self.child_frame_id)
        msg.pose.pose = pose(data)
        msg.twist.twist.linear = Vector3(data.get("vx", 0.0), data.get("vy", 0.0), data.get("vz", 0.0))
        msg.twist.twist.angular = Vector3(data.get("wx", 0.0), data.get("wy", 0.0), data.get("wz", 0.0))
        self.pub.publish(msg)
        self.transform(data, self.frame_id, self.child_frame_id)


class JointStateOut(RosOut):
    message = JointState

    def convert(self, data):
        names = [k for k in data if k != "timestamp"]
        return JointState(header=self.header(data), name=names, position=[float(data[k]) for k in names])


class JointTrajectoryControllerStateOut(RosOut):
    """control_msgs/JointTrajectoryControllerState of an armature's pose sensor: where the joints are
    (actual, and desired: morsec reports no lag), no error."""

    def __init__(self, node, component, endpoint):
        from control_msgs.msg import JointTrajectoryControllerState
        self.message = JointTrajectoryControllerState
        super().__init__(node, component, endpoint)

    def convert(self, data):
        names = [k for k in data if k != "timestamp"]
        values = [float(data[k]) for k in names]
        zeros = [0.0] * len(names)
        return self.message(header=self.header(data), joint_names=names,
                            desired=JointTrajectoryPoint(positions=values, velocities=zeros),
                            actual=JointTrajectoryPoint(positions=values, velocities=zeros),
                            error=JointTrajectoryPoint(positions=zeros, velocities=zeros))


class LaserScanOut(RosOut):
    """sensor_msgs/LaserScan: the ranges of the scan, from -scan_window/2 to +scan_window/2 (MORSE's)."""

    message = LaserScan

    def convert(self, data):
        g = self.endpoint.get("geometry", {})
        window = math.radians(float(g.get("scan_window", 180.0)))
        ranges = [float(r) for r in data["range_list"]]
        increment = math.radians(float(g.get("resolution", 1.0)))
        return LaserScan(header=self.header(data), angle_min=-window / 2,
                         angle_max=-window / 2 + increment * max(len(ranges) - 1, 0), angle_increment=increment,
                         time_increment=0.0, scan_time=0.0, range_min=0.0,
                         range_max=float(g.get("laser_range", 30.0)), ranges=ranges,
                         intensities=[float(v) for v in data.get("remission_list") or []])


class ImuOut(RosOut):
    message = Imu

    def convert(self, data):
        msg = Imu(header=self.header(data))
        msg.angular_velocity = Vector3(*data["angular_velocity"])
        msg.linear_acceleration = Vector3(*data["linear_acceleration"])
        if "orientation" in data:
            q = data["orientation"]
            msg.orientation = Quaternion(q["x"], q["y"], q["z"], q["w"]) if isinstance(q, dict) else Quaternion(*q)
        else:
            msg.orientation_covariance[0] = -1.0  # ROS: no orientation estimate
        return msg


class NavSatFixOut(RosOut):
    message = NavSatFix

    def convert(self, data):
        return NavSatFix(header=self.header(data), status=NavSatStatus(status=NavSatStatus.STATUS_FIX,
                                                                       service=NavSatStatus.SERVICE_GPS),
                         latitude=data["latitude"], longitude=data["longitude"], altitude=data["altitude"])


class TwistStampedOut(RosOut):
    message = TwistStamped

    def convert(self, data):
        msg = TwistStamped(header=self.header(data))
        msg.twist.linear = Vector3(*data["linear_velocity"])
        msg.twist.angular = Vector3(*data["angular_velocity"])
        return msg


class ClockOut(RosOut):
    message = Clock

    def convert(self, data):
        return Clock(clock=stamp(data))


class ImageOut(RosOut):
    """sensor_msgs/Image (rgba8) on <topic>/image and its CameraInfo on <topic>/camera_info (MORSE's)."""

    message = Image

    def __init__(self, node, component, endpoint):
        self.node = node
        super().__init__(node, component, {**endpoint, "topic": endpoint["topic"] + "/image"})
        self.info = node.publisher(endpoint["topic"] + "/camera_info", CameraInfo)

    @property
    def listening(self) -> bool:
        return bool(self.pub.listening or self.info.listening)

    def send(self, data):
        image = data.get("image")
        if image is None:
            return
        header = self.header(data)
        width, height = int(data["width"]), int(data["height"])
        pixels = base64.b64decode(image) if isinstance(image, str) else bytes(image)
        self.pub.publish(Image(header=header, height=height, width=width, encoding="rgba8", is_bigendian=0,
                               step=width * 4, data=pixels))
        k = [float(v) for row in data["intrinsic_matrix"] for v in row]
        p = [k[0], k[1], k[2], 0.0, k[3], k[4], k[5], 0.0, k[6], k[7], k[8], 0.0]
        self.info.publish(CameraInfo(header=header, height=height, width=width, distortion_model="plumb_bob",
                                     D=[0.0] * 5, K=k, R=[1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0], P=p))


class PointCloud2Out(RosOut):
    """sensor_msgs/PointCloud2 of a depth camera's points: x, y, z float32 in the camera's optical frame."""

    message = PointCloud2

    def convert(self, data):
        points = data["points"]
        raw = base64.b64decode(points) if isinstance(points, str) else bytes(memoryview(points))
        count = len(raw) // 12
        fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1)
                  for i, n in enumerate("xyz")]
        return PointCloud2(header=self.header(data), height=1, width=count, fields=fields, is_bigendian=False,
                           point_step=12, row_step=12 * count, data=raw, is_dense=False)


# ---- actuators

class RosIn:
    """An actuator's stream: the last message of a topic, converted to the actuator's data."""

    message: Any = None

    def __init__(self, node, component: str, endpoint: dict[str, Any]):
        self.component = component
        self.endpoint = endpoint
        self._lock = threading.Lock()
        self._latest: dict | None = None
        self.failed: set[str] = set()
        self.sub = node.subscriber(endpoint["topic"], self.message, self._received)

    def _received(self, msg) -> None:  # on a rospy thread
        try:
            data = self.convert(msg)
        except Exception as err:
            key = f"{type(err).__name__}: {err}"
            if key not in self.failed:
                self.failed.add(key)
                log.error("%s: ROS message on %s: %s", self.component, self.endpoint["topic"], key)
            return
        with self._lock:
            self._latest = data

    def take(self, frames: int) -> dict | None:
        """The last message rospy delivered, at the actuator's next tick whatever the frame (`frames` is the
        socket's frame order, docs/running.md#time): MORSE's ROS subscribers stored what came on their own
        thread and the actuator read it at its next action."""
        with self._lock:
            data, self._latest = self._latest, None
        return data

    def convert(self, msg) -> dict:
        raise NotImplementedError

    def close(self) -> None:
        pass


class TwistIn(RosIn):
    """geometry_msgs/Twist -> (v, w): forward speed linear.x, turn rate angular.z."""

    message = Twist

    def convert(self, msg):
        return {"v": msg.linear.x, "w": msg.angular.z}


class TwistXywIn(RosIn):
    message = Twist

    def convert(self, msg):
        return {"x": msg.linear.x, "y": msg.linear.y, "w": msg.angular.z}


class PoseIn(RosIn):
    message = Pose

    def convert(self, msg):
        q = msg.orientation
        roll, pitch, yaw = matrix_to_euler(quat_to_matrix([q.w, q.x, q.y, q.z]))
        return {"x": msg.position.x, "y": msg.position.y, "z": msg.position.z,
                "roll": roll, "pitch": pitch, "yaw": yaw}


class PointIn(RosIn):
    message = Point

    def convert(self, msg):
        return {"x": msg.x, "y": msg.y, "z": msg.z}


class JointStateIn(RosIn):
    message = JointState

    def convert(self, msg):
        return {name: float(value) for name, value in zip(msg.name, msg.position)}


STREAMS: dict[str, type] = {
    "pose_stamped": PoseStampedOut, "pose": PoseOut, "pose_with_covariance": PoseWithCovarianceOut,
    "pose_tf": PoseTfOut, "static_tf": StaticTfOut, "static_tf2": StaticTf2Out, "odometry": OdometryOut,
    "joint_state": JointStateOut,
    "joint_trajectory_controller_state": JointTrajectoryControllerStateOut, "laser_scan": LaserScanOut,
    "imu": ImuOut, "nav_sat_fix": NavSatFixOut, "twist_stamped": TwistStampedOut, "clock": ClockOut,
    "image": ImageOut, "point_cloud2": PointCloud2Out,
    "twist": TwistIn, "twist_xyw": TwistXywIn, "pose_in": PoseIn, "point_in": PointIn,
    "joint_state_in": JointStateIn,
}


def stream_class(serialiser: str) -> type:
    return STREAMS[serialiser]


# ---- helpers

def stamp(data: dict) -> rospy.Time:
    return rospy.Time.from_sec(float(data.get("timestamp", 0.0)))


def position(data: dict) -> tuple[float, float, float]:
    return float(data["x"]), float(data["y"]), float(data["z"])


def orientation(data: dict) -> Quaternion:
    w, x, y, z = euler_to_quat(float(data.get("roll", 0.0)), float(data.get("pitch", 0.0)),
                               float(data.get("yaw", 0.0)))
    return Quaternion(x=float(x), y=float(y), z=float(z), w=float(w))


def pose(data: dict) -> Pose:
    return Pose(position=Point(*position(data)), orientation=orientation(data))
