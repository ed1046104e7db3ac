from morsec.component import Actuator, ControlTypeProperties, DataField


class MotionXYW(Actuator):
    """Holonomic body velocity: forward speed x, lateral speed y (to the left) and yaw rate w in the
    robot's frame, re-applied every tick with the last command (MORSE's MotionXYW). Kinematic, as
    MORSE: velocity servos on the robot's base hold the three velocities inside every physics step;
    ground robots keep the vertical velocity, roll and pitch rates that gravity and contacts give them."""

    short_descr = "Forward, lateral and yaw speeds of the robot"
    builder_name = "MotionXYW"
    frequency = 60.0
    base_servo = True

    class Properties(ControlTypeProperties):
        pass

    data = (
        DataField("x", 0.0, "float", "movement forward (x of the robot), m/s"),
        DataField("y", 0.0, "float", "movement sideways (y of the robot, to the left), m/s"),
        DataField("w", 0.0, "float", "angular velocity about z, rad/s"),
    )

    def default_action(self):
        d = self.local_data
        self.robot.apply_speed(self.properties.ControlType, [float(d["x"]), float(d["y"]), 0.0],
                               [0.0, 0.0, float(d["w"])], self.frequency)


COMPONENT = MotionXYW
