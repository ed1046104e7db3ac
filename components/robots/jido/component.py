from morsec.component import Robot, RobotProperties


class Jido(Robot):
    """LAAS's Jido mobile manipulator: a Neobotix MP-L655 base (0.76 x 0.56 m) with a KUKA LWR arm at its
    front and a 1.4 m mast with the pan-tilt head at its rear, 150 kg, one rigid body as MORSE's robot body
    (the arm and the head are drawn; append `kuka_lwr` or `ptu` components to move some). Its origin is on
    the floor, under the centre of the base."""

    short_descr = "Mobile manipulator: Neobotix base, KUKA LWR arm, mast (rigid body)"
    builder_name = "Jido"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.0

    class Properties(RobotProperties):
        GroundRobot: bool = True


COMPONENT = Jido
