import mujoco

from morsec.component import Actuator, ComponentProperties, DataField, service

SLIP_FRACTION = 0.5  # the most the wheels are asked beyond the command, as a part of it (plus 0.05)


class MotionVWDiff(Actuator):
    """Linear and angular velocity (v, w) turned into wheel speeds of a differential-drive robot
    (MORSE's PhysicsDifferentialRobot: Pioneer3DX, SegwayRMP400): the left wheels turn at
    (v - e w) / R and the right wheels at (v + e w) / R, e half the distance between the wheels
    (or half the robot's `FixTurningSpeed` when not 0), R the wheel radius. The wheels are driven by
    MuJoCo velocity servos inside the physics sub-steps: the robot moves through wheel-ground friction,
    as a real one; a (v, w) held unchanged is corrected at each tick by what the wheels' slip made the
    robot miss, so that it goes at v and turns at w (as MORSE's, whose FixTurningSpeed was tuned so).

    The robot class declares `wheel_radius`, `wheel_track` (m), `left_wheel_joints` and
    `right_wheel_joints` (URDF joint names), and optionally `wheel_kv` (servo gain, N m s/rad) and
    `wheel_max_torque` (N m)."""

    short_descr = "Forward speed and yaw rate applied through the wheels of a differential robot"
    builder_name = "MotionVWDiff"
    frequency = 60.0
    robot_requires = ("wheel_radius", "wheel_track", "left_wheel_joints", "right_wheel_joints")

    class Properties(ComponentProperties):
        pass

    data = (
        DataField("v", 0.0, "float", "linear velocity in x direction (forward movement), m/s"),
        DataField("w", 0.0, "float", "angular velocity about z, rad/s"),
    )

    def start(self):
        m = self.sim.model
        prefix = self.name + "/"
        self._wheels = []  # (actuator id, side, radius, half track)
        for i in range(m.nu):
            name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_ACTUATOR, i) or ""
            if name.startswith(prefix) and m.nuser_actuator >= 3:
                side, radius, half_track = (float(x) for x in m.actuator_user[i][:3])
                self._wheels.append((i, side, radius, half_track))
        if not self._wheels:
            raise RuntimeError(f"{self.name}: no wheel servos in scene.xml (is the robot a differential one?)")

    def default_action(self):
        v, w = float(self.local_data["v"]), float(self.local_data["w"])
        # the wheels slip (skid-steering most): what the robot missed of a held (v, w) over the last tick
        # is added to what the wheels are asked, within half the command (MORSE's FixTurningSpeed, tuned on
        # Bullet, made its robots turn at about w; this makes them turn at w)
        v, _, w = self.robot.follow(self.name, [v, 0.0, w], fraction=SLIP_FRACTION, settle=10)
        fix = float(getattr(self.robot.properties, "FixTurningSpeed", 0.0) or 0.0)
        ctrl = self.sim.data.ctrl
        for i, side, radius, half_track in self._wheels:
            e = fix / 2 if fix else half_track
            ctrl[i] = (v - side * e * w) / radius

    @service
    def set_speed(self, v: float, w: float):
        """Set v (m/s) and w (rad/s)."""
        self.local_data["v"] = float(v)
        self.local_data["w"] = float(w)

    @service
    def stop(self):
        """Stop the robot: set (v, w) to (0, 0)."""
        self.local_data["v"] = 0.0
        self.local_data["w"] = 0.0


COMPONENT = MotionVWDiff
