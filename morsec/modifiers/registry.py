"""Which modifier class `alter(name)` gives for each component type (MORSE's MORSE_MODIFIER_DICT)."""

from __future__ import annotations

from morsec.modifiers import coordinates as c
from morsec.modifiers import noise as n
from morsec.modifiers.base import Modifier

_POSITION_OUT = ("pose", "gps")
_POSITION_IN = ("destination", "waypoint", "teleport")


def _coords(to, frm) -> dict[str, type[Modifier]]:
    return {**{t: to for t in _POSITION_OUT}, **{t: frm for t in _POSITION_IN}}


MODIFIERS: dict[str, dict[str, type[Modifier]]] = {
    "noise": {"imu": n.IMUNoise, "odometry": n.PoseNoise, "pose": n.PoseNoise, "gps": n.PositionNoise,
              "gyroscope": n.OrientationNoise},
    "posenoise": {"odometry": n.PoseNoise, "pose": n.PoseNoise},
    "imunoise": {"imu": n.IMUNoise},
    "odometrynoise": {"odometry": n.OdometryNoise},
    "ned": {**_coords(c.ToNED, c.FromNED), "gyroscope": c.AnglesToNED, "orientation": c.AnglesFromNED},
    "utm": {"pose": c.ToUTM, "gps": c.ToUTM, "destination": c.FromUTM, "waypoint": c.FromUTM},
    "ecef": _coords(c.ToECEF, c.FromECEF),
    "geodetic": _coords(c.ToGeodetic, c.FromGeodetic),
    "geocentric": _coords(c.ToGeocentric, c.FromGeocentric),
    "feet": _coords(c.ToFeet, c.FromFeet),
}


def modifier_class(name: str, component_cls) -> type[Modifier] | None:
    """The modifier class for a component class, looked up by its id then its parents' (a preset such as
    `sick` takes the modifiers of `laser_scanner`)."""
    table = MODIFIERS.get(name.lower(), {})
    for klass in component_cls.__mro__:
        cid = vars(klass).get("id")
        if cid and cid in table:
            return table[cid]
    return None


def applicable(name: str) -> list[str]:
    return sorted(MODIFIERS.get(name.lower(), {}))
