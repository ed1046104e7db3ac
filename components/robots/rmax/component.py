from morsec.component import Robot, RobotProperties


class RMax(Robot):
    """Yamaha RMAX unmanned helicopter: 3.63 m long rotor tip to tail rotor tip (fuselage and boom
    2.75 m, main rotor 3.115 m), 94 kg, one rigid body as MORSE's. It floats by default (NoGravity):
    gravity is compensated and it holds its pose until an actuator moves it. Its origin is on the main
    rotor axis, 0.55 m above the bottom of the skids; floating, it is where `translate` puts it, as MORSE's
    (with gravity it falls from there, and put lower than 0.55 m it stands on its skids)."""

    short_descr = "Unmanned helicopter (rigid body, floats)"
    builder_name = "RMax"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.55

    class Properties(RobotProperties):
        NoGravity: bool = True


COMPONENT = RMax
