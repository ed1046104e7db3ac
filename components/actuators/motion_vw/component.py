from morsec.component import Actuator, ControlTypeProperties, DataField, service


class MotionVW(Actuator):
    """Linear and angular velocity in the robot's frame (v forward, w about z), re-applied every tick.
    As MORSE's, it sets the robot's body velocity rather than wheel torques: stiff MuJoCo velocity servos
    on the robot's base hold forward speed v, lateral speed 0 and yaw rate w inside every physics step,
    while vertical motion, roll and pitch stay free (gravity and contacts act: ground robots stay on the
    ground, go over slopes and are stopped by walls). ControlType 'Position' displaces the robot by
    v/frequency and rotates it by w/frequency each tick instead, kinematically."""

    short_descr = "Forward speed and yaw rate of the robot"
    builder_name = "MotionVW"
    frequency = 60.0
    base_servo = True

    class Properties(ControlTypeProperties):
        pass

    data = (
        DataField("v", 0.0, "float", "forward velocity, robot frame, m/s"),
        DataField("w", 0.0, "float", "angular velocity about z, rad/s"),
    )

    def default_action(self):
        v, w = float(self.local_data["v"]), float(self.local_data["w"])
        self.robot.apply_planar_speed(self.properties.ControlType, v, w, self.frequency)

    @service
    def set_speed(self, v: float, w: float):
        """Set v (m/s) and w (rad/s)."""
        self.local_data["v"] = float(v)
        self.local_data["w"] = float(w)

    @service
    def stop(self):
        """Set both speeds to 0."""
        self.local_data["v"] = 0.0
        self.local_data["w"] = 0.0


COMPONENT = MotionVW
