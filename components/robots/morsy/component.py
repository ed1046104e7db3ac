from morsec.component import Robot, RobotProperties


class Morsy(Robot):
    """Morsy, MORSE's small default robot (the one `morse create` puts in a new simulation): a blue
    round body with a head, 0.40 m in diameter, 0.63 m tall, 8 kg, one rigid body on four ball casters.
    Its origin is on the floor, on the robot's vertical axis. Drive it with `motion_vw`; recolour it
    with the robot's `color` (MORSE's `set_color`, blue (0, 0, 0.8) by default)."""

    short_descr = "MORSE's small default robot (rigid body)"
    builder_name = "Morsy"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.0

    class Properties(RobotProperties):
        GroundRobot: bool = True


COMPONENT = Morsy
