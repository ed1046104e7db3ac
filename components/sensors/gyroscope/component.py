from morsec.component import DataField, Sensor
from morsec.modifiers.coordinates import AnglesToNED
from morsec.modifiers.noise import OrientationNoise


class Gyroscope(Sensor):
    """Orientation of the sensor in the world frame, as MORSE's Gyroscope: an attitude sensor that
    gives angles (XYZ Euler: roll about x, then pitch about y, then yaw about z, fixed axes), not a
    rate gyro (the IMU gives rates)."""

    short_descr = "Yaw, pitch and roll of the sensor, world frame"
    builder_name = "Gyroscope"
    frequency = 60.0
    modifiers = {"noise": OrientationNoise, "ned": AnglesToNED}
    data = (
        DataField("yaw", 0.0, "float", "rotation about the world z axis, rad in [-pi, pi)"),
        DataField("pitch", 0.0, "float", "rotation about the y axis, rad in [-pi/2, pi/2]"),
        DataField("roll", 0.0, "float", "rotation about the x axis, rad in [-pi, pi)"),
    )

    def default_action(self):
        roll, pitch, yaw = self.euler()
        self.local_data.update(yaw=float(yaw), pitch=float(pitch), roll=float(roll))


COMPONENT = Gyroscope
