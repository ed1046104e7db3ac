from morsec.component import Robot


class FakeRobot(Robot):
    """An invisible holder for sensors and actuators that are on no robot (MORSE's FakeRobot, an Empty):
    a fixed camera watching the scene, a pose reference, a clock. It has no body to see or hit, is
    fixed in the world at its `translate`/`rotate` and is not moved by physics."""

    short_descr = "Invisible, fixed holder for components that are on no robot"
    builder_name = "FakeRobot"
    xacro = "robot.urdf.xacro"
    static = True
    collision = False


COMPONENT = FakeRobot
