"""Coordinate modifiers: sensor outputs converted from the scene frame (ENU at the environment's geodetic
origin) to another convention, actuator inputs converted back. Positions are the fields x, y, z."""

from __future__ import annotations

import logging
import math

from pydantic import Field

from morsec.kits.geometry import normalize_angle
from morsec.modifiers.base import Modifier, ModifierParams

FEET_PER_METRE = 3.2808399
log = logging.getLogger("morsec.modifiers")


def _lacks(modifier: Modifier, data: dict, keys: tuple[str, ...] = ("x", "y", "z")) -> bool:
    """True (and a warning, once) when the data has not the fields this modifier converts (a GPS at its
    raw level has no x, y, z): the data then goes out unchanged, as MORSE's, instead of not at all."""
    missing = [k for k in keys if k not in data]
    if missing and not getattr(modifier, "_warned", False):
        modifier._warned = True
        log.warning("modifier %s: the data has no field %s; left unchanged", type(modifier).__name__,
                    ", ".join(missing))
    return bool(missing)


def _xyz(data: dict):
    return float(data["x"]), float(data["y"]), float(data["z"])


def _set(data: dict, x: float, y: float, z: float) -> None:
    data["x"], data["y"], data["z"] = float(x), float(y), float(z)


class ToNED(Modifier):
    """x' = y (north), y' = x (east), z' = -z (down)."""

    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        x, y, z = _xyz(data)
        _set(data, y, x, -z)


FromNED = ToNED  # the swap is its own inverse


class AnglesToNED(Modifier):
    """Heading from north, clockwise: yaw' = pi/2 - yaw; pitch' = -pitch; roll unchanged."""

    def modify(self, data: dict) -> None:
        if _lacks(self, data, ("yaw", "pitch")):
            return
        data["yaw"] = normalize_angle(math.pi / 2 - float(data["yaw"]))
        data["pitch"] = -float(data["pitch"])


AnglesFromNED = AnglesToNED  # its own inverse too


class UTMParams(ModifierParams):
    x_offset: float = Field(0.0, description="m, or env property UTMXOffset")
    y_offset: float = Field(0.0, description="m, or env property UTMYOffset")
    z_offset: float = Field(0.0, description="m, or env property UTMZOffset")


class ToUTM(Modifier):
    """Adds the UTM offsets of the scene origin (strings are accepted for large values)."""

    Params = UTMParams
    env_defaults = {"x_offset": "UTMXOffset", "y_offset": "UTMYOffset", "z_offset": "UTMZOffset"}
    sign = 1.0

    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        p = self.params
        x, y, z = _xyz(data)
        _set(data, x + self.sign * p.x_offset, y + self.sign * p.y_offset, z + self.sign * p.z_offset)


class FromUTM(ToUTM):
    sign = -1.0


class ToECEF(Modifier):
    """Earth-centred, Earth-fixed coordinates (WGS84), m."""
    needs_geo = True

    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        _set(data, *self.sim.geo.to_ecef(_xyz(data)))


class FromECEF(Modifier):
    needs_geo = True

    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        _set(data, *self.sim.geo.from_ecef(_xyz(data)))


class ToGeodetic(Modifier):
    """x = longitude (deg), y = latitude (deg), z = altitude (m, WGS84 ellipsoid)."""
    needs_geo = True

    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        lat, lon, alt = self.sim.geo.to_geodetic(_xyz(data))
        _set(data, lon, lat, alt)


class FromGeodetic(Modifier):
    needs_geo = True

    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        lon, lat, alt = _xyz(data)
        _set(data, *self.sim.geo.from_geodetic(lat, lon, alt))


class ToGeocentric(Modifier):
    """Spherical geocentric coordinates: x = longitude (deg), y = geocentric latitude (deg), z = distance
    to the Earth's centre (m)."""
    needs_geo = True

    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        ex, ey, ez = self.sim.geo.to_ecef(_xyz(data))
        r = math.sqrt(ex * ex + ey * ey + ez * ez)
        _set(data, math.degrees(math.atan2(ey, ex)), math.degrees(math.asin(ez / r)), r)


class FromGeocentric(Modifier):
    needs_geo = True

    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        lon_deg, lat_deg, radius = _xyz(data)
        lon, lat = math.radians(lon_deg), math.radians(lat_deg)
        ecef = (radius * math.cos(lat) * math.cos(lon), radius * math.cos(lat) * math.sin(lon), radius * math.sin(lat))
        _set(data, *self.sim.geo.from_ecef(ecef))


class ToFeet(Modifier):
    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        x, y, z = _xyz(data)
        _set(data, x * FEET_PER_METRE, y * FEET_PER_METRE, z * FEET_PER_METRE)


class FromFeet(Modifier):
    def modify(self, data: dict) -> None:
        if _lacks(self, data):
            return
        x, y, z = _xyz(data)
        _set(data, x / FEET_PER_METRE, y / FEET_PER_METRE, z / FEET_PER_METRE)


# the coordinate modifiers of a component whose data holds a position x, y, z: a sensor's output converted
# (`modifiers = {**POSITION_OUT, ...}`) or an actuator's input converted back (POSITION_IN)
POSITION_OUT: dict[str, type[Modifier]] = {"ned": ToNED, "utm": ToUTM, "ecef": ToECEF, "geodetic": ToGeodetic,
                                           "geocentric": ToGeocentric, "feet": ToFeet}
POSITION_IN: dict[str, type[Modifier]] = {"ned": FromNED, "utm": FromUTM, "ecef": FromECEF, "geodetic": FromGeodetic,
                                          "geocentric": FromGeocentric, "feet": FromFeet}
