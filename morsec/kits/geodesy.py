"""WGS84 conversions between the scene frame, ECEF and geodetic coordinates.

The scene frame is a local tangent plane at the environment's geodetic origin (properties `longitude`,
`latitude` in degrees, `altitude` in metres). With `angle_against_north` = 0 the scene's x axis points
East and y North (ENU, as MORSE's Blender world); a non-zero angle (degrees) turns the scene's axes
clockwise seen from above: y then points that many degrees east of true north.

These properties are read as MORSE read them: a number is a Blender game property, a 32-bit float (43.6
becomes 43.59999847...: about 17 cm east of 43.6 at the equator, and MORSE's positions, ECEF and geodetic
outputs all start from that origin); a string (`longitude: "43.6"`) keeps every digit, as MORSE advised for
its UTM offsets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

A = 6378137.0  # WGS84 semi-major axis, m
F = 1 / 298.257223563
E2 = F * (2 - F)
B = A * (1 - F)


def geodetic_to_ecef(lat_deg: float, lon_deg: float, alt: float) -> np.ndarray:
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return np.array([
        (n + alt) * math.cos(lat) * math.cos(lon),
        (n + alt) * math.cos(lat) * math.sin(lon),
        (n * (1 - E2) + alt) * math.sin(lat),
    ])


def ecef_to_geodetic(p) -> tuple[float, float, float]:
    """(latitude deg, longitude deg, altitude m), Bowring's method refined to sub-millimetre."""
    x, y, z = (float(v) for v in p)
    lon = math.atan2(y, x)
    r = math.hypot(x, y)
    lat = math.atan2(z, r * (1 - E2))
    for _ in range(6):
        n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
        alt = r / math.cos(lat) - n if abs(lat) < math.radians(89) else abs(z) / math.sin(abs(lat)) - n * (1 - E2)
        lat = math.atan2(z, r * (1 - E2 * n / (n + alt)))
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    alt = r / math.cos(lat) - n if abs(lat) < math.radians(89) else abs(z) / math.sin(abs(lat)) - n * (1 - E2)
    return math.degrees(lat), math.degrees(lon), alt


def enu_rotation(lat_deg: float, lon_deg: float) -> np.ndarray:
    """Rows: East, North, Up unit vectors in ECEF."""
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    return np.array([
        [-math.sin(lon), math.cos(lon), 0.0],
        [-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)],
        [math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)],
    ])


def blender_float(value) -> float:
    """An environment property as MORSE's scene held it: a number becomes a Blender game property (a 32-bit
    float); a string is read with all its digits."""
    if isinstance(value, str):
        return float(value)
    return float(np.float32(value))


@dataclass
class GeoFrame:
    latitude: float
    longitude: float
    altitude: float
    angle_against_north: float = 0.0

    @classmethod
    def from_properties(cls, props: dict) -> GeoFrame:
        missing = [k for k in ("longitude", "latitude", "altitude") if k not in props]
        if missing:
            raise ValueError("geodetic conversions need the environment properties longitude, latitude and "
                             f"altitude (missing: {', '.join(missing)})")
        return cls(blender_float(props["latitude"]), blender_float(props["longitude"]),
                   blender_float(props["altitude"]), blender_float(props.get("angle_against_north", 0.0)))

    def __post_init__(self):
        self.origin = geodetic_to_ecef(self.latitude, self.longitude, self.altitude)
        self.enu = enu_rotation(self.latitude, self.longitude)
        a = math.radians(self.angle_against_north)
        # scene -> ENU: turn the scene clockwise by the angle
        self.scene_to_enu = np.array([[math.cos(a), math.sin(a), 0.0], [-math.sin(a), math.cos(a), 0.0], [0, 0, 1.0]])

    def to_enu(self, p) -> np.ndarray:
        return self.scene_to_enu @ np.asarray(p, dtype=float)

    def from_enu(self, enu) -> np.ndarray:
        return self.scene_to_enu.T @ np.asarray(enu, dtype=float)

    def to_ecef(self, p) -> np.ndarray:
        return self.origin + self.enu.T @ self.to_enu(p)

    def from_ecef(self, ecef) -> np.ndarray:
        return self.from_enu(self.enu @ (np.asarray(ecef, dtype=float) - self.origin))

    def to_geodetic(self, p) -> tuple[float, float, float]:
        return ecef_to_geodetic(self.to_ecef(p))

    def from_geodetic(self, lat: float, lon: float, alt: float) -> np.ndarray:
        return self.from_ecef(geodetic_to_ecef(lat, lon, alt))
