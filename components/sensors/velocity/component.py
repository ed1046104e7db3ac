import mujoco
import numpy as np

from morsec.component import ComputationModeProperties, DataField, Sensor
from morsec.kits.geometry import matrix_to_quat


class Velocity(Sensor):
    """Linear and angular velocity of the sensor, in its own frame, and its linear velocity in the world
    frame. With physics (`ComputationMode` Velocity) they are MuJoCo's velocity of the sensor's frame
    (a sensor off the robot's centre sees the rotation's lever arm); in Position mode, finite
    differences of the pose over the measured time since the previous tick."""

    short_descr = "Linear and angular velocity, sensor and world frames"
    builder_name = "Velocity"
    frequency = 60.0

    class Properties(ComputationModeProperties):
        pass

    data = (
        DataField("linear_velocity", [0.0, 0.0, 0.0], "vec3", "velocity along the sensor's x, y, z axes, m/s"),
        DataField("angular_velocity", [0.0, 0.0, 0.0], "vec3", "rates about the sensor's x, y, z axes, rad/s"),
        DataField("world_linear_velocity", [0.0, 0.0, 0.0], "vec3", "velocity along the world x, y, z axes, m/s"),
    )

    def start(self):
        mode = self.properties.ComputationMode
        self.mode = ("Velocity" if self.robot.free else "Position") if mode == "Automatic" else mode
        self.previous_time = self.sim.clock.elapsed  # simulated seconds (exact, unlike epoch timestamps)
        self.previous_pos = self.position().copy()
        self.previous_rot = self.rotation().copy()

    def default_action(self):
        rot = self.rotation().copy()
        if self.mode == "Velocity":
            linear, angular = self.velocity(local=True)
            world = rot @ linear
        else:
            now = self.sim.clock.elapsed
            dt = now - self.previous_time
            if dt < 1e-9:
                return
            pos = self.position().copy()
            world = (pos - self.previous_pos) / dt
            linear = rot.T @ world
            angular = np.zeros(3)
            mujoco.mju_quat2Vel(angular, matrix_to_quat(self.previous_rot.T @ rot), dt)
            self.previous_time, self.previous_pos = now, pos
        self.previous_rot = rot
        self.local_data["linear_velocity"] = [float(v) for v in linear]
        self.local_data["angular_velocity"] = [float(v) for v in angular]
        self.local_data["world_linear_velocity"] = [float(v) for v in world]


COMPONENT = Velocity
