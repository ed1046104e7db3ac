import datetime

import numpy as np

from morsec.component import DataField, GeomagneticDateProperties, Sensor
from morsec.kits.geomagnetism import decimal_year, field_in_scene

RELOCATE_M = 1000.0  # the field is recomputed when the sensor has moved this far
# the sensor frame (x forward, y left, z up) relabelled as the `ned` modifier relabels the scene:
# x' = y, y' = x, z' = -z; with the scene's orientation that is north, east, down
SENSOR_TO_NED = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])


class Magnetometer(Sensor):
    """The Earth's magnetic field at the sensor, from the World Magnetic Model (WMM2010 to WMM2025,
    through the `pygeomag` package), in nT. With the sensor in the scene's orientation (and the
    environment's `angle_against_north` at 0) x is the northern, y the eastern and z the downward
    component, as MORSE's; the reading turns with the sensor (it is the field in the sensor's frame,
    its axes relabelled as the `ned` modifier relabels the scene's: x' = y, y' = x, z' = -z).

    Needs the environment properties `longitude`, `latitude` and `altitude`: without them the
    simulation does not start."""

    short_descr = "Earth's magnetic field (World Magnetic Model), nT"
    builder_name = "Magnetometer"
    frequency = 60.0

    class Properties(GeomagneticDateProperties):
        pass

    data = (
        DataField("x", 0.0, "float", "northern component of the magnetic field, nT"),
        DataField("y", 0.0, "float", "eastern component of the magnetic field, nT"),
        DataField("z", 0.0, "float", "downward component of the magnetic field, nT"),
    )

    def start(self):
        self.geo = self.sim.geo  # ValueError (the simulation does not start) without geodetic properties
        self.year = self.properties.date or decimal_year(datetime.date.today())
        self.field_at = None
        self.field = np.zeros(3)  # scene frame, nT

    def default_action(self):
        pos = self.position()
        if self.field_at is None or np.linalg.norm(pos - self.field_at) > RELOCATE_M:
            self.field = field_in_scene(self.geo, pos, self.year)
            self.field_at = pos.copy()
        x, y, z = SENSOR_TO_NED @ (self.rotation().T @ self.field)
        self.local_data.update(x=float(x), y=float(y), z=float(z))


COMPONENT = Magnetometer
