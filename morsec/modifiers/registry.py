"""The modifier names `alter(name)` accepts (MORSE's modifier modules), each with what it does.

Which class a name gives on a component, and so which components it applies to, the component declares
(`Device.modifiers`, e.g. `{"noise": PoseNoise, "ned": ToNED}`); the catalogue collects the declarations
(`morsec.component.catalogue.modifier_class`, `Catalogue.applies_to`). This table is the set of names a scene
may use: the scene IR checks names against it and the JSON Schema and docs list it."""

from __future__ import annotations

MODIFIERS: dict[str, str] = {
    "noise": "Gaussian noise on what the component measures (pose, position, orientation, IMU rates and "
             "accelerations)",
    "posenoise": "Gaussian noise on a pose: x, y, z and roll, pitch, yaw",
    "imunoise": "Gaussian noise on an IMU's angular velocity and linear acceleration",
    "odometrynoise": "odometry scale error and heading drift",
    "ned": "North-East-Down coordinates (x north, y east, z down; headings clockwise from north)",
    "utm": "UTM coordinates: the scene's UTM offsets added (out) or subtracted (in)",
    "ecef": "Earth-centred, Earth-fixed coordinates (WGS84), m",
    "geodetic": "longitude, latitude (degrees) and altitude (m, WGS84)",
    "geocentric": "longitude, geocentric latitude (degrees) and distance to the Earth's centre (m)",
    "feet": "positions in feet",
}
