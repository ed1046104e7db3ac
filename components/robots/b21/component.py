from morsec.component import Robot, RobotProperties


class B21(Robot):
    """RWI B21r: a round indoor research robot, 0.525 m in diameter and 1.20 m tall, 122 kg, one rigid
    body as MORSE's, on four ball casters standing for its synchro-drive wheels. Its origin is on the
    floor, on the robot's vertical axis. Drive it with `motion_vw` (kinematic body velocity, as MORSE)."""

    short_descr = "Round indoor research robot (rigid body)"
    builder_name = "B21"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.0

    class Properties(RobotProperties):
        GroundRobot: bool = True


COMPONENT = B21
