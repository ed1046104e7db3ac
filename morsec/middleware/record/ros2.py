"""A stream's data -> its ROS 2 messages in CDR, one converter per ROS serialiser (`ros.serialisers.SERIALISERS`),
as the ROS middleware's `conversions` build the ROS 1 ones: the same fields, stamps (the data's simulated
time) and frames, with ROS 2's differences (no header seq; builtin_interfaces/Time; CameraInfo's d, k, r, p;
frame ids without the leading '/', which tf2 refuses). Messages of a fixed layout are packed by `cdr`; those
of variable size are rosbags" message classes serialised by its typestore. Runs in the writer process."""

from __future__ import annotations

import base64
import math
from typing import Any

import numpy as np

from morsec.kits.geometry import euler_to_quat_tuple
from morsec.middleware.record.cdr import ENCAPSULATION, Layout

ZEROS = (0.0,) * 36


def frame(name: str | None) -> str:
    return (name or "").lstrip("/")


def stamp(seconds: float) -> tuple[int, int]:
    """builtin_interfaces/Time (sec, nanosec) of a time in seconds."""
    nanoseconds = round(float(seconds) * 1e9)
    return nanoseconds // 1_000_000_000, nanoseconds % 1_000_000_000


def quaternion(data: dict) -> tuple[float, float, float, float]:
    """(x, y, z, w), ROS's order, of the data's roll, pitch, yaw."""
    w, x, y, z = euler_to_quat_tuple(float(data.get("roll", 0.0)), float(data.get("pitch", 0.0)),
                                     float(data.get("yaw", 0.0)))
    return x, y, z, w


def pose(data: dict) -> tuple[float, ...]:
    """geometry_msgs/Pose's seven numbers: position, then orientation (x, y, z, w)."""
    return (float(data["x"]), float(data["y"]), float(data["z"]), *quaternion(data))


class Converter:
    """Turns one stream's data into a list of CDR messages, one per output of `channels.ros2_outputs` (None:
    nothing on that output this time)."""

    needs: tuple[str, ...] = ()  # the fields its data must have (a component's level may lack them)

    def __init__(self, store: Any, endpoint: dict[str, Any]):
        self.store = store  # rosbags" typestore: message classes (store.types) and their serialiser
        self.endpoint = endpoint
        self.frame_id = frame(endpoint.get("frame_id"))
        self.child_frame_id = frame(endpoint.get("child_frame_id"))

    def convert(self, data: dict) -> list[bytes | None]:
        raise NotImplementedError

    def serialise(self, message) -> bytes:
        return bytes(self.store.serialize_cdr(message, message.__msgtype__))

    def header(self, data: dict):
        sec, nanosec = stamp(data.get("timestamp", 0.0))
        t = self.store.types
        return t["std_msgs/msg/Header"](stamp=t["builtin_interfaces/msg/Time"](sec=sec, nanosec=nanosec),
                                        frame_id=self.frame_id)


def transform_layout(parent: str, child: str):
    """tf2_msgs/TFMessage holding one geometry_msgs/TransformStamped: (pack, parent's values, child's)."""
    layout = Layout().add("I")  # the sequence's length
    parent_values = layout.header(parent)
    child_values = layout.string(child)
    layout.add("d", 7)  # translation, rotation
    return layout.struct().pack, parent_values, child_values


class PoseStamped(Converter):
    needs = ("x", "y", "z")

    def __init__(self, store, endpoint):
        super().__init__(store, endpoint)
        layout = Layout()
        self.frame = layout.header(self.frame_id)
        self.pack = layout.add("d", 7).struct().pack

    def convert(self, data):
        return [ENCAPSULATION + self.pack(*stamp(data["timestamp"]), *self.frame, *pose(data))]


class Pose(Converter):
    needs = ("x", "y", "z")

    pack = Layout().add("d", 7).struct().pack

    def convert(self, data):
        return [ENCAPSULATION + self.pack(*pose(data))]


class PoseWithCovariance(Converter):
    needs = ("x", "y", "z")

    def __init__(self, store, endpoint):
        super().__init__(store, endpoint)
        layout = Layout()
        self.frame = layout.header(self.frame_id)
        self.pack = layout.add("d", 7 + 36).struct().pack

    def convert(self, data):
        return [ENCAPSULATION + self.pack(*stamp(data["timestamp"]), *self.frame, *pose(data), *ZEROS)]


class PoseTf(Converter):
    needs = ("x", "y", "z")

    def __init__(self, store, endpoint):
        super().__init__(store, endpoint)
        self.pack, self.parent, self.child = transform_layout(self.frame_id, self.child_frame_id or "base_link")

    def convert(self, data):
        return [ENCAPSULATION + self.pack(1, *stamp(data["timestamp"]), *self.parent, *self.child, *pose(data))]


class StaticTf(Converter):
    """The component's place on its robot, parent_frame_id -> frame_id, once a simulated second, stamped a
    second ahead (the ROS middleware's StaticTFPublisher)."""

    def __init__(self, store, endpoint):
        super().__init__(store, endpoint)
        self.last = -math.inf
        self.pack, self.parent, self.child = transform_layout(frame(endpoint["parent_frame_id"]),
                                                              self.child_frame_id or self.frame_id)
        (x, y, z), (roll, pitch, yaw) = endpoint["placement"]
        self.placement = pose({"x": x, "y": y, "z": z, "roll": roll, "pitch": pitch, "yaw": yaw})

    def due(self, data) -> bool:
        if float(data["timestamp"]) > self.last + 1.0:
            self.last = float(data["timestamp"])
            return True
        return False

    def convert(self, data):
        if not self.due(data):
            return [None]
        return [ENCAPSULATION + self.pack(1, *stamp(float(data["timestamp"]) + 1.0), *self.parent, *self.child,
                                          *self.placement)]


class StaticTf2(StaticTf):
    """The same transform once, on /tf_static."""

    def due(self, data) -> bool:
        first = self.last == -math.inf
        self.last = 0.0
        return first


class Odometry(Converter):
    """nav_msgs/Odometry in frame_id of child_frame_id, and that transform on /tf."""

    needs = ("x", "y", "z")

    def __init__(self, store, endpoint):
        super().__init__(store, endpoint)
        layout = Layout()
        self.frame = layout.header(self.frame_id)
        self.child = layout.string(self.child_frame_id)
        self.pack = layout.add("d", 7 + 36 + 6 + 36).struct().pack  # pose, its covariance, twist, its covariance
        self.pack_tf, self.tf_parent, self.tf_child = transform_layout(self.frame_id, self.child_frame_id)

    def convert(self, data):
        time = stamp(data["timestamp"])
        where = pose(data)
        g = data.get
        twist = (g("vx", 0.0), g("vy", 0.0), g("vz", 0.0), g("wx", 0.0), g("wy", 0.0), g("wz", 0.0))
        return [ENCAPSULATION + self.pack(*time, *self.frame, *self.child, *where, *ZEROS, *twist, *ZEROS),
                ENCAPSULATION + self.pack_tf(1, *time, *self.tf_parent, *self.tf_child, *where)]


class Imu(Converter):
    needs = ("angular_velocity", "linear_acceleration")

    def __init__(self, store, endpoint):
        super().__init__(store, endpoint)
        layout = Layout()
        self.frame = layout.header(self.frame_id)
        # orientation, its covariance, angular velocity, its covariance, linear acceleration, its covariance
        self.pack = layout.add("d", 4 + 9 + 3 + 9 + 3 + 9).struct().pack

    def convert(self, data):
        covariance = ZEROS[:9]
        if "orientation" in data:
            q = data["orientation"]
            orientation = (q["x"], q["y"], q["z"], q["w"]) if isinstance(q, dict) else tuple(q)
        else:
            orientation, covariance = (0.0, 0.0, 0.0, 1.0), (-1.0, *ZEROS[:8])  # ROS: no orientation estimate
        return [ENCAPSULATION + self.pack(*stamp(data["timestamp"]), *self.frame, *orientation, *covariance,
                                          *data["angular_velocity"], *ZEROS[:9], *data["linear_acceleration"],
                                          *ZEROS[:9])]


class NavSatFix(Converter):
    needs = ("latitude", "longitude", "altitude")

    def __init__(self, store, endpoint):
        super().__init__(store, endpoint)
        layout = Layout()
        self.frame = layout.header(self.frame_id)
        # NavSatStatus (int8 status, uint16 service), latitude, longitude, altitude, the position's covariance
        # and its type
        self.pack = layout.add("b").add("H").add("d", 3 + 9).add("B").struct().pack

    def convert(self, data):
        return [ENCAPSULATION + self.pack(*stamp(data["timestamp"]), *self.frame, 0, 1,  # STATUS_FIX, SERVICE_GPS
                                          data["latitude"], data["longitude"], data["altitude"], *ZEROS[:9], 0)]


class TwistStamped(Converter):
    needs = ("linear_velocity", "angular_velocity")

    def __init__(self, store, endpoint):
        super().__init__(store, endpoint)
        layout = Layout()
        self.frame = layout.header(self.frame_id)
        self.pack = layout.add("d", 6).struct().pack

    def convert(self, data):
        return [ENCAPSULATION + self.pack(*stamp(data["timestamp"]), *self.frame, *data["linear_velocity"],
                                          *data["angular_velocity"])]


class Clock(Converter):
    pack = Layout().add("i").add("I").struct().pack

    def convert(self, data):
        return [ENCAPSULATION + self.pack(*stamp(data["timestamp"]))]


class LaserScan(Converter):
    """The ranges from -scan_window/2 to +scan_window/2 (MORSE's)."""

    needs = ("range_list",)

    def convert(self, data):
        g = self.endpoint.get("geometry", {})
        window = math.radians(float(g.get("scan_window", 180.0)))
        ranges = np.asarray(data["range_list"], dtype=np.float32)
        increment = math.radians(float(g.get("resolution", 1.0)))
        last = -window / 2 + increment * max(len(ranges) - 1, 0)
        return [self.serialise(self.store.types["sensor_msgs/msg/LaserScan"](
            header=self.header(data), angle_min=-window / 2, angle_max=last, angle_increment=increment,
            time_increment=0.0, scan_time=0.0, range_min=0.0,
            range_max=float(g.get("laser_range", 30.0)), ranges=ranges,
            intensities=np.asarray(data.get("remission_list") or [], dtype=np.float32)))]


class JointState(Converter):
    def convert(self, data):
        names = [k for k in data if k != "timestamp"]
        return [self.serialise(joint_state(self.store.types, self.header(data), names,
                                           [float(data[k]) for k in names]))]


class Image(Converter):
    """rgba8 pixels on <topic>/image and the camera's CameraInfo on <topic>/camera_info."""

    needs = ("image", "width", "height", "intrinsic_matrix")

    def convert(self, data):
        image = data.get("image")
        if image is None:
            return [None, None]
        t = self.store.types
        header = self.header(data)
        width, height = int(data["width"]), int(data["height"])
        pixels = base64.b64decode(image) if isinstance(image, str) else bytes(image)
        k = [float(v) for row in data["intrinsic_matrix"] for v in row]
        p = [k[0], k[1], k[2], 0.0, k[3], k[4], k[5], 0.0, k[6], k[7], k[8], 0.0]
        roi = t["sensor_msgs/msg/RegionOfInterest"](x_offset=0, y_offset=0, height=0, width=0, do_rectify=False)
        return [self.serialise(t["sensor_msgs/msg/Image"](
                    header=header, height=height, width=width, encoding="rgba8", is_bigendian=0, step=width * 4,
                    data=np.frombuffer(pixels, dtype=np.uint8))),
                self.serialise(t["sensor_msgs/msg/CameraInfo"](
                    header=header, height=height, width=width, distortion_model="plumb_bob", d=np.zeros(5),
                    k=np.array(k), r=np.eye(3).ravel(), p=np.array(p), binning_x=0, binning_y=0, roi=roi))]


class PointCloud2(Converter):
    """x, y, z float32 in the camera's optical frame."""

    needs = ("points",)

    def convert(self, data):
        t = self.store.types
        points = data["points"]
        raw = base64.b64decode(points) if isinstance(points, str) else bytes(memoryview(points))
        count = len(raw) // 12
        fields = [t["sensor_msgs/msg/PointField"](name=n, offset=4 * i, datatype=7, count=1)  # FLOAT32
                  for i, n in enumerate("xyz")]
        return [self.serialise(t["sensor_msgs/msg/PointCloud2"](
            header=self.header(data), height=1, width=count, fields=fields, is_bigendian=False, point_step=12,
            row_step=12 * count, data=np.frombuffer(raw[:12 * count], dtype=np.uint8), is_dense=False))]


# ---- actuators: the command an actuator took, as the ROS message the ROS middleware would have read it from

class TwistIn(Converter):
    pack = Layout().add("d", 6).struct().pack

    def convert(self, data):
        return [ENCAPSULATION + self.pack(data.get("v", 0.0), 0.0, 0.0, 0.0, 0.0, data.get("w", 0.0))]


class TwistXywIn(TwistIn):
    def convert(self, data):
        return [ENCAPSULATION + self.pack(data.get("x", 0.0), data.get("y", 0.0), 0.0, 0.0, 0.0, data.get("w", 0.0))]


class PoseIn(Pose):
    def convert(self, data):
        return super().convert({"x": 0.0, "y": 0.0, "z": 0.0, **data})


class PointIn(Converter):
    pack = Layout().add("d", 3).struct().pack

    def convert(self, data):
        return [ENCAPSULATION + self.pack(data.get("x", 0.0), data.get("y", 0.0), data.get("z", 0.0))]


class JointStateIn(Converter):
    def convert(self, data):
        names = list(data)
        header = self.header({})
        return [self.serialise(joint_state(self.store.types, header, names, [float(data[k]) for k in names]))]


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


def converter(serialiser: str, store: Any, endpoint: dict[str, Any]) -> Converter:
    return CONVERTERS[serialiser](store, endpoint)
