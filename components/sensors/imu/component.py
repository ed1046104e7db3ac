import datetime
import logging
import math

import mujoco
import numpy as np

from morsec.component import ComputationModeProperties, DataField, GeomagneticDateProperties, SampledSensor
from morsec.kits.geomagnetism import decimal_year, field_in_scene
from morsec.kits.geometry import matrix_to_quat, transpose_apply
from morsec.modifiers.noise import IMUNoise

log = logging.getLogger("morsec.sensors.imu")

RELOCATE_M = 1000.0  # the geomagnetic field is recomputed when the sensor has moved this far
XBODY = int(mujoco.mjtObj.mjOBJ_XBODY)  # the body's own frame (see Component.velocity)


class IMU(SampledSensor):
    """Inertial measurement unit: body rates, specific force (gravity included: +9.81 on z at rest)
    and the Earth's magnetic field, all in the IMU's own frame.

    With physics (`ComputationMode` Velocity, the default for robots that move under physics), the rates
    are MuJoCo's angular velocity of the IMU's frame and the acceleration is the change of the velocity
    of the IMU's own point (`mj_objectVelocity`) since the previous tick, as MORSE differentiates the
    physics velocity: an IMU mounted off the robot's centre feels the centripetal and tangential terms.
    (MuJoCo's `accelerometer` sensor is not used: it reads the forward pass's acceleration, which the
    implicit integration of the stiff base velocity servos does not follow — 30 % off in a turn.) In
    Position mode (robots moved kinematically, fixed robots) velocities are finite differences of the
    sensor's pose too."""

    short_descr = "Angular velocity, linear acceleration (with gravity) and magnetic field, IMU frame"
    builder_name = "IMU"
    frequency = 60.0
    modifiers = {"noise": IMUNoise, "imunoise": IMUNoise}

    class Properties(ComputationModeProperties, GeomagneticDateProperties):
        pass

    data = (
        DataField("angular_velocity", [0.0, 0.0, 0.0], "vec3", "rates about the IMU's x, y, z axes, rad/s"),
        DataField("linear_acceleration", [0.0, 0.0, 0.0], "vec3",
                  "specific force along the IMU's x, y, z axes, m/s^2, gravity included: an IMU at rest reads "
                  "(0, 0, +9.81); mounted off the robot's centre it also feels the centripetal and tangential "
                  "accelerations of the robot's rotation"),
        DataField("magnetic_field", [0.0, 0.0, 0.0], "vec3",
                  "Earth's magnetic field in the IMU frame, nT, from the World Magnetic Model (see magnetometer) "
                  "at the sensor's geodetic position and the `date` property (default: today); (0, 0, 0) when "
                  "the environment has no longitude/latitude/altitude"),
    )

    def start(self):
        m = self.sim.model
        mode = self.properties.ComputationMode
        self.mode = ("Velocity" if self.robot.free else "Position") if mode == "Automatic" else mode
        self.gravity = m.opt.gravity.tolist()  # (0, 0, -g)
        self.previous_time = self.sim.clock.elapsed  # simulated seconds (exact, unlike epoch timestamps)
        self.previous_pos = self.position().tolist()
        self.previous_rot = self.sim.data.xmat[self.body_id].tolist()
        self.previous_vel = self.velocity(local=False)[0].tolist() if self.mode == "Velocity" else [0.0] * 3
        # views of the sensor's world position and rotation in MjData (whose arrays stay put), and the buffer
        # mj_objectVelocity writes (angular, linear; world frame): this ticks every frame
        self.xpos, self.xmat = self.sim.data.xpos[self.body_id], self.sim.data.xmat[self.body_id]
        self._velocity = np.zeros(6)
        self.field_at = None  # scene position where the field was last computed
        self.field = [0.0, 0.0, 0.0]  # field in the scene frame, nT
        try:
            self.geo = self.sim.geo
        except ValueError:
            self.geo = None
            log.info("%s: no geodetic environment properties: magnetic_field stays zero", self.name)

    def sample(self):
        now = self.sim.clock.elapsed
        dt = now - self.previous_time
        if dt < 1e-9:
            return None  # no time passed: no new sample, the data stays
        rot = self.xmat.tolist()  # row-major 3x3, plain floats: this ticks every frame
        pos = self.xpos.tolist()
        previous_rot = None
        if self.mode == "Velocity":  # Component.velocity(local=False), written out
            mujoco.mj_objectVelocity(self.sim.model, self.sim.data, XBODY, self.body_id, self._velocity, 0)
            velocity = self._velocity.tolist()
            vel, angular = velocity[3:], velocity[:3]  # world frame
        else:
            vel = [(p - q) / dt for p, q in zip(pos, self.previous_pos)]
            angular, previous_rot = None, self.previous_rot
        previous_vel = self.previous_vel
        self.previous_time, self.previous_pos, self.previous_rot, self.previous_vel = now, pos, rot, vel
        # the field's relocation is checked at every tick: where it was last computed follows the ticks
        return rot, previous_rot, angular, vel, previous_vel, dt, self._field(pos)

    def compute(self, rot, previous_rot, angular, vel, previous_vel, dt, field):
        if angular is not None:
            rates = transpose_apply(rot, angular)
        else:
            rates = np.zeros(3)
            relative = np.reshape(previous_rot, (3, 3)).T @ np.reshape(rot, (3, 3))
            mujoco.mju_quat2Vel(rates, matrix_to_quat(relative), dt)
            rates = rates.tolist()
        (g0, g1, g2), (p0, p1, p2), (v0, v1, v2) = self.gravity, previous_vel, vel
        # specific force: the acceleration minus gravity (gravity's reaction), in the IMU frame
        accel = transpose_apply(rot, ((v0 - p0) / dt - g0, (v1 - p1) / dt - g1, (v2 - p2) / dt - g2))
        local = self.local_dict
        local["angular_velocity"] = list(rates)
        local["linear_acceleration"] = list(accel)
        local["magnetic_field"] = list(transpose_apply(rot, field))

    def _field(self, pos):
        if self.geo is None:
            return self.field
        if self.field_at is None or math.dist(pos, self.field_at) > RELOCATE_M:
            year = self.properties.date or decimal_year(datetime.date.today())
            self.field = field_in_scene(self.geo, pos, year).tolist()
            self.field_at = pos
        return self.field


COMPONENT = IMU
