from morsec.component import Robot, RobotProperties


class ATRV(Robot):
    """iRobot ATRV: a 4-wheel skid-steer outdoor robot, 0.9 x 0.55 m chassis, 70 kg. Its origin sits
    0.10 m above the ground, as MORSE's (a Pose sensor at z = -0.10 reads the ground pose)."""

    short_descr = "4-wheel skid-steer outdoor robot"
    builder_name = "ATRV"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.10

    class Properties(RobotProperties):
        GroundRobot: bool = True


COMPONENT = ATRV
