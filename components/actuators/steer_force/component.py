import mujoco
import numpy as np

from morsec.component import Actuator, ComponentProperties, DataField

ENGINE_SHARE = 0.4  # MORSE: each of the 4 wheels gets force * 0.4
BRAKE_SHARE = (0.1, 0.1, 1.3, 1.3)  # MORSE: brake * 0.1 on the front wheels, * 1.3 on the rear ones
BULLET_RATE = 60.0  # MORSE's Bullet vehicle takes the brake as an impulse per 1/60 s physics step


class SteerForce(Actuator):
    """Steering angle, engine force and brake of a car-like robot (MORSE's vehicle-wrapper Hummer), as
    MORSE: both front wheels are steered to `steer` (rad, positive to the left, clamped to the hinges'
    range) by position servos; each of the four wheels is driven with an engine force of `force` x 0.4
    (N at the tyre; negative forward, as MORSE's vehicle); `brake` brakes the front wheels with
    brake x 0.1 and the rear ones with brake x 1.3 (MORSE's Bullet impulse per 1/60 s step, i.e. a
    friction force of brake x 0.1 x 60 N at each front tyre and brake x 1.3 x 60 N at each rear one).

    The robot class declares `steering_joints`, `drive_wheel_joints` (front left, front right, rear
    left, rear right: URDF joint names), `wheel_radius` (m) and optionally `steering_kp` / `steering_kv`."""

    short_descr = "Steering angle, engine force and brake of a car"
    builder_name = "SteerForce"
    frequency = 60.0

    robot_requires = ("steering_joints", "drive_wheel_joints", "wheel_radius")

    class Properties(ComponentProperties):
        pass

    data = (
        DataField("steer", 0.0, "float", "steering angle of the front wheels, rad (positive: to the left)"),
        DataField("force", 0.0, "float", "engine force, N at the tyre, x 0.4 on each wheel (negative: forward)"),
        DataField("brake", 0.0, "float", "braking, x 0.1 on the front wheels, x 1.3 on the rear ones"),
    )

    def start(self):
        m = self.sim.model
        steer_prefix, drive_prefix = self.name + "/steer/", self.name + "/drive/"
        self._steer, self._drive = [], []
        for i in range(m.nu):
            name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_ACTUATOR, i) or ""
            joint = int(m.actuator_trnid[i][0])
            if name.startswith(steer_prefix):
                lo, hi = m.jnt_range[joint] if m.jnt_limited[joint] else (-np.inf, np.inf)
                self._steer.append((i, float(lo), float(hi)))
            elif name.startswith(drive_prefix):
                dof = int(m.jnt_dofadr[joint])
                radius = abs(float(m.actuator_gear[i][0]))
                self._drive.append((i, dof, radius, float(m.dof_frictionloss[dof])))
        if not self._steer or not self._drive:
            raise RuntimeError(f"{self.name}: no steering servos or wheel motors in scene.xml (is the robot a car?)")

    def default_action(self):
        m, d = self.sim.model, self.sim.data
        steer = float(self.local_data["steer"])
        force = float(self.local_data["force"])
        brake = max(0.0, float(self.local_data["brake"]))
        for i, lo, hi in self._steer:
            d.ctrl[i] = min(hi, max(lo, steer))
        for k, (i, dof, radius, friction) in enumerate(self._drive):
            d.ctrl[i] = force * ENGINE_SHARE
            share = BRAKE_SHARE[k] if k < len(BRAKE_SHARE) else BRAKE_SHARE[-1]
            # a brake is dry friction on the wheel's joint: MuJoCo's frictionloss, a torque in N m
            m.dof_frictionloss[dof] = friction + brake * share * BULLET_RATE * radius


COMPONENT = SteerForce
