"""MORSE's RotorcraftAttitude: roll, pitch, yaw (or yaw rate) and collective thrust commands, as a pilot's
radio or a higher-level controller gives them, turned into a thrust force along the robot's z axis and PD
attitude torques on its base (d.xfrc_applied). The robot keeps its weight (gravity on).

Angles are in the aerospace North-East-Down convention, as MORSE's: roll positive right side down (the same
as the robot frame's), pitch positive nose up and yaw positive clockwise seen from above (both the opposite
of the robot frame's x forward, y left, z up). With UseAngleAgainstNorth, yaw is measured from true north
(the environment's `angle_against_north`) instead of from the scene's x axis.

Per tick, while thrust > 0: yaw_sp += yaw / frequency with YawRateControl (else yaw_sp = yaw);
err = (roll - roll_now, pitch - pitch_now, yaw_sp - yaw_now) in NED; torque_i = I_i (Kp_i err_i + Kd_i
d(err_i)/dt) with Kp = (RollPitchPgain, RollPitchPgain, YawPgain), Kd = (RollPitchDgain, RollPitchDgain,
YawDgain), I the robot's principal moments, turned into the robot frame and scaled by thrust; force =
ThrustFactor * thrust (LinearThrust) or ThrustFactor * thrust^2, N. Thrust 0 releases the robot.
"""

from __future__ import annotations

import math

import numpy as np
from pydantic import Field

from morsec.component import Actuator, DataField, RotorcraftProperties
from morsec.kits.geometry import matrix_to_euler, normalize_angle


class RotorcraftAttitude(Actuator):
    """Attitude and thrust control of a rotorcraft: a PD controller on roll, pitch and yaw (or yaw rate)
    applying torques, and the collective thrust applied as a force along the robot's z axis."""

    short_descr = "Fly a rotorcraft from attitude and thrust commands (forces and torques)"
    builder_name = "RotorcraftAttitude"
    frequency = 60.0

    class Properties(RotorcraftProperties):
        RollPitchPgain: float = 100.0
        RollPitchDgain: float = 20.0
        YawPgain: float = 16.0
        YawDgain: float = 4.0
        ThrustFactor: float = Field(40.0, description="thrust force at full thrust (thrust = 1), N")
        LinearThrust: bool = Field(True, description="force = ThrustFactor * thrust (false: ThrustFactor * "
                                   "thrust^2)")
        YawRateControl: bool = Field(True, description="the `yaw` field is a yaw rate, integrated into the yaw "
                                     "setpoint (false: it is the yaw setpoint)")
        UseAngleAgainstNorth: bool = Field(False, description="yaw against true north (needs the environment's "
                                           "longitude, latitude, altitude and angle_against_north), else "
                                           "against the scene's x axis")

    data = (
        DataField("roll", 0.0, "float", "roll angle, rad (NED: positive right side down)"),
        DataField("pitch", 0.0, "float", "pitch angle, rad (NED: positive nose up)"),
        DataField("yaw", 0.0, "float", "yaw rate, rad/s, with YawRateControl, else yaw angle, rad (NED: "
                  "positive clockwise seen from above)"),
        DataField("thrust", 0.0, "float", "collective thrust: 0 .. 1 (= 0 .. 100 %)"),
    )

    def start(self):
        self._inertia = np.diag(self.robot.inertia()).copy()
        _, rot = self.robot.pose()
        self._yaw_sp = self._ned_angles(rot)[2]
        self._prev_err = None

    def _ned_angles(self, rot: np.ndarray) -> tuple[float, float, float]:
        roll, pitch, yaw = matrix_to_euler(rot)
        if self.properties.UseAngleAgainstNorth:
            east, north, _ = self.sim.geo.to_enu(rot[:, 0])
            heading = math.atan2(east, north)  # clockwise from true north
        else:
            heading = -yaw
        return roll, -pitch, normalize_angle(heading)

    def default_action(self):
        p, d = self.properties, self.local_data
        thrust = float(d["thrust"])
        if thrust <= 0:
            self._prev_err = None
            self.robot.apply_wrench(self.name, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
            return
        if p.YawRateControl:
            self._yaw_sp = normalize_angle(self._yaw_sp + float(d["yaw"]) / self.frequency)
        else:
            self._yaw_sp = normalize_angle(float(d["yaw"]))
        _, rot = self.robot.pose()
        roll, pitch, yaw = self._ned_angles(rot)
        err = np.array([float(d["roll"]) - roll, float(d["pitch"]) - pitch, normalize_angle(self._yaw_sp - yaw)])
        rate = (err - self._prev_err) * self.frequency if self._prev_err is not None else np.zeros(3)
        self._prev_err = err
        kp = np.array([p.RollPitchPgain, p.RollPitchPgain, p.YawPgain])
        kd = np.array([p.RollPitchDgain, p.RollPitchDgain, p.YawDgain])
        ned = self._inertia * (kp * err + kd * rate)
        torque = np.array([ned[0], -ned[1], -ned[2]]) * thrust  # NED -> robot frame (x forward, y left, z up)
        force = p.ThrustFactor * (thrust if p.LinearThrust else thrust * thrust)
        self.robot.apply_wrench(self.name, rot @ np.array([0.0, 0.0, force]), rot @ torque)


COMPONENT = RotorcraftAttitude
