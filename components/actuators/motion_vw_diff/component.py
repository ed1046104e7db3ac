import mujoco

from morsec.component import Actuator, ComponentProperties, DataField, service

SLIP_FRACTION = 0.5  # the most the wheels are asked beyond the command, as a part of it (plus 0.05)


class MotionVWDiff(Actuator):
    """Linear and angular velocity (v, w) turned into wheel speeds of a differential-drive robot
    (MORSE's PhysicsDifferentialRobot: Pioneer3DX, SegwayRMP400): in MORSE the left wheels turn at
    (v - e w) / R and the right wheels at (v + e w) / R, e half the distance between the wheels (or half
    the robot's `FixTurningSpeed` when not 0), R the wheel radius. The robot goes at v and turns at w, or,
    for a skid-steering robot that declares MORSE's effective track B (`morse_skid_track`), at the
    (v_right - v_left) / B = 2 e w / B those wheel speeds turned MORSE's (SegwayRMP400: 0.97 w). The wheels
    are driven by MuJoCo velocity servos inside the physics sub-steps: the robot moves through wheel-ground
    friction, as a real one; a command held unchanged is corrected at each tick by what the wheels' slip
    made the robot miss.

    The robot class declares `wheel_radius`, `wheel_track` (m), `left_wheel_joints` and
    `right_wheel_joints` (URDF joint names), and optionally `wheel_kv` (servo gain, N m s/rad),
    `wheel_max_torque` (N m), `morse_skid_track` and `skid_track` (m: the model's own effective track on
    MuJoCo, used for the wheel speeds instead of 2 e)."""

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
        # (actuator id, side, radius, half track), then the effective tracks of skid steering (0: none)
        self._wheels: list[tuple[int, float, float, float]] = []
        self._skid_track = self._morse_skid_track = 0.0
        for i in range(m.nu):
            name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_ACTUATOR, i) or ""
            if name.startswith(prefix) and m.nuser_actuator >= 5:
                side, radius, half_track, skid, morse_skid = (float(x) for x in m.actuator_user[i][:5])
                self._wheels.append((i, side, radius, half_track))
                self._skid_track, self._morse_skid_track = skid, morse_skid
        if not self._wheels:
            raise RuntimeError(f"{self.name}: no wheel servos in scene.xml (is the robot a differential one?)")

    def default_action(self):
        v, w = float(self.local_data["v"]), float(self.local_data["w"])
        fix = float(getattr(self.robot.properties, "FixTurningSpeed", 0.0) or 0.0)
        track = fix or 2.0 * self._wheels[0][3]  # MORSE's wheel speeds: (v -+ track / 2 w) / R
        # what MORSE's robot made of those wheel speeds: a skid-steering one turned at (v_r - v_l) / B
        turn = w * track / self._morse_skid_track if self._morse_skid_track else w
        # the wheels slip (skid-steering most): what the robot missed of a held command over the last tick is
        # added to what the wheels are asked, within half the command
        v, _, turn = self.robot.follow(self.name, [v, 0.0, turn], fraction=SLIP_FRACTION, settle=10)
        drive = self._skid_track or track  # the track that turns this model on MuJoCo
        ctrl = self.sim.data.ctrl
        for i, side, radius, _ in self._wheels:
            ctrl[i] = (v - side * drive / 2.0 * turn) / radius

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
