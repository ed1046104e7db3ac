"""MORSE's StabilizedQuadrotor: the linear model of a quadrotor whose attitude and height are already
stabilised, driven kinematically (as MORSE's, the robot does not fly by its own physics).

Per tick (dt = 1 / frequency):

* roll and pitch follow phi_c and theta_c through second-order filters (natural frequency 10 rad/s,
  damping 0.7, integrated as MORSE's Filt2); the yaw filter (same constants) is fed with its own output
  minus psi_c, so psi_c makes the robot turn at about -psi_c * 10 / 1.4 rad/s (psi_c = 0.1: -0.71 rad/s);
* the thrust acceleration along the robot's z axis is 10 + 9 (h_c - z) - 2 * 0.7 * 3 * v_z (m/s^2), z
  the robot's height; the velocity integrates that acceleration, turned into the world by the filtered
  attitude, minus 10 m/s^2 of gravity (theta_c = 0.1 accelerates forward at about 1 m/s^2);
* the robot is then given the filtered attitude (on top of its initial heading) and that velocity, and its
  weight is compensated by a force on its base (d.xfrc_applied): between two ticks it coasts, and contacts
  still stop it (the velocity integrated is the robot's measured one).
"""

from __future__ import annotations

import numpy as np

from morsec.component import Actuator, DataField, service
from morsec.kits.geometry import euler_to_quat, quat_to_matrix


class SecondOrder:
    """x'' = wn^2 (u - x) - 2 ksi wn x', integrated as MORSE's Filt2 does: each step the position takes the
    mean of the last two velocities, and the velocity the mean of the last acceleration and the one
    computed now (from the state before the step)."""

    def __init__(self, wn: float, ksi: float, x: float = 0.0):
        self.wn, self.ksi = wn, ksi
        self.x, self.v = x, 0.0
        self.last_v = self.last_a = 0.0

    def step(self, u: float, dt: float) -> float:
        a = self.wn ** 2 * (u - self.x) - 2.0 * self.ksi * self.wn * self.v
        self.x, self.last_v = self.x + (self.last_v + self.v) * dt / 2.0, self.v
        self.v, self.last_a = self.v + (self.last_a + a) * dt / 2.0, a
        return self.x


class StabilizedQuadrotor(Actuator):
    """Commands a stabilised quadrotor with pitch, roll, yaw and height set-points through MORSE's linear
    model (second-order filters on the attitude, PD on the height), moving the robot kinematically."""

    short_descr = "Linear model of a stabilised quadrotor: attitude and height set-points"
    builder_name = "StabilizedQuadrotor"
    frequency = 60.0

    data = (
        DataField("theta_c", 0.0, "float", "pitch command, rad: the acceleration along x (about 10 theta_c m/s^2)"),
        DataField("phi_c", 0.0, "float", "roll command, rad: the acceleration along -y"),
        DataField("psi_c", 0.0, "float", "yaw command: the robot turns at about -7.1 psi_c rad/s"),
        DataField("h_c", 0.0, "float", "height command, m (z of the robot's origin); starts at the robot's "
                  "initial height"),
    )

    def start(self):
        pos, rot = self.robot.pose()
        self._yaw0 = float(np.arctan2(rot[1, 0], rot[0, 0]))
        self.local_data["h_c"] = float(pos[2])
        self._reset_filters()

    def _reset_filters(self, keep_yaw: bool = False):
        psi = self.f_psi.x if keep_yaw else 0.0
        self.f_phi = SecondOrder(10.0, 0.7)
        self.f_theta = SecondOrder(10.0, 0.7)
        self.f_psi = SecondOrder(10.0, 0.7, psi)

    def default_action(self):
        if not self.robot.free:
            return
        d = self.local_data
        dt = 1.0 / self.frequency
        phi = self.f_phi.step(float(d["phi_c"]), dt)
        theta = self.f_theta.step(float(d["theta_c"]), dt)
        psi = self.f_psi.step(self.f_psi.x - float(d["psi_c"]), dt)
        rot = quat_to_matrix(euler_to_quat(phi, theta, psi + self._yaw0))

        pos, _ = self.robot.pose()
        vel, _ = self.robot.velocity()
        thrust = 10.0 + 9.0 * (float(d["h_c"]) - pos[2]) - 2.0 * 0.7 * 3.0 * vel[2]
        acc = rot @ np.array([0.0, 0.0, thrust]) - np.array([0.0, 0.0, 10.0])
        vel = vel + dt * acc

        self.robot.set_pose(pos, rot)  # stops the robot: its velocity is set right after
        qvel = self.sim.data.qvel
        qvel[self.robot.qvel_adr:self.robot.qvel_adr + 3] = vel
        gravity = self.sim.model.opt.gravity
        norm = float(np.linalg.norm(gravity))
        up = -gravity / norm if norm > 0 else np.zeros(3)
        self.robot.apply_wrench(self.name, up * self.robot.weight(), [0.0, 0.0, 0.0])

    @service
    def set_cons(self, phi: float, theta: float, psi: float, h: float) -> None:
        """Set the commands, as writing them on the stream would; `psi` is added to psi_c."""
        self.local_data["phi_c"] = float(phi)
        self.local_data["theta_c"] = float(theta)
        self.local_data["psi_c"] = float(self.local_data["psi_c"]) + float(psi)
        self.local_data["h_c"] = float(h)

    @service
    def stop(self) -> None:
        """Stop the robot where it is: velocity 0, roll, pitch and yaw commands 0, filters reset (the
        heading is kept, the height command too)."""
        self.local_data.update(phi_c=0.0, theta_c=0.0, psi_c=0.0)
        self._reset_filters(keep_yaw=True)
        if self.robot.free:
            self.sim.data.qvel[self.robot.qvel_adr:self.robot.qvel_adr + 6] = 0.0


COMPONENT = StabilizedQuadrotor
