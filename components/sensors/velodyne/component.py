"""MORSE's `Velodyne` builder (DepthCameraRotationZ): a depth camera that turns about its vertical axis
after every tick."""

import math

import numpy as np
from pydantic import Field

from morsec.component.catalogue import component_class
from morsec.kits.camera import optical_rotation
from morsec.kits.geometry import euler_to_quat

DepthCamera = component_class("sensors", "depth_camera")

# MORSE's builder sets `rotation` to the camera's angle: the field of view of its default 35 mm lens
FOV_35MM = 2.0 * math.atan(16.0 / 35.0)


def _quat_mul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw])


class Velodyne(DepthCamera):
    """A depth camera that turns: after each tick, whether it grabbed or not, the camera turns `rotation`
    radians about the component's +z (to the left, counter-clockwise seen from above), so that
    consecutive pictures sweep around the sensor; with the defaults (256 x 256 pixels, 35 mm lens, 20 Hz)
    each picture covers 49.1 degrees and the camera turns by exactly that much: a full turn every 7.3
    pictures, 2.7 turns per second. Tick k (k = 0 first) looks at azimuth k * rotation (mod 2 pi) from the
    component's +x.

    The points are those of `depth_camera` but expressed in the optical frame of the camera **at
    azimuth 0** (x right, y down, z forward along the component's +x): the component's frame does not
    turn, only its camera, so consecutive messages add up to a 360-degree cloud without knowing the
    azimuth. `nb_points`, `keep_list`, `keep_resolution` and the socket message are depth_camera's."""

    short_descr = "Depth camera turning about its vertical axis each tick (MORSE's Velodyne)"
    builder_name = "Velodyne"
    frequency = 20.0

    class Properties(DepthCamera.Properties):
        rotation: float = Field(FOV_35MM, description="angle the camera turns after each tick, rad; negative turns "
                                "right (default: the field of view of the default 35 mm lens, 2 atan(16/35) = "
                                "0.857 rad)")

    def start(self) -> None:
        super().start()
        self.azimuth = 0.0  # of the next picture, rad
        self._quat0 = self.sim.model.cam_quat[self.view.id].copy()

    def grab(self) -> None:
        super().grab()
        points = self.local_data["points"]
        if self.azimuth and len(points):
            back = optical_rotation(self.azimuth).astype(np.float32)
            self.local_data["points"] = np.ascontiguousarray(points @ back.T)

    def default_action(self) -> None:
        super().default_action()
        self.azimuth = (self.azimuth + float(self.properties.rotation)) % (2.0 * math.pi)
        turn = euler_to_quat(0.0, 0.0, self.azimuth)
        self.sim.model.cam_quat[self.view.id] = _quat_mul(turn, self._quat0)


COMPONENT = Velodyne
