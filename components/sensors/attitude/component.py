import math

import mujoco
import numpy as np
from pydantic import Field

from morsec.component import ComputationModeProperties, DataField, Sensor
from morsec.kits.geometry import matrix_to_quat, normalize_angle


class Attitude(Sensor):
    """Attitude of the sensor: its orientation (XYZ Euler angles) and its body rates, as an integrated
    IMU or a gyroscope/gyrometer pair would give. Rates come from the physics (`ComputationMode`
    Velocity) or from finite differences of the orientation over the nominal period (Position). With
    `UseAngleAgainstNorth` the yaw is measured from true north (counter-clockwise, as the scene's yaw),
    which needs the environment's geodetic properties."""

    short_descr = "Orientation (Euler angles) and angular velocity of the sensor"
    builder_name = "Attitude"
    frequency = 60.0

    class Properties(ComputationModeProperties):
        UseAngleAgainstNorth: bool = Field(
            False, description="yaw from true north instead of from the scene's x axis, counter-clockwise like "
            "the scene's yaw (-bearing of the sensor's x axis, in [-pi, pi)): facing north reads 0, facing east "
            "-pi/2. Needs the environment's longitude, latitude, altitude (and optionally angle_against_north): "
            "without them the simulation does not start")

    data = (
        DataField("rotation", {"yaw": 0.0, "pitch": 0.0, "roll": 0.0}, "dict",
                  "{yaw, pitch, roll} of the sensor (XYZ Euler angles, as pose), rad, as MORSE's socket encoder "
                  "sent a Euler; yaw from north with UseAngleAgainstNorth"),
        DataField("angular_velocity", [0.0, 0.0, 0.0], "vec3", "rates about the sensor's x, y, z axes, rad/s"),
    )

    def start(self):
        mode = self.properties.ComputationMode
        self.mode = ("Velocity" if self.robot.free else "Position") if mode == "Automatic" else mode
        self.previous_rot = self.rotation().copy()
        # ValueError (the simulation does not start) when north is asked for without geodetic properties
        self.geo = self.sim.geo if self.properties.UseAngleAgainstNorth else None

    def default_action(self):
        rot = self.rotation().copy()
        if self.mode == "Velocity":
            _, rates = self.velocity(local=True)
        else:
            rates = np.zeros(3)
            mujoco.mju_quat2Vel(rates, matrix_to_quat(self.previous_rot.T @ rot), 1.0 / self.frequency)
        self.previous_rot = rot
        roll, pitch, yaw = self.euler()
        if self.geo is not None:
            forward = self.geo.to_enu(rot[:, 0])
            bearing = math.atan2(forward[0], forward[1])  # clockwise from north
            yaw = normalize_angle(-bearing)
        self.local_data["rotation"] = {"yaw": float(yaw), "pitch": float(pitch), "roll": float(roll)}
        self.local_data["angular_velocity"] = [float(v) for v in rates]


COMPONENT = Attitude
