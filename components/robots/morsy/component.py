from morsec.component import Robot, RobotProperties


class Morsy(Robot):
    """Morsy, MORSE's small default robot (the one `morse create` puts in a new simulation): a blue
    round body with a head, 0.40 m in diameter, 0.63 m tall, 15 kg, one rigid body on four ball casters.
    Its origin is on the floor, on the robot's vertical axis. Drive it with `motion_vw`; recolour it
    with the robot's `color` (MORSE's `set_color`, blue (0, 0, 0.8) by default). Its body is heavily
    damped, as MORSE's: pushed then let go, it loses half its speed in a second."""

    short_descr = "MORSE's small default robot (rigid body)"
    builder_name = "Morsy"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.0
    # MORSE's morsy.blend: the physics object (an empty holding the collision box) weighs 15 kg, Damping
    # 0.493, Rotation Damping 0.658
    damping = (0.493, 0.658)

    class Properties(RobotProperties):
        GroundRobot: bool = True


COMPONENT = Morsy
