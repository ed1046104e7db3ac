"""MORSE's RotorcraftVelocity: a PD cascade that makes a rotorcraft hold a velocity and a yaw rate by
applying a thrust force along its z axis and torques to its base (d.xfrc_applied), the robot keeping its
weight (gravity on, not NoGravity).

Per tick, with v_sp the commanded velocity turned from the robot's heading frame into the world (its
norm limited to MaxVelocity), v the robot's velocity and a its acceleration (finite difference):

* horizontal: c = HorizontalPgain (v_sp - v)_xy - HorizontalDgain a_xy (rad per m/s, rad per m/s^2),
  turned into roll / pitch setpoints in the heading frame, each saturated at MaxBankAngle;
* yaw: the setpoint is the integral of `vyaw` (counter-clockwise seen from above, as every angle here);
* vertical: thrust = weight / max(cos^2 MaxBankAngle, cos roll cos pitch) + VerticalPgain (vz_sp - vz)
  (N), at least 0 (VerticalDgain is accepted but unused, as in MORSE's controller);
* attitude: torque_i = I_i (Kp_i err_i + Kd_i d(err_i)/dt) scaled by thrust / weight, as RotorcraftWaypoint.
"""

from __future__ import annotations

import math

import numpy as np
from pydantic import Field

from morsec.component import Actuator, DataField, RotorcraftProperties, service
from morsec.kits.geometry import matrix_to_euler, normalize_angle


class RotorcraftVelocity(Actuator):
    """Makes a rotorcraft hold a velocity (vx, vy, vz in its heading frame) and a yaw rate, with a PD
    cascade applied as a force and torques on the robot's base."""

    short_descr = "Fly a rotorcraft at a commanded velocity and yaw rate (forces and torques)"
    builder_name = "RotorcraftVelocity"
    frequency = 60.0

    class Properties(RotorcraftProperties):
        HorizontalPgain: float = Field(0.2, description="horizontal velocity P gain, rad of tilt per m/s")
        HorizontalDgain: float = Field(0.8, description="horizontal acceleration D gain, rad per m/s^2")
        VerticalPgain: float = Field(8.0, description="vertical velocity P gain, N per m/s")
        VerticalDgain: float = Field(2.0, description="vertical acceleration D gain, N per m/s^2: unused, as "
                                     "in MORSE (an acceleration fed back through the thrust makes a light "
                                     "robot oscillate)")
        YawDgain: float = 8.0
        MaxBankAngle: float = Field(math.radians(30), gt=0, lt=math.pi / 2,
                                    description="largest roll or pitch setpoint, rad (limits the horizontal "
                                    "acceleration)")
        MaxVelocity: float = Field(2.0, gt=0, description="largest commanded speed, m/s")

    data = (
        DataField("vx", 0.0, "float", "velocity forward (x of the robot's heading frame), m/s"),
        DataField("vy", 0.0, "float", "velocity to the left (y of the heading frame), m/s"),
        DataField("vz", 0.0, "float", "velocity up, m/s"),
        DataField("vyaw", 0.0, "float", "yaw rate, rad/s (counter-clockwise seen from above)"),
        DataField("tolerance", 0.2, "float", "velocity difference, m/s, under which `setvel` reports the "
                  "velocity reached"),
    )

    def start(self):
        _, rot = self.robot.pose()
        self._yaw_sp = math.atan2(rot[1, 0], rot[0, 0])
        self._prev_vel = None
        self._prev_err = None
        self._inertia = np.diag(self.robot.inertia()).copy()
        self._weight = self.robot.weight()

    def _setpoint(self, yaw: float) -> np.ndarray:
        d = self.local_data
        local = np.array([float(d["vx"]), float(d["vy"]), float(d["vz"])])
        c, s = math.cos(yaw), math.sin(yaw)
        world = np.array([c * local[0] - s * local[1], s * local[0] + c * local[1], local[2]])
        norm = float(np.linalg.norm(world))
        limit = self.properties.MaxVelocity
        return world * (limit / norm) if norm > limit else world

    def default_action(self):
        p = self.properties
        _, rot = self.robot.pose()
        roll, pitch, yaw = matrix_to_euler(rot)
        vel, _ = self.robot.velocity()
        accel = (vel - self._prev_vel) * self.frequency if self._prev_vel is not None else np.zeros(3)
        self._prev_vel = vel
        error = self._setpoint(yaw) - vel

        cx = p.HorizontalPgain * error[0] - p.HorizontalDgain * accel[0]
        cy = p.HorizontalPgain * error[1] - p.HorizontalDgain * accel[1]
        bank = p.MaxBankAngle
        roll_sp = max(-bank, min(bank, math.sin(yaw) * cx - math.cos(yaw) * cy))
        pitch_sp = max(-bank, min(bank, math.cos(yaw) * cx + math.sin(yaw) * cy))
        self._yaw_sp = normalize_angle(self._yaw_sp + float(self.local_data["vyaw"]) / self.frequency)

        weight = self._weight
        compensation = max(math.cos(bank) ** 2, math.cos(roll) * math.cos(pitch))
        thrust = weight / compensation + p.VerticalPgain * error[2]  # MORSE leaves the D term out
        if weight > 0:
            thrust = max(0.0, thrust)

        att_err = np.array([normalize_angle(roll_sp - roll), normalize_angle(pitch_sp - pitch),
                            normalize_angle(self._yaw_sp - yaw)])
        rate = (att_err - self._prev_err) * self.frequency if self._prev_err is not None else np.zeros(3)
        self._prev_err = att_err
        kp = np.array([p.RollPitchPgain, p.RollPitchPgain, p.YawPgain])
        kd = np.array([p.RollPitchDgain, p.RollPitchDgain, p.YawDgain])
        torque = self._inertia * (kp * att_err + kd * rate) * (thrust / weight if weight > 0 else 1.0)
        self.robot.apply_wrench(self.name, rot @ np.array([0.0, 0.0, thrust]), rot @ torque)

    @service
    def setvel(self, vx: float, vy: float, vz: float, vyaw: float, tolerance: float = 0.1) -> bool:
        """Command a velocity (heading frame, m/s) and a yaw rate (rad/s) and return at once: False if the
        robot already moves at that velocity and yaw rate (each within `tolerance`; nothing is changed),
        else True."""
        _, rot = self.robot.pose()
        yaw = math.atan2(rot[1, 0], rot[0, 0])
        c, s = math.cos(yaw), math.sin(yaw)
        wanted = np.array([c * float(vx) - s * float(vy), s * float(vx) + c * float(vy), float(vz)])
        vel, omega = self.robot.velocity()
        if float(np.linalg.norm(wanted - vel)) <= float(tolerance) and abs(float(vyaw) - omega[2]) <= float(tolerance):
            return False
        self.local_data.update(vx=float(vx), vy=float(vy), vz=float(vz), vyaw=float(vyaw),
                               tolerance=float(tolerance))
        return True


COMPONENT = RotorcraftVelocity
