from morsec.component import Robot, RobotProperties


class Submarine(Robot):
    """A small submersible: a 2.5 m long, 0.5 m diameter yellow hull with a sail and tail fins, 470 kg,
    one rigid body as MORSE's. It floats by default (NoGravity): gravity is compensated and it holds its
    pose until an actuator moves it. Its origin is on the hull's axis at mid-length, 0.25 m above the
    bottom of the hull; floating, it is where `translate` puts it (with gravity it falls from there, and
    put lower than 0.25 m it lies on the ground)."""

    short_descr = "Small submersible (rigid body, floats)"
    builder_name = "Submarine"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.25

    class Properties(RobotProperties):
        NoGravity: bool = True


COMPONENT = Submarine
