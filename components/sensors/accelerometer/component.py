import mujoco
import numpy as np

from morsec.component import ComputationModeProperties, DataField, Sensor
from morsec.kits.geometry import matrix_to_quat


class Accelerometer(Sensor):
    """Distance travelled since the previous tick, velocity, acceleration (**without** gravity) and
    angular acceleration of the sensor, in the sensor's frame.

    With physics (`ComputationMode` Velocity) the velocities are MuJoCo's velocity of the sensor's frame
    and the accelerations their change since the previous tick, over the elapsed simulated time (as
    MORSE differentiates the physics velocities); in Position mode the velocities are finite differences
    of the pose too."""

    short_descr = "Distance, velocity, acceleration (no gravity) and angular acceleration, sensor frame"
    builder_name = "Accelerometer"
    frequency = 60.0

    class Properties(ComputationModeProperties):
        pass

    data = (
        DataField("distance", 0.0, "float", "distance travelled since the previous tick, m"),
        DataField("velocity", [0.0, 0.0, 0.0], "vec3", "velocity along the sensor's x, y, z axes, m/s"),
        DataField("acceleration", [0.0, 0.0, 0.0], "vec3",
                  "acceleration along the sensor's x, y, z axes, gravity not included, m/s^2"),
        DataField("angular_acceleration", [0.0, 0.0, 0.0], "vec3",
                  "angular acceleration about the sensor's x, y, z axes, rad/s^2"),
    )

    def start(self):
        mode = self.properties.ComputationMode
        self.mode = ("Velocity" if self.robot.free else "Position") if mode == "Automatic" else mode
        self.previous_time = self.sim.clock.elapsed  # simulated seconds (exact, unlike epoch timestamps)
        self.previous_pos = self.position().copy()
        self.previous_rot = self.rotation().copy()
        if self.mode == "Velocity":
            linear, angular = self.velocity(local=False)
            self.previous_vel, self.previous_rates = linear.copy(), angular.copy()
        else:
            self.previous_vel, self.previous_rates = np.zeros(3), np.zeros(3)  # world frame

    def default_action(self):
        now = self.sim.clock.elapsed
        dt = now - self.previous_time
        if dt < 1e-9:
            return
        pos, rot = self.position().copy(), self.rotation().copy()
        if self.mode == "Velocity":
            linear, angular = self.velocity(local=False)
            vel, rates = linear.copy(), angular.copy()
        else:
            vel = (pos - self.previous_pos) / dt
            local_rates = np.zeros(3)
            mujoco.mju_quat2Vel(local_rates, matrix_to_quat(self.previous_rot.T @ rot), dt)
            rates = rot @ local_rates
        self.local_data["distance"] = float(np.linalg.norm(pos - self.previous_pos))
        self.local_data["velocity"] = [float(v) for v in rot.T @ vel]
        self.local_data["acceleration"] = [float(v) for v in rot.T @ (vel - self.previous_vel) / dt]
        self.local_data["angular_acceleration"] = [float(v) for v in rot.T @ (rates - self.previous_rates) / dt]
        self.previous_time, self.previous_pos, self.previous_rot = now, pos, rot
        self.previous_vel, self.previous_rates = vel, rates


COMPONENT = Accelerometer
