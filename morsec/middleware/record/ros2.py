"""A stream's data -> its ROS 2 messages, one converter per ROS serialiser (`ros.serialisers.SERIALISERS`),
as the ROS middleware's `conversions` build the ROS 1 ones: the same fields, stamps (the data's simulated
time) and frames, with ROS 2's differences (no header seq; builtin_interfaces/Time; CameraInfo's d, k, r, p;
frame ids without the leading '/', which tf2 refuses). Messages are rosbags' classes of the typestore the
writer passes, serialised to CDR by it. Runs in the writer process."""

from __future__ import annotations

import base64
import math
from typing import Any

import numpy as np

from morsec.kits.geometry import euler_to_quat


def frame(name: str | None) -> str:
    return (name or "").lstrip("/")


class Converter:
    """Turns one stream's data into a list of messages, one per output of `channels.ros2_outputs` (None:
    nothing on that output this time)."""

    def __init__(self, types: dict[str, Any], endpoint: dict[str, Any]):
        self.t = types  # ROS 2 type name -> rosbags message class
        self.endpoint = endpoint
        self.frame_id = frame(endpoint.get("frame_id"))
        self.child_frame_id = frame(endpoint.get("child_frame_id"))

    def convert(self, data: dict) -> list:
        raise NotImplementedError

    # ---- building blocks
    def stamp(self, seconds: float):
        nanoseconds = round(float(seconds) * 1e9)
        return self.t["builtin_interfaces/msg/Time"](sec=nanoseconds // 1_000_000_000,
                                                     nanosec=nanoseconds % 1_000_000_000)

    def header(self, data: dict, frame_id: str | None = None):
        return self.t["std_msgs/msg/Header"](stamp=self.stamp(data.get("timestamp", 0.0)),
                                             frame_id=self.frame_id if frame_id is None else frame_id)

    def vector(self, x=0.0, y=0.0, z=0.0):
        return self.t["geometry_msgs/msg/Vector3"](x=float(x), y=float(y), z=float(z))

    def quaternion(self, data: dict):
        w, x, y, z = euler_to_quat(float(data.get("roll", 0.0)), float(data.get("pitch", 0.0)),
                                   float(data.get("yaw", 0.0)))
        return self.t["geometry_msgs/msg/Quaternion"](x=float(x), y=float(y), z=float(z), w=float(w))

    def pose(self, data: dict):
        point = self.t["geometry_msgs/msg/Point"](x=float(data["x"]), y=float(data["y"]), z=float(data["z"]))
        return self.t["geometry_msgs/msg/Pose"](position=point, orientation=self.quaternion(data))

    def transform(self, stamp, parent: str, child: str, translation, rotation):
        t = self.t
        return t["tf2_msgs/msg/TFMessage"](transforms=[t["geometry_msgs/msg/TransformStamped"](
            header=t["std_msgs/msg/Header"](stamp=stamp, frame_id=parent), child_frame_id=child,
            transform=t["geometry_msgs/msg/Transform"](translation=translation, rotation=rotation))])

    def pose_transform(self, data: dict, parent: str, child: str):
        return self.transform(self.stamp(data.get("timestamp", 0.0)), parent, child,
                              self.vector(data["x"], data["y"], data["z"]), self.quaternion(data))


class PoseStamped(Converter):
    def convert(self, data):
        return [self.t["geometry_msgs/msg/PoseStamped"](header=self.header(data), pose=self.pose(data))]


class Pose(Converter):
    def convert(self, data):
        return [self.pose(data)]


class PoseWithCovariance(Converter):
    def convert(self, data):
        t = self.t
        inner = t["geometry_msgs/msg/PoseWithCovariance"](pose=self.pose(data), covariance=np.zeros(36))
        return [t["geometry_msgs/msg/PoseWithCovarianceStamped"](header=self.header(data), pose=inner)]


class PoseTf(Converter):
    def convert(self, data):
        return [self.pose_transform(data, self.frame_id, self.child_frame_id or "base_link")]


class StaticTf(Converter):
    """The component's place on its robot, parent_frame_id -> frame_id, once a simulated second, stamped a
    second ahead (the ROS middleware's StaticTFPublisher)."""

    def __init__(self, types, endpoint):
        super().__init__(types, endpoint)
        self.last = -math.inf

    def due(self, data) -> bool:
        if float(data["timestamp"]) > self.last + 1.0:
            self.last = float(data["timestamp"])
            return True
        return False

    def message(self, data):
        (x, y, z), (roll, pitch, yaw) = self.endpoint["placement"]
        return self.transform(self.stamp(float(data["timestamp"]) + 1.0), frame(self.endpoint["parent_frame_id"]),
                              self.child_frame_id or self.frame_id, self.vector(x, y, z),
                              self.quaternion({"roll": roll, "pitch": pitch, "yaw": yaw}))

    def convert(self, data):
        return [self.message(data) if self.due(data) else None]


class StaticTf2(StaticTf):
    """The same transform once, on /tf_static."""

    def due(self, data) -> bool:
        first = self.last == -math.inf
        self.last = 0.0
        return first


class Odometry(Converter):
    def convert(self, data):
        t = self.t
        twist = t["geometry_msgs/msg/Twist"](linear=self.vector(data.get("vx", 0.0), data.get("vy", 0.0),
                                                                data.get("vz", 0.0)),
                                             angular=self.vector(data.get("wx", 0.0), data.get("wy", 0.0),
                                                                 data.get("wz", 0.0)))
        msg = t["nav_msgs/msg/Odometry"](
            header=self.header(data), child_frame_id=self.child_frame_id,
            pose=t["geometry_msgs/msg/PoseWithCovariance"](pose=self.pose(data), covariance=np.zeros(36)),
            twist=t["geometry_msgs/msg/TwistWithCovariance"](twist=twist, covariance=np.zeros(36)))
        return [msg, self.pose_transform(data, self.frame_id, self.child_frame_id)]


class JointState(Converter):
    def convert(self, data):
        names = [k for k in data if k != "timestamp"]
        return [joint_state(self.t, self.header(data), names, [float(data[k]) for k in names])]


class LaserScan(Converter):
    """The ranges from -scan_window/2 to +scan_window/2 (MORSE's)."""

    def convert(self, data):
        g = self.endpoint.get("geometry", {})
        window = math.radians(float(g.get("scan_window", 180.0)))
        ranges = np.asarray(data["range_list"], dtype=np.float32)
        increment = math.radians(float(g.get("resolution", 1.0)))
        return [self.t["sensor_msgs/msg/LaserScan"](
            header=self.header(data), angle_min=-window / 2, angle_max=-window / 2 + increment * max(len(ranges) - 1, 0),
            angle_increment=increment, time_increment=0.0, scan_time=0.0, range_min=0.0,
            range_max=float(g.get("laser_range", 30.0)), ranges=ranges,
            intensities=np.asarray(data.get("remission_list") or [], dtype=np.float32))]


class Imu(Converter):
    def convert(self, data):
        t = self.t
        orientation = t["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0)
        covariance = np.zeros(9)
        if "orientation" in data:
            q = data["orientation"]
            x, y, z, w = (q["x"], q["y"], q["z"], q["w"]) if isinstance(q, dict) else q
            orientation = t["geometry_msgs/msg/Quaternion"](x=float(x), y=float(y), z=float(z), w=float(w))
        else:
            covariance[0] = -1.0  # ROS: no orientation estimate
        return [t["sensor_msgs/msg/Imu"](
            header=self.header(data), orientation=orientation, orientation_covariance=covariance,
            angular_velocity=self.vector(*data["angular_velocity"]), angular_velocity_covariance=np.zeros(9),
            linear_acceleration=self.vector(*data["linear_acceleration"]), linear_acceleration_covariance=np.zeros(9))]


class NavSatFix(Converter):
    def convert(self, data):
        t = self.t
        status = t["sensor_msgs/msg/NavSatStatus"](status=0, service=1)  # STATUS_FIX, SERVICE_GPS
        return [t["sensor_msgs/msg/NavSatFix"](header=self.header(data), status=status,
                                               latitude=float(data["latitude"]), longitude=float(data["longitude"]),
                                               altitude=float(data["altitude"]), position_covariance=np.zeros(9),
                                               position_covariance_type=0)]


class TwistStamped(Converter):
    def convert(self, data):
        twist = self.t["geometry_msgs/msg/Twist"](linear=self.vector(*data["linear_velocity"]),
                                                  angular=self.vector(*data["angular_velocity"]))
        return [self.t["geometry_msgs/msg/TwistStamped"](header=self.header(data), twist=twist)]


class Clock(Converter):
    def convert(self, data):
        return [self.t["rosgraph_msgs/msg/Clock"](clock=self.stamp(data.get("timestamp", 0.0)))]


class Image(Converter):
    """rgba8 pixels on <topic>/image and the camera's CameraInfo on <topic>/camera_info."""

    def convert(self, data):
        image = data.get("image")
        if image is None:
            return [None, None]
        t = self.t
        header = self.header(data)
        width, height = int(data["width"]), int(data["height"])
        pixels = base64.b64decode(image) if isinstance(image, str) else bytes(image)
        k = [float(v) for row in data["intrinsic_matrix"] for v in row]
        p = [k[0], k[1], k[2], 0.0, k[3], k[4], k[5], 0.0, k[6], k[7], k[8], 0.0]
        roi = t["sensor_msgs/msg/RegionOfInterest"](x_offset=0, y_offset=0, height=0, width=0, do_rectify=False)
        return [t["sensor_msgs/msg/Image"](header=header, height=height, width=width, encoding="rgba8",
                                           is_bigendian=0, step=width * 4, data=np.frombuffer(pixels, dtype=np.uint8)),
                t["sensor_msgs/msg/CameraInfo"](header=header, height=height, width=width, distortion_model="plumb_bob",
                                                d=np.zeros(5), k=np.array(k), r=np.eye(3).ravel(), p=np.array(p),
                                                binning_x=0, binning_y=0, roi=roi)]


class PointCloud2(Converter):
    """x, y, z float32 in the camera's optical frame."""

    def convert(self, data):
        t = self.t
        points = data["points"]
        raw = base64.b64decode(points) if isinstance(points, str) else bytes(memoryview(points))
        count = len(raw) // 12
        fields = [t["sensor_msgs/msg/PointField"](name=n, offset=4 * i, datatype=7, count=1)  # FLOAT32
                  for i, n in enumerate("xyz")]
        return [t["sensor_msgs/msg/PointCloud2"](header=self.header(data), height=1, width=count, fields=fields,
                                                 is_bigendian=False, point_step=12, row_step=12 * count,
                                                 data=np.frombuffer(raw[:12 * count], dtype=np.uint8), is_dense=False)]


# ---- actuators: the command an actuator took, as the ROS message the ROS middleware would have read it from

class TwistIn(Converter):
    def convert(self, data):
        return [self.t["geometry_msgs/msg/Twist"](linear=self.vector(data.get("v", 0.0)),
                                                  angular=self.vector(0.0, 0.0, data.get("w", 0.0)))]


class TwistXywIn(Converter):
    def convert(self, data):
        return [self.t["geometry_msgs/msg/Twist"](linear=self.vector(data.get("x", 0.0), data.get("y", 0.0)),
                                                  angular=self.vector(0.0, 0.0, data.get("w", 0.0)))]


class PoseIn(Converter):
    def convert(self, data):
        return [self.pose({"x": 0.0, "y": 0.0, "z": 0.0, **data})]


class PointIn(Converter):
    def convert(self, data):
        return [self.t["geometry_msgs/msg/Point"](x=float(data.get("x", 0.0)), y=float(data.get("y", 0.0)),
                                                  z=float(data.get("z", 0.0)))]


class JointStateIn(Converter):
    def convert(self, data):
        names = list(data)
        header = self.t["std_msgs/msg/Header"](stamp=self.stamp(0.0), frame_id="")
        return [joint_state(self.t, header, names, [float(data[k]) for k in names])]


def joint_state(t, header, names: list[str], positions: list[float]):
    return t["sensor_msgs/msg/JointState"](header=header, name=names, position=np.array(positions, dtype=np.float64),
                                           velocity=np.zeros(0), effort=np.zeros(0))


CONVERTERS: dict[str, type[Converter]] = {
    "pose_stamped": PoseStamped, "pose": Pose, "pose_with_covariance": PoseWithCovariance, "pose_tf": PoseTf,
    "static_tf": StaticTf, "static_tf2": StaticTf2, "odometry": Odometry, "joint_state": JointState,
    "laser_scan": LaserScan, "imu": Imu, "nav_sat_fix": NavSatFix, "twist_stamped": TwistStamped, "clock": Clock,
    "image": Image, "point_cloud2": PointCloud2,
    "twist": TwistIn, "twist_xyw": TwistXywIn, "pose_in": PoseIn, "point_in": PointIn, "joint_state_in": JointStateIn,
}


def converter(serialiser: str, types: dict[str, Any], endpoint: dict[str, Any]) -> Converter:
    return CONVERTERS[serialiser](types, endpoint)
