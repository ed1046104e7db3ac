from typing import Literal

import mujoco
import numpy as np
from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor
from morsec.geometry import matrix_to_quat

VEC3 = "vec3<float>"


class Accelerometer(Sensor):
    """Distance travelled since the previous tick, velocity, acceleration (**without** gravity) and
    angular acceleration of the sensor, in the sensor's frame.

    With physics (`ComputationMode` Velocity) the values come from MuJoCo's `velocimeter`,
    `accelerometer` and `frameangacc` sensors on the accelerometer's site (`sensor.xml.j2`), gravity
    taken out; in Position mode they are finite differences of the pose over the measured time since
    the previous tick, as MORSE."""

    short_descr = "Distance, velocity, acceleration (no gravity) and angular acceleration, sensor frame"
    builder_name = "Accelerometer"
    frequency = 60.0

    class Properties(ComponentProperties):
        ComputationMode: Literal["Automatic", "Velocity", "Position"] = Field(
            "Automatic", description="Velocity: from the physics; Position: finite differences of the pose; "
            "Automatic: Velocity for a robot moving under physics, Position otherwise")

    data = (
        DataField("distance", 0.0, "float", "distance travelled since the previous tick, m"),
        DataField("velocity", [0.0, 0.0, 0.0], VEC3, "velocity along the sensor's x, y, z axes, m/s"),
        DataField("acceleration", [0.0, 0.0, 0.0], VEC3,
                  "acceleration along the sensor's x, y, z axes, gravity not included, m/s^2"),
        DataField("angular_acceleration", [0.0, 0.0, 0.0], VEC3,
                  "angular acceleration about the sensor's x, y, z axes, rad/s^2"),
    )

    def start(self):
        m = self.sim.model
        mode = self.properties.ComputationMode
        self.mode = ("Velocity" if self.robot.free else "Position") if mode == "Automatic" else mode
        self.adr = {key: _sensor_adr(m, f"{self.name}/{key}") for key in ("velocimeter", "accelerometer", "angacc")}
        self.gravity = np.array(m.opt.gravity, dtype=float)
        self.previous_time = float(self.sim.clock.now())
        self.previous_pos = self.position().copy()
        self.previous_rot = self.rotation().copy()
        self.previous_vel = np.zeros(3)  # world frame
        self.previous_rates = np.zeros(3)  # sensor frame

    def default_action(self):
        now = float(self.local_data["timestamp"])
        dt = now - self.previous_time
        if dt < 1e-9:
            return
        pos, rot = self.position().copy(), self.rotation().copy()
        self.local_data["distance"] = float(np.linalg.norm(pos - self.previous_pos))
        if self.mode == "Velocity":
            data = self.sim.data.sensordata
            velocity = data[self.adr["velocimeter"]:self.adr["velocimeter"] + 3].copy()
            accel = data[self.adr["accelerometer"]:self.adr["accelerometer"] + 3] + rot.T @ self.gravity
            angular = rot.T @ data[self.adr["angacc"]:self.adr["angacc"] + 3]
        else:
            world_vel = (pos - self.previous_pos) / dt
            rates = np.zeros(3)
            mujoco.mju_quat2Vel(rates, matrix_to_quat(self.previous_rot.T @ rot), dt)
            velocity = rot.T @ world_vel
            accel = rot.T @ (world_vel - self.previous_vel) / dt
            angular = (rates - self.previous_rates) / dt
            self.previous_vel, self.previous_rates = world_vel, rates
        self.previous_time, self.previous_pos, self.previous_rot = now, pos, rot
        self.local_data["velocity"] = [float(v) for v in velocity]
        self.local_data["acceleration"] = [float(v) for v in accel]
        self.local_data["angular_acceleration"] = [float(v) for v in angular]


def _sensor_adr(model, name: str) -> int:
    sid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, name)
    if sid < 0:
        raise ValueError(f"scene.xml has no MuJoCo sensor {name!r}: rebuild the scene")
    return int(model.sensor_adr[sid])


COMPONENT = Accelerometer
