import math

import numpy as np
from pydantic import Field

from morsec.component.catalogue import component_class

LaserScanner = component_class("sensors", "laser_scanner")

FAN_TILT_DEG = 12.0  # the builder's arc rotation: Euler XYZ (90 deg, 12 deg, 0), i.e. a vertical fan tilted down
STEP_RAD = 0.01745  # LaserScannerRotationZ.applyRotationZ: the fan turns this much about z after every scan


def fan_rotation() -> np.ndarray:
    """Ry(12 deg) @ Rx(90 deg): turns MORSE's horizontal arc into the vertical fan of VelodyneRayCast."""
    a, t = math.radians(90.0), math.radians(FAN_TILT_DEG)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, math.cos(a), -math.sin(a)], [0.0, math.sin(a), math.cos(a)]])
    ry = np.array([[math.cos(t), 0.0, math.sin(t)], [0.0, 1.0, 0.0], [-math.sin(t), 0.0, math.cos(t)]])
    return ry @ rx


class VelodyneRayCast(LaserScanner):
    """Ray-cast Velodyne (MORSE's `VelodyneRayCast` builder, class LaserScannerRotationZ): a vertical fan of
    64 rays, 0.5 degree apart over 31.5 degrees, up to 50 m, that turns 0.01745 rad (1 degree) about the
    sensor's z axis after every scan: at the default 60 Hz, one turn in 6 simulated seconds.

    The fan is MORSE's arc turned upright and tilted 12 degrees down: ray i has elevation
    -27.75 + 0.5 i degrees (ray 0 lowest, ray 63 at +3.75) and, at scan k (k = 0 first), azimuth
    k * 0.01745 rad about +z from the sensor's +x axis (mod 2 pi). The sensor body does not turn: points
    are given in its (fixed) mounting frame, so consecutive scans add up to a 3-D cloud without knowing
    the azimuth. See `laser_scanner` for the fields and levels."""

    short_descr = "Rotating vertical ray fan (Velodyne-like): 64 rays, 31.5 deg, 50 m, 1 deg per scan"
    builder_name = "VelodyneRayCast"
    frequency = 60.0

    class Properties(LaserScanner.Properties):
        laser_range: float = 50.0
        scan_window: float = Field(31.5, ge=0, le=360, description="vertical angle covered by the fan, deg")
        resolution: float = Field(0.5, gt=0, description="angle between two rays of the fan, deg")
        Visible_arc: bool = True

    def ray_directions(self) -> np.ndarray:
        return super().ray_directions() @ fan_rotation().T

    def start(self) -> None:
        super().start()
        self.azimuth = 0.0  # of the next scan, rad
        self._fan = self._dirs
        self._turned = np.empty_like(self._fan)

    def scan_directions(self) -> np.ndarray:
        c, s = math.cos(self.azimuth), math.sin(self.azimuth)
        np.matmul(self._fan, np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]), out=self._turned)
        return self._turned

    def default_action(self) -> None:
        super().default_action()
        self.azimuth = (self.azimuth + STEP_RAD) % (2.0 * math.pi)


COMPONENT = VelodyneRayCast
