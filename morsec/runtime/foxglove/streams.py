"""A component's messages as Foxglove channels, on MORSE's topic names (`robot.sick` -> `/robot/sick`), in
the component's frame (its body: `robot.sick`), stamped with the simulated time of the data:

- a laser scanner (sick, hokuyo ...): foxglove.LaserScan, from -scan_window/2 to +scan_window/2; one with
  several layers (sick_ld_mrs, velodyne_ray_cast): foxglove.PointCloud of its hit points;
- a depth camera (velodyne, vlp16 ...): foxglove.PointCloud of its points, in its optical frame (x right,
  y down, z forward) placed in the component's frame;
- a video camera: foxglove.RawImage rgba8; a depth video camera: 32FC1 (metres); a kinect: both, on
  `<topic>/rgb` and `<topic>/depth`;
- anything else (a sensor's message, the commands an actuator receives): JSON, with the component's message
  schema (`morsec schema --messages`) as its JSON Schema.

Each stream is an OutStream of the simulation (`listening`: a Foxglove client subscribed), so a sensor
builds its message only while a client looks at it."""

from __future__ import annotations

import base64
import json
import logging
import math
from typing import Any

import numpy as np
from foxglove import Channel, Context, Schema
from foxglove.channels import LaserScanChannel, PointCloudChannel, RawImageChannel
from foxglove.messages import (
    LaserScan,
    PackedElementField,
    PackedElementFieldNumericType,
    PointCloud,
    Pose,
    Quaternion,
    RawImage,
    Vector3,
)

from morsec.component.catalogue import type_lineage
from morsec.component.fields import JSON_SCHEMA_DIALECT
from morsec.kits.geometry import euler_to_quat
from morsec.middleware.ros.serialisers import default_topic
from morsec.runtime.foxglove.world import stamp

log = logging.getLogger("morsec.runtime.foxglove")

# the camera's optical frame (x right, y down, z forward) in the component's frame (x forward, y left, z up)
OPTICAL = (-0.5, 0.5, -0.5, 0.5)  # x, y, z, w
XYZ_FIELDS = [PackedElementField(name=axis, offset=4 * i, type=PackedElementFieldNumericType.Float32)
              for i, axis in enumerate("xyz")]
VLP16_AZIMUTH = 60.0  # deg between the VLP-16's three cameras (camera 1 looks ahead)


def nanoseconds(seconds: float) -> int:
    return int(round(float(seconds) * 1e9))


class FoxgloveStream:
    """One channel fed with a component's messages, each converted by `convert` (None: nothing to send)."""

    def __init__(self, component: str, channel):
        self.component = component
        self.channel = channel
        self.failed: set[str] = set()

    @property
    def topic(self) -> str:
        return self.channel.topic()

    @property
    def listening(self) -> bool:
        return self.channel.has_sinks()

    def publish(self, message: dict, seconds: float | None = None) -> None:
        """`seconds`: the simulated time of a message that has no timestamp (an actuator's command)."""
        try:
            converted = self.convert(message)
            if converted is not None:
                when = message["timestamp"] if seconds is None else seconds
                self.channel.log(converted, log_time=nanoseconds(when))
        except Exception as err:  # a message this stream cannot read (a level without its fields ...): said once
            key = f"{type(err).__name__}: {err}"
            if key not in self.failed:
                self.failed.add(key)
                log.error("%s: Foxglove stream %s: %s", self.component, self.topic, key)

    def convert(self, message: dict) -> Any:
        raise NotImplementedError

    def close(self) -> None:
        self.channel.close()


class LaserScanStream(FoxgloveStream):
    def __init__(self, component: str, context: Context, topic: str, properties):
        super().__init__(component, LaserScanChannel(topic, context=context))
        self.start = -math.radians(float(properties.scan_window)) / 2
        self.increment = math.radians(float(properties.resolution))

    def convert(self, message):
        ranges = np.asarray(message["range_list"], dtype=float)
        remission = message.get("remission_list")
        return LaserScan(timestamp=stamp(message["timestamp"]), frame_id=self.component,
                         start_angle=self.start, end_angle=self.start + self.increment * max(len(ranges) - 1, 0),
                         ranges=ranges.tolist(),
                         intensities=np.asarray(remission, dtype=float).tolist() if remission is not None else None)


class PointCloudStream(FoxgloveStream):
    """x, y, z float32 points, from a message's `points` (base64 or bytes, MORSE's buffer) or, for a
    layered laser, its `point_list`; `pose` places the points' frame in the component's."""

    def __init__(self, component: str, context: Context, topic: str, pose: Pose | None = None,
                 key: str = "points"):
        super().__init__(component, PointCloudChannel(topic, context=context))
        self.pose = pose
        self.key = key

    def convert(self, message):
        value = message[self.key]
        if self.key == "point_list":
            raw = np.asarray(value, dtype=np.float32).reshape(-1, 3).tobytes()
        else:
            raw = base64.b64decode(value) if isinstance(value, str) else bytes(memoryview(value))
        return PointCloud(timestamp=stamp(message["timestamp"]), frame_id=self.component, pose=self.pose,
                          point_stride=12, fields=XYZ_FIELDS, data=raw)


class ImageStream(FoxgloveStream):
    """A camera's picture (`part`: the kinect's rgb or depth half of its message). MORSE's pictures are
    delivered top row first unless Vertical_Flip is off: then they are flipped back for display."""

    def __init__(self, component: str, context: Context, topic: str, encoding: str, flip: bool,
                 part: str | None = None):
        super().__init__(component, RawImageChannel(topic, context=context))
        self.encoding = encoding
        self.flip = flip
        self.part = part

    def convert(self, message):
        picture = message[self.part] if self.part else message
        image = picture.get("image")
        if image is None:
            return None
        width, height = int(picture["width"]), int(picture["height"])
        pixels = base64.b64decode(image) if isinstance(image, str) else bytes(memoryview(image))
        step = len(pixels) // height if height else 0
        if self.flip:
            pixels = np.frombuffer(pixels, dtype=np.uint8).reshape(height, step)[::-1].tobytes()
        return RawImage(timestamp=stamp(picture.get("timestamp", message["timestamp"])), frame_id=self.component,
                        width=width, height=height, encoding=self.encoding, step=step, data=pixels)


class JsonStream(FoxgloveStream):
    """The message as MORSE's socket stream sends it (numbers, lists, objects; NaN and infinities as null,
    which JSON lacks), with its JSON Schema."""

    def __init__(self, component: str, context: Context, topic: str, name: str, schema: dict):
        schema = {"$schema": JSON_SCHEMA_DIALECT, **schema}
        super().__init__(component, Channel(topic, schema=Schema(name=name, encoding="jsonschema",
                                                                 data=json.dumps(schema).encode("utf-8")),
                                            message_encoding="json", context=context))

    def convert(self, message):
        try:
            return json.dumps(message, default=_plain, allow_nan=False).encode("utf-8")
        except ValueError:  # NaN or infinity somewhere
            return json.dumps(_finite(message), default=_plain, allow_nan=False).encode("utf-8")


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (bytes, bytearray, memoryview)):
        return base64.b64encode(bytes(value)).decode("ascii")
    raise TypeError(f"{type(value).__name__} is not JSON serializable")


def _finite(value):
    if isinstance(value, float) or isinstance(value, np.floating):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    if isinstance(value, np.ndarray):
        return _finite(value.tolist())
    return value


def schema_name(cls, level: str | None) -> str:
    """The name a JSON channel's schema has in Foxglove: morsec.<kind>.<id>[.<level>]."""
    kind = "sensors" if getattr(cls, "direction", "OUT") == "OUT" else "actuators"
    return f"morsec.{kind}.{cls.id}" + (f".{level}" if level else "")


def streams_for(context: Context, fqn: str, cls, level: str | None, properties) -> list[FoxgloveStream]:
    """The Foxglove streams of one component (`cls`: its class, `properties`: its resolved properties)."""
    topic = default_topic(fqn)
    types = type_lineage(cls)
    if "laser_scanner" in types:
        if int(getattr(properties, "layers", 1)) > 1:
            return [PointCloudStream(fqn, context, topic, key="point_list")]
        return [LaserScanStream(fqn, context, topic, properties)]
    if "vlp16" in types:  # its points are in the optical frame of its camera `master_camera`
        yaw = math.radians(VLP16_AZIMUTH * (int(properties.master_camera) - 1))
        return [PointCloudStream(fqn, context, topic, _optical_pose(yaw))]
    if "depth_camera" in types:
        return [PointCloudStream(fqn, context, topic, _optical_pose(0.0))]
    flip = not bool(getattr(properties, "Vertical_Flip", True))
    if "depth_video_camera" in types:
        return [ImageStream(fqn, context, topic, "32FC1", flip)]
    if "video_camera" in types:
        return [ImageStream(fqn, context, topic, "rgba8", flip)]
    if "kinect" in types:
        return [ImageStream(fqn, context, f"{topic}/rgb", "rgba8", flip, part="rgb"),
                ImageStream(fqn, context, f"{topic}/depth", "32FC1", flip, part="depth")]
    return [JsonStream(fqn, context, topic, schema_name(cls, level), cls.message_schema(level))]


def optical_quaternion(yaw: float) -> tuple[float, float, float, float]:
    """(x, y, z, w) of the optical frame of a camera turned by `yaw` (rad) about the component's z axis."""
    w1, _, _, z1 = euler_to_quat(0.0, 0.0, yaw)
    x2, y2, z2, w2 = OPTICAL
    # (w1 + z1 k) * (w2 + x2 i + y2 j + z2 k)
    return (float(w1 * x2 - z1 * y2), float(w1 * y2 + z1 * x2), float(w1 * z2 + z1 * w2), float(w1 * w2 - z1 * z2))


def _optical_pose(yaw: float) -> Pose:
    x, y, z, w = optical_quaternion(yaw)
    return Pose(position=Vector3(x=0.0, y=0.0, z=0.0), orientation=Quaternion(x=x, y=y, z=z, w=w))
