"""MORSE's DepthCameraAggregator: the points of the depth cameras appended to it, merged in one camera's frame."""

from __future__ import annotations

from typing import ClassVar

import numpy as np
from pydantic import Field

from morsec.component import DataField, Sensor
from morsec.kits.camera import OPTICAL_TO_COMPONENT, b64


class AggregatorBuilder:
    """MORSE's builder: `append(camera)` adds a depth camera, `set_master(i)` makes the i-th appended one (0
    first) the camera whose frame the points are given in."""

    def set_master(self, master):
        self.properties(master_camera=str(master))


class DepthCameraAggregator(Sensor):
    """Merges the points of the depth cameras appended to it (depth_camera, or anything giving `points` in its
    optical frame), each camera's latest cloud, in the order they were appended, into **the optical frame of
    the master camera** (`master_camera`: a child's name or its place among them, 0 first; default the first):
    x right, y down, z forward. NaN points (a camera with `keep_resolution`) stay NaN. It sends a message
    when one of its cameras grabbed a new picture; the cameras keep their own frequency, size and rows
    (`keep_list`): three cameras side by side make a wide multi-layer lidar (MORSE's VLP16_180, here
    `vlp16`). Socket message as depth_camera's: `{timestamp, points (base64 float32 x, y, z ...),
    nb_points}`."""

    short_descr = "Points of several depth cameras merged in one camera's frame"
    builder_name = "DepthCameraAggregator"
    frequency = 60.0
    tick_last: ClassVar[bool] = True  # after its cameras, whose clouds it merges
    builder_mixin = AggregatorBuilder

    class Properties(Sensor.Properties):
        master_camera: str = Field("", description="the camera whose optical frame the points are in: the name "
                                   "of one of the cameras appended to it, or its place among them (0 first); "
                                   "empty: the first")

    data = (
        DataField("points", None, "base64", "nb_points x 3 float32: the cameras' points, x, y, z in the master "
                  "camera's optical frame (x right, y down, z forward), m; the first camera's first, each as it "
                  "gives them; on the wire base64 of nb_points * 12 bytes"),
        DataField("nb_points", 0, "int", "number of points"),
    )

    def start(self) -> None:
        cameras = [c for c in self.sim.components if c.parent == self.name and c.kind == "sensor"
                   and any(f.name == "points" for f in type(c.instance).data)]
        if not cameras:
            raise ValueError("no depth camera appended to it: append depth_camera components to the aggregator")
        self.cameras = [c.instance for c in cameras]
        names = [c.fqn.rsplit(".", 1)[-1] for c in cameras]
        master = self.properties.master_camera.strip()
        if not master:
            index = 0
        elif master in names:
            index = names.index(master)
        elif master.isdigit() and int(master) < len(cameras):
            index = int(master)
        else:
            raise ValueError(f"master_camera {master!r} is none of its cameras ({', '.join(names)})")
        self.master = self.cameras[index]
        self._seen = [None] * len(self.cameras)
        self.fresh = False
        self.local_data["points"] = np.zeros((0, 3), dtype=np.float32)

    def default_action(self) -> None:
        stamps = [c.local_data.get("timestamp") if c.capturing else None for c in self.cameras]
        self.fresh = any(s is not None and s != seen for s, seen in zip(stamps, self._seen))
        self._seen = [s if s is not None else seen for s, seen in zip(stamps, self._seen)]
        if not self.fresh:
            return
        # optical frame of camera i -> world -> the master's optical frame
        m_pos, m_rot = self.master.position(), self.master.rotation() @ OPTICAL_TO_COMPONENT
        clouds = []
        for cam in self.cameras:
            points = np.asarray(cam.local_data.get("points"), dtype=np.float64).reshape(-1, 3)
            rot = m_rot.T @ cam.rotation() @ OPTICAL_TO_COMPONENT
            shift = m_rot.T @ (cam.position() - m_pos)
            clouds.append(points @ rot.T + shift)
        points = np.ascontiguousarray(np.concatenate(clouds), dtype=np.float32)
        self.local_data["points"] = points
        self.local_data["nb_points"] = int(len(points))

    def serialize(self) -> dict | None:
        if not self.fresh:
            return None
        return {"timestamp": self.local_data["timestamp"], "points": b64(self.local_data["points"]),
                "nb_points": self.local_data["nb_points"]}


COMPONENT = DepthCameraAggregator
