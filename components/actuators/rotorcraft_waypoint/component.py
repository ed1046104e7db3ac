"""MORSE's RotorcraftWaypoint: a PD cascade that flies a rotorcraft to a 3D point and a heading by
applying a thrust force along its z axis and torques to its base (d.xfrc_applied), the robot keeping its
weight (gravity on, not NoGravity).

Per tick, with e the position error and v the velocity (world frame, of the robot's origin):

* horizontal: a = HorizontalPgain * e_xy - HorizontalDgain * v_xy (rad per m, rad per m/s), turned into
  roll / pitch setpoints in the robot's heading frame (roll = sin(yaw) a_x - cos(yaw) a_y,
  pitch = cos(yaw) a_x + sin(yaw) a_y), each saturated at MaxBankAngle;
* vertical: thrust = weight / max(cos^2 MaxBankAngle, cos roll cos pitch) + VerticalPgain e_z -
  VerticalDgain v_z (N), at least 0;
* attitude: torque_i = I_i (Kp_i err_i + Kd_i d(err_i)/dt), Kp = (RollPitchPgain, RollPitchPgain,
  YawPgain), Kd = (RollPitchDgain, RollPitchDgain, YawDgain), I the robot's principal moments (its
  inertia tensor's diagonal, robot frame), scaled by thrust / weight;
* status "Arrived" when the robot's origin is within `tolerance` of the goal (a pending `goto`
  completes with SUCCESS "Arrived"), else "Transit".
"""

from __future__ import annotations

import logging
import math

import numpy as np
from pydantic import Field

from morsec.component import Actuator, DataField, RotorcraftProperties, async_service, service
from morsec.kits.geometry import matrix_to_euler, normalize_angle
from morsec.kits.markers import visual_marker

log = logging.getLogger("morsec.actuators.rotorcraft_waypoint")


class RotorcraftWaypoint(Actuator):
    """Flies a rotorcraft (quadrotor, helicopter) to a 3D waypoint and heading with a PD cascade on
    position, attitude and thrust, applied as a force and torques on the robot's base."""

    short_descr = "Fly a rotorcraft to a 3D point and heading (forces and torques)"
    builder_name = "RotorcraftWaypoint"
    frequency = 60.0

    class Properties(RotorcraftProperties):
        HorizontalPgain: float = Field(math.radians(6), description="horizontal position P gain, rad of tilt "
                                       "per m")
        HorizontalDgain: float = Field(math.radians(8), description="horizontal velocity D gain, rad per m/s")
        VerticalPgain: float = Field(8.0, description="vertical position P gain, N per m")
        VerticalDgain: float = Field(8.0, description="vertical velocity D gain, N per m/s")
        MaxBankAngle: float = Field(math.radians(30), gt=0, lt=math.pi / 2,
                                    description="largest roll or pitch setpoint, rad")
        RemainAtDestination: bool = Field(True, description="keep flying to the goal once reached (false: "
                                          "release the controls there, the robot falls)")
        Target: str = Field("wp_target", description="name of a scene object moved to the goal (a visual "
                            "marker); ignored when there is none")

    data = (
        DataField("x", 0.0, "float", "x of the goal, world frame, m (default: the robot's initial position)"),
        DataField("y", 0.0, "float", "y of the goal, world frame, m"),
        DataField("z", 0.0, "float", "z of the goal, world frame, m"),
        DataField("yaw", 0.0, "float", "heading at the goal, rad (default: the initial heading)"),
        DataField("tolerance", 0.2, "float", "distance, m, under which the goal is reached"),
    )

    def start(self):
        pos, rot = self.robot.pose()
        self.local_data.update(x=float(pos[0]), y=float(pos[1]), z=float(pos[2]),
                               yaw=math.atan2(rot[1, 0], rot[0, 0]))
        self.status = "Arrived"
        self._arrived_at = None
        self._prev_err = None
        self._target = None
        self._inertia = np.diag(self.robot.inertia()).copy()
        self._weight = self.robot.weight()

    def _goal(self) -> np.ndarray:
        d = self.local_data
        return np.array([float(d["x"]), float(d["y"]), float(d["z"])])

    def default_action(self):
        p, d = self.properties, self.local_data
        goal = self._goal()
        self._place_target(goal, float(d["yaw"]))
        pos, rot = self.robot.pose()
        key = (*goal, float(d["yaw"]), float(d["tolerance"]))
        if np.linalg.norm(goal - pos) <= float(d["tolerance"]):
            self.status = "Arrived"
            self._arrived_at = key
            self.completed("SUCCESS", "Arrived")
        else:
            self.status = "Transit"
            if key != self._arrived_at:
                self._arrived_at = None
        if not p.RemainAtDestination and self._arrived_at == key:
            self.robot.apply_wrench(self.name, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
            self._prev_err = None
            return

        vel, _ = self.robot.velocity()
        roll, pitch, yaw = matrix_to_euler(rot)
        err = goal - pos
        ax = p.HorizontalPgain * err[0] - p.HorizontalDgain * vel[0]
        ay = p.HorizontalPgain * err[1] - p.HorizontalDgain * vel[1]
        bank = p.MaxBankAngle
        roll_sp = _clip(math.sin(yaw) * ax - math.cos(yaw) * ay, bank)
        pitch_sp = _clip(math.cos(yaw) * ax + math.sin(yaw) * ay, bank)
        yaw_sp = normalize_angle(float(d["yaw"]))

        weight = self._weight
        compensation = max(math.cos(bank) ** 2, math.cos(roll) * math.cos(pitch))
        thrust = weight / compensation + p.VerticalPgain * err[2] - p.VerticalDgain * vel[2]
        if weight > 0:
            thrust = max(0.0, thrust)

        att_err = np.array([normalize_angle(roll_sp - roll), normalize_angle(pitch_sp - pitch),
                            normalize_angle(yaw_sp - yaw)])
        rate = (att_err - self._prev_err) * self.frequency if self._prev_err is not None else np.zeros(3)
        self._prev_err = att_err
        kp = np.array([p.RollPitchPgain, p.RollPitchPgain, p.YawPgain])
        kd = np.array([p.RollPitchDgain, p.RollPitchDgain, p.YawDgain])
        torque = self._inertia * (kp * att_err + kd * rate) * (thrust / weight if weight > 0 else 1.0)
        self.robot.apply_wrench(self.name, rot @ np.array([0.0, 0.0, thrust]), rot @ torque)

    def _place_target(self, goal: np.ndarray, yaw: float):
        name = self.properties.Target
        if not name:
            return
        if self._target is None:
            self._target = visual_marker(self.sim, name)  # MORSE's marker had NO_COLLISION: not in the way
            if self._target is None:
                return
        c, s = math.cos(yaw), math.sin(yaw)
        self.sim.place_body(self._target, goal, np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]))

    # ------------------------------------------------------------------ services
    @service
    def setdest(self, x: float, y: float, z: float, yaw: float, tolerance: float = 0.2) -> bool:
        """Set a new goal and return at once: False if the robot is already within `tolerance` of it (the
        goal is then not changed), else True."""
        pos, _ = self.robot.pose()
        if np.linalg.norm(np.array([float(x), float(y), float(z)]) - pos) <= float(tolerance):
            return False
        self.local_data.update(x=float(x), y=float(y), z=float(z), yaw=float(yaw), tolerance=float(tolerance))
        return True

    @async_service(interruptible=True)
    def goto(self, x: float, y: float, z: float, yaw: float, tolerance: float = 0.2) -> None:
        """Fly to (x, y, z) with heading `yaw`; answers SUCCESS "Arrived" when within `tolerance`.
        Interruptible: a new `goto` preempts it, `cancel` aborts it (PREEMPTED) and the robot hovers where
        it is."""
        self.local_data.update(x=float(x), y=float(y), z=float(z), yaw=float(yaw), tolerance=float(tolerance))

    def interrupt(self) -> None:
        pos, rot = self.robot.pose()
        self.local_data.update(x=float(pos[0]), y=float(pos[1]), z=float(pos[2]),
                               yaw=math.atan2(rot[1, 0], rot[0, 0]))

    @service
    def get_status(self) -> str:
        """"Arrived" or "Transit"."""
        return self.status


def _clip(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))


COMPONENT = RotorcraftWaypoint
