from morsec.component import Robot, RobotProperties


class ATRV(Robot):
    """iRobot ATRV: a 4-wheel skid-steer outdoor robot, 0.9 x 0.55 m chassis, 20 kg as MORSE's. Its origin
    sits 0.10 m above the ground, as MORSE's (a Pose sensor at z = -0.10 reads the ground pose). Pushed then
    let go it coasts, slowed by Bullet's velocity damping, 2 % per second."""

    short_descr = "4-wheel skid-steer outdoor robot"
    builder_name = "ATRV"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.10
    # MORSE's own tests tell its mass and damping: 100 N speeds the ATRV up at 5 m/s^2 (20 kg) and, let go at
    # 10 m/s, it slows down by 0.2 m/s^2 (damping 0.02); its atrv.blend (`morsec import-blend atrv.blend --list`)
    # has 20 kg, Damping 0.0254 and Rotation Damping 0.18
    damping = (0.02, 0.1)

    class Properties(RobotProperties):
        GroundRobot: bool = True


COMPONENT = ATRV
